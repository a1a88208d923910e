/* nodl studio's page: draws the state the server holds and sends the user's edits to it.
 *
 * Every edit is a request to the studio's API; its answer is the whole new state (nodes,
 * ports, edges, findings), which is drawn again.  Text from definitions and launch files is
 * only ever put in the page with textContent (never innerHTML) and in the canvas as labels.
 */
(function () {
  'use strict';

  var TOKEN = document.querySelector('meta[name="nodl-token"]').content;
  var PORT_W = 150;      // half the distance between the two columns of ports
  var PORT_H = 18;       // the distance between two rows of ports
  var OFFERS = {publisher: true, service_server: true, action_server: true};
  var SHORT = {publisher: 'pub', subscription: 'sub', service_server: 'srv', service_client: 'cli',
               action_server: 'act srv', action_client: 'act cli'};
  var studio = window.studio = {state: null, palette: [], cy: null, eh: null, selected: null,
                                compatible: null, ready: false, version: 0, busy: 0};

  function $(id) { return document.getElementById(id); }
  function el(tag, cls, text) {
    var e = document.createElement(tag);
    if (cls) { e.className = cls; }
    if (text !== undefined && text !== null) { e.textContent = String(text); }
    return e;
  }
  // ``text`` into ``e`` with a line-break opportunity after each '_' and '/' (identifiers break
  // between their words, not inside one)
  function breakable(e, text) {
    String(text).split(/(?<=[_/])/).forEach(function (part, i) {
      if (i) { e.appendChild(document.createElement('wbr')); }
      e.appendChild(document.createTextNode(part));
    });
    return e;
  }
  function clear(node) { while (node.firstChild) { node.removeChild(node.firstChild); } }
  function status(text) { $('status').textContent = text || ''; $('status').title = text || ''; }

  function call(path, data) {
    studio.busy += 1;
    return fetch('/api/' + path, {
      method: 'POST', headers: {'X-Nodl-Token': TOKEN, 'Content-Type': 'application/json'},
      body: JSON.stringify(data || {})
    }).then(function (response) {
      return response.json().then(function (answer) {
        studio.busy -= 1;
        if (answer.state) { show(answer.state); }
        if (!response.ok || answer.ok === false) {
          var why = answer.error || (answer.diagnostics || []).map(function (d) { return d.message; }).join('; ');
          status(why || ('the studio refused: ' + response.status));
        }
        return answer;
      });
    }, function (err) { studio.busy -= 1; status('the studio does not answer: ' + err); throw err; });
  }

  // -- the canvas ---------------------------------------------------------------------------

  function portId(node, port) { return node.id + '|' + port.kind + '|' + port.name; }

  function namespaceChain(ns) {
    var parts = (ns || '/').split('/').filter(Boolean), out = [], path = '';
    parts.forEach(function (p) { path += '/' + p; out.push(path); });
    return out;
  }

  function nodeHeight(n) { return Math.max(1, rowsOf(n)) * PORT_H + 56; }
  function boxAt(n, p) {
    var h = nodeHeight(n) / 2;
    return {x1: p.x - PORT_W - 20, x2: p.x + PORT_W + 20, y1: p.y - h, y2: p.y + h};
  }
  function union(a, b) {
    return {x1: Math.min(a.x1, b.x1), x2: Math.max(a.x2, b.x2), y1: Math.min(a.y1, b.y1), y2: Math.max(a.y2, b.y2)};
  }
  function meets(a, b, pad) {
    return a.x1 - pad < b.x2 && b.x1 - pad < a.x2 && a.y1 - pad < b.y2 && b.y1 - pad < a.y2;
  }

  // A node added to a namespace drawn already goes with its namespace: under a column of its
  // nodes, or in a new column at their right, wherever the namespace's box then meets no other
  // namespace's (null: nowhere; it is placed as a new block).
  function besideItsNamespace(n, nodes, placed, cellW) {
    var ns = n.namespace || '/', mine = null, others = [], columns = {};
    nodes.forEach(function (m) {
      var p = placed[m.id];
      if (!p || m.id === n.id) { return; }
      var b = boxAt(m, p);
      if ((m.namespace || '/') === ns) {
        mine = mine ? union(mine, b) : b;
        if (!(p.x in columns) || b.y2 > columns[p.x]) { columns[p.x] = b.y2; }
      } else {
        others.push(b);
      }
    });
    if (!mine) { return null; }
    var h = nodeHeight(n), right = -Infinity;
    var candidates = Object.keys(columns).map(function (x) {
      right = Math.max(right, Number(x));
      return {x: Number(x), y: columns[x] + 16 + h / 2};
    }).sort(function (a, b) { return a.y - b.y; });
    candidates.push({x: right + cellW, y: mine.y1 + h / 2});
    return candidates.filter(function (c) {
      var grown = union(mine, boxAt(n, c));
      return !others.some(function (o) { return meets(grown, o, 60); });
    })[0] || null;
  }

  function defaultPositions(nodes, known) {
    // Nodes without a kept position: with their namespace's when it is drawn already (see
    // besideItsNamespace); the others each namespace's as a block of columns about as wide
    // as tall, the blocks in rows (as many per row as rows), right of the placed nodes.
    var out = {}, groups = {}, order = [], x0 = 0, cellW = 2 * PORT_W + 90, gap = 150;
    var placed = Object.assign({}, known), drawn = {};
    nodes.forEach(function (n) { if (placed[n.id]) { drawn[n.namespace || '/'] = true; } });
    nodes.forEach(function (n) {
      if (placed[n.id] || !drawn[n.namespace || '/']) { return; }  // (a first drawing: none)
      var p = besideItsNamespace(n, nodes, placed, cellW);
      if (p) { out[n.id] = placed[n.id] = p; }
    });
    Object.keys(placed).forEach(function (k) { x0 = Math.max(x0, placed[k].x + cellW + gap); });
    nodes.forEach(function (n) {
      if (placed[n.id]) { return; }
      var ns = n.namespace || '/';
      if (!groups[ns]) { groups[ns] = []; order.push(ns); }
      groups[ns].push(n);
    });
    var perRow = Math.max(1, Math.ceil(Math.sqrt(order.length)));
    var x = x0, y = 0, rowHeight = 0;
    order.forEach(function (ns, g) {
      var members = groups[ns];
      var heights = members.map(function (n) { return Math.max(1, rowsOf(n)) * PORT_H + 56; });
      var total = heights.reduce(function (a, b) { return a + b + 16; }, 0);
      var cols = Math.max(1, Math.round(Math.sqrt(total / cellW)));
      var limit = total / cols, cx = 0, cy = 0, width = cellW, height = 0;
      members.forEach(function (n, i) {
        if (cy > 0 && cy + heights[i] > limit + 40) { cy = 0; cx += cellW; width += cellW; }
        out[n.id] = {x: x + cx, y: y + cy + heights[i] / 2};
        cy += heights[i] + 16;
        height = Math.max(height, cy);
      });
      rowHeight = Math.max(rowHeight, height);
      x += width + gap;
      if ((g + 1) % perRow === 0) { x = x0; y += rowHeight + gap; rowHeight = 0; }
    });
    return out;
  }

  function rowsOf(node) {
    var ins = 0, outs = 0;
    node.ports.forEach(function (p) { if (OFFERS[p.kind]) { outs += 1; } else { ins += 1; } });
    return Math.max(ins, outs);
  }

  function severityOf(findings) {
    var rank = {error: 3, warning: 2, info: 1}, best = '';
    findings.forEach(function (f) { if (!best || rank[f.severity] > rank[best]) { best = f.severity; } });
    return best;
  }

  function findingsIndex(state) {
    var byFqn = {}, byNode = {}, byPort = {}, byEdge = {};
    state.nodes.forEach(function (n) { (byFqn[n.fqn] = byFqn[n.fqn] || []).push(n); });
    state.findings.forEach(function (f) {
      (f.nodes || []).forEach(function (fqn) {
        (byFqn[fqn] || []).forEach(function (n) {
          (byNode[n.id] = byNode[n.id] || []).push(f);
          if (f.endpoint) {
            n.ports.forEach(function (p) {
              if (p.final === f.endpoint) { var id = portId(n, p); (byPort[id] = byPort[id] || []).push(f); }
            });
          }
        });
      });
    });
    state.edges.forEach(function (e) {
      state.findings.forEach(function (f) {
        if (f.endpoint && f.endpoint === e.name) { (byEdge[e.id] = byEdge[e.id] || []).push(f); }
      });
    });
    return {byNode: byNode, byPort: byPort, byEdge: byEdge};
  }

  function elements(state) {
    var out = [], groups = {}, index = findingsIndex(state);
    var positions = Object.assign({}, state.positions || {});
    if (studio.cy) {  // where the nodes drawn already are (the user may have moved them)
      studio.cy.nodes('.instance').forEach(function (n) { positions[n.id()] = anchorOf(n); });
    }
    Object.assign(positions, defaultPositions(state.nodes, positions));
    studio.positions = positions;
    state.nodes.forEach(function (n) {
      var chain = namespaceChain(n.namespace), parent;
      chain.forEach(function (ns, i) {
        if (!groups[ns]) {
          groups[ns] = true;
          out.push({group: 'nodes', data: {id: 'ns:' + ns, label: ns, parent: i ? 'ns:' + chain[i - 1] : undefined},
                    classes: 'namespace', selectable: false});
        }
      });
      parent = chain.length ? 'ns:' + chain[chain.length - 1] : undefined;
      var nf = index.byNode[n.id] || [];
      out.push({group: 'nodes', data: {id: n.id, label: n.name + (n.definition ? '' : ' (no definition)'), parent: parent},
                classes: ['instance', severityOf(nf), n.editable ? '' : 'readonly'].join(' ')});
      var pos = positions[n.id], ins = 0, outs = 0, rows = rowsOf(n);
      n.ports.forEach(function (p) {
        var offers = !!OFFERS[p.kind], row = offers ? outs++ : ins++;
        var id = portId(n, p), pf = index.byPort[id] || [];
        out.push({group: 'nodes', data: {id: id, label: p.name, node: n.id, kind: p.kind, type: p.type,
                                          final: p.final, dx: offers ? PORT_W : -PORT_W,
                                          dy: (row - (rows - 1) / 2) * PORT_H, parent: n.id},
                  position: {x: pos.x + (offers ? PORT_W : -PORT_W), y: pos.y + (row - (rows - 1) / 2) * PORT_H},
                  classes: ['port', p.kind, offers ? 'out' : 'in', severityOf(pf)].join(' '),
                  grabbable: false});
      });
      // two invisible corners: every node's box is as wide as two columns of ports
      [-PORT_W, PORT_W].forEach(function (dx, i) {
        out.push({group: 'nodes', data: {id: n.id + '|spacer' + i, parent: n.id, dx: dx, dy: 0},
                  position: {x: pos.x + dx, y: pos.y}, classes: 'spacer', grabbable: false,
                  selectable: false});
      });
    });
    state.edges.forEach(function (e) {
      out.push({group: 'edges', data: {id: e.id, source: e.source, target: e.target, label: e.name,
                                        communication: e.communication},
                classes: ['link', e.communication, severityOf(index.byEdge[e.id] || [])].join(' ')});
    });
    return out;
  }

  var STYLE = [
    // labels too small to read are not drawn (a large system zoomed out draws in time)
    {selector: 'node', style: {'font-family': 'DejaVu Sans, Liberation Sans, Arial, sans-serif',
                               'min-zoomed-font-size': 7}},
    {selector: 'node.namespace', style: {
      'shape': 'round-rectangle', 'background-color': '#e8eef5', 'background-opacity': 0.7,
      'border-width': 1, 'border-style': 'dashed', 'border-color': '#8aa0b8', 'label': 'data(label)',
      'text-valign': 'top', 'text-halign': 'center', 'font-size': 14, 'color': '#4a5f75', 'padding': 18}},
    {selector: 'node.instance', style: {
      'shape': 'round-rectangle', 'background-color': '#ffffff', 'border-width': 1.5, 'border-color': '#5a6b7b',
      'label': 'data(label)', 'text-valign': 'top', 'text-halign': 'center', 'font-size': 13,
      'font-weight': 'bold', 'color': '#1d2733', 'padding': 10, 'min-width': 2 * PORT_W, 'min-height': 20}},
    {selector: 'node.instance.readonly', style: {'border-style': 'dotted'}},
    {selector: 'node.instance:selected', style: {'border-width': 3, 'border-color': '#2a6fdb'}},
    {selector: 'node.port', style: {
      'width': 11, 'height': 11, 'label': 'data(label)', 'font-size': 10, 'color': '#33475b',
      'text-valign': 'center', 'text-max-width': 120, 'text-wrap': 'ellipsis',
      'border-width': 1.5, 'border-color': '#4a78b5', 'background-color': '#4a78b5'}},
    {selector: 'node.port.in', style: {'text-halign': 'right', 'text-margin-x': 4, 'background-color': '#ffffff'}},
    {selector: 'node.port.out', style: {'text-halign': 'left', 'text-margin-x': -4}},
    {selector: 'node.port.service_server, node.port.service_client', style: {'shape': 'diamond', 'border-color': '#3c9d5d'}},
    {selector: 'node.port.service_server', style: {'background-color': '#3c9d5d'}},
    {selector: 'node.port.action_server, node.port.action_client', style: {'shape': 'hexagon', 'border-color': '#a05ab4'}},
    {selector: 'node.port.action_server', style: {'background-color': '#a05ab4'}},
    {selector: 'edge.link', style: {
      'curve-style': 'bezier', 'width': 1.6, 'line-color': '#4a78b5', 'target-arrow-color': '#4a78b5',
      'target-arrow-shape': 'triangle', 'arrow-scale': 0.9}},
    {selector: 'edge.service', style: {'line-color': '#3c9d5d', 'target-arrow-color': '#3c9d5d', 'line-style': 'dashed'}},
    {selector: 'edge.action', style: {'line-color': '#a05ab4', 'target-arrow-color': '#a05ab4', 'line-style': 'dashed'}},
    {selector: '.info', style: {'border-color': '#7d8fa3'}},
    {selector: '.warning', style: {'border-color': '#e69500', 'border-width': 2.5}},
    {selector: '.error', style: {'border-color': '#d32f2f', 'border-width': 2.5}},
    {selector: 'edge.warning', style: {'line-color': '#e69500', 'target-arrow-color': '#e69500', 'width': 2.5}},
    {selector: 'edge.error', style: {'line-color': '#d32f2f', 'target-arrow-color': '#d32f2f', 'width': 2.5}},
    {selector: 'node.port.compatible', style: {'border-color': '#1e9e3e', 'border-width': 3.5, 'width': 15, 'height': 15}},
    {selector: 'node.port.incompatible', style: {'opacity': 0.3}},
    // the selected node keeps the colour of its findings and gets a blue halo (its border alone
    // was overridden by a finding's colour: the panel's node was not marked on the canvas)
    {selector: 'node.instance:selected', style: {'underlay-color': '#2a6fdb', 'underlay-opacity': 0.25,
                                                 'underlay-padding': 6, 'underlay-shape': 'round-rectangle'}},
    {selector: 'node.spacer', style: {'width': 1, 'height': 1, 'opacity': 0, 'events': 'no'}},
    {selector: '.eh-preview, .eh-ghost-edge', style: {'line-color': '#2a6fdb', 'target-arrow-color': '#2a6fdb',
                                                      'target-arrow-shape': 'triangle', 'line-style': 'dotted', 'width': 2}},
    {selector: '.eh-ghost-node', style: {'opacity': 0, 'width': 1, 'height': 1}}
  ];

  function makeCanvas() {
    var cy = studio.cy = cytoscape({
      container: $('canvas'), style: STYLE, elements: [],
      minZoom: 0.05, maxZoom: 3, boxSelectionEnabled: false, autoungrabify: false,
      textureOnViewport: true, pixelRatio: 1
    });
    // a namespace's name stays readable however far the drawing is zoomed out (13 pixels on
    // screen at least; its nodes' labels are not drawn when too small)
    function namespaceLabels() {
      var size = Math.max(14, 13 / cy.zoom());
      if (size !== studio.namespaceFont) {
        studio.namespaceFont = size;
        cy.nodes('.namespace').style('font-size', size);
      }
    }
    cy.on('zoom', namespaceLabels);
    cy.on('add', 'node.namespace', function () { studio.namespaceFont = null; namespaceLabels(); });
    studio.eh = cy.edgehandles({
      canConnect: function (source, target) {
        return !!(studio.compatible && studio.compatible[target.id()] && studio.compatible[target.id()].ok);
      },
      edgeParams: function () { return {classes: 'pending'}; },
      hoverDelay: 50, snap: true, snapThreshold: 12, snapFrequency: 30, noEdgeEventsInDraw: true,
      disableBrowserGestures: true
    });
    cy.on('tapstart', 'node.port', function (evt) {
      var port = evt.target;
      cy.userPanningEnabled(false);  // the drag draws an edge: the drawing must not move
      studio.compatible = null;
      markCompatible(port);
      studio.eh.start(port);
    });
    cy.on('ehhoverover', function (evt, source, target) {
      var verdict = studio.compatible && studio.compatible[target.id()];
      if (verdict) { status(verdict.ok ? 'connect to ' + target.data('label') : verdict.reason); }
    });
    cy.on('ehcomplete', function (evt, source, target, added) {
      added.remove();
      call('connect', {a: source.id(), b: target.id()}).then(function (answer) {
        if (answer.ok) { status((answer.message || 'connected') + ''); }
      });
    });
    cy.on('ehstop', function () {
      cy.userPanningEnabled(true);
      cy.nodes('.port').removeClass('compatible incompatible');
    });
    cy.on('tap', 'node.instance', function (evt) { select(evt.target.id()); });
    cy.on('tap', 'node.port', function (evt) { select(evt.target.data('node')); });
    cy.on('tap', function (evt) { if (evt.target === cy) { select(null); } });
    cy.on('tap', 'edge.link', function (evt) {
      var e = evt.target;
      status(e.data('communication') + ' ' + e.data('label'));
    });
    cy.on('cxttap', 'edge.link', function (evt) {
      var e = evt.target;
      if (window.confirm('Disconnect ' + e.data('label') + '?')) {
        call('disconnect', {a: e.data('source'), b: e.data('target')});
      }
    });
    cy.on('dragfree', 'node.instance', function () { savePositions(); });
    cy.on('mouseover', 'node.port', function (evt) {
      var p = evt.target;
      status(SHORT[p.data('kind')] + ' ' + p.data('label') + ' → ' + p.data('final') + ' (' + p.data('type') + ')');
    });
  }

  function markCompatible(port) {
    var cy = studio.cy;
    call('compatible', {port: port.id()}).then(function (answer) {
      studio.compatible = answer.ports || {};
      cy.batch(function () {
        cy.nodes('.port').forEach(function (p) {
          if (p.id() === port.id()) { return; }
          var verdict = studio.compatible[p.id()];
          p.removeClass('compatible incompatible');
          p.addClass(verdict && verdict.ok ? 'compatible' : 'incompatible');
        });
      });
    });
  }

  function anchorOf(instance) {
    var ports = instance.children();
    if (!ports.length) { return instance.position(); }
    var p = ports[0];
    return {x: p.position('x') - p.data('dx'), y: p.position('y') - p.data('dy')};
  }

  var positionTimer = null;
  function savePositions() {
    clearTimeout(positionTimer);
    positionTimer = setTimeout(function () {
      var positions = {};
      studio.cy.nodes('.instance').forEach(function (n) {
        var a = anchorOf(n);
        positions[n.id()] = {x: Math.round(a.x), y: Math.round(a.y)};
      });
      studio.positions = positions;
      call('positions', {positions: positions});
    }, 150);
  }

  function sameClasses(ele, classes) {
    var want = classes.split(' ').filter(Boolean).sort().join(' ');
    return ele.classes().slice().sort().join(' ') === want;
  }

  function inView(ele) {
    if (!ele.length || !ele.visible()) { return true; }
    var box = ele.boundingBox(), view = studio.cy.extent();
    return box.x1 >= view.x1 && box.x2 <= view.x2 && box.y1 >= view.y1 && box.y2 <= view.y2;
  }

  // everything in view, never magnified beyond its natural size (one node does not fill the
  // canvas)
  function fitAll() {
    var cy = studio.cy;
    cy.fit(undefined, 24);
    if (cy.zoom() > 1) { cy.zoom(1); cy.center(); }
  }

  function draw(state, fit) {
    // Only what changed is changed: the elements drawn already keep their place and their
    // cached pictures (a 100-node system is redrawn in time after an edit).
    var cy = studio.cy, fresh = elements(state), keep = {}, added = [];
    var keepView = cy.elements().length > 0 && !fit;
    var zoom = cy.zoom(), pan = cy.pan();
    cy.batch(function () {
      fresh.forEach(function (e) {
        var id = e.data.id, old = cy.getElementById(id);
        keep[id] = true;
        if (!old.length) { added.push(e); return; }
        if (e.group === 'nodes' && (old.data('parent') || null) !== (e.data.parent || null)) {
          old.remove();
          added.push(e);
          return;
        }
        var update = {}, changed = false;
        Object.keys(e.data).forEach(function (k) {
          if (k !== 'parent' && old.data(k) !== e.data[k]) { update[k] = e.data[k]; changed = true; }
        });
        if (changed) {
          old.data(update);
          if (e.position && ('dx' in update || 'dy' in update)) { old.position(e.position); }
        }
        if (!sameClasses(old, e.classes || '')) { old.classes(e.classes || ''); }
      });
      cy.elements().forEach(function (ele) {
        if (!keep[ele.id()] && !ele.removed()) { ele.remove(); }
      });
      cy.add(added);
    });
    if (keepView) { cy.viewport({zoom: zoom, pan: pan}); }
    // a node just added where the view does not reach (another namespace's block) is shown:
    // everything is fitted again
    if (!keepView || added.some(function (e) { return e.group === 'nodes' && !inView(cy.getElementById(e.data.id)); })) {
      fitAll();
    }
    if (studio.selected && cy.getElementById(studio.selected).length) {
      cy.getElementById(studio.selected).select();
    }
  }

  // -- the toolbar, the findings ------------------------------------------------------------

  function showCounts(state) {
    var counts = $('counts');
    clear(counts);
    ['error', 'warning', 'info'].forEach(function (sev, i) {
      var n = state.counts[sev] || 0;
      if (i) { counts.appendChild(document.createTextNode(' · ')); }
      counts.appendChild(el('span', sev, n + ' ' + (n === 1 ? sev : sev + 's').replace('infos', 'info')));
    });
  }

  function findingLine(f) {
    var li = el('li');
    li.appendChild(el('span', 'sev ' + f.severity, f.severity));
    li.appendChild(el('span', 'code', f.code));
    li.appendChild(document.createTextNode(f.message));
    li.title = f.message + (f.file ? ' (' + f.file + ':' + f.line + ':' + f.column + ')' : '');
    return li;
  }

  function showFindings(state) {
    var list = $('findings');
    clear(list);
    state.findings.forEach(function (f) {
      var li = findingLine(f);
      li.addEventListener('click', function () {
        var target = state.nodes.filter(function (n) { return (f.nodes || []).indexOf(n.fqn) >= 0; })[0];
        if (target) { select(target.id); studio.cy.animate({center: {eles: studio.cy.getElementById(target.id)}}, {duration: 200}); }
      });
      list.appendChild(li);
    });
    var kept = $('readonly-items');
    clear(kept);
    (state.readonly || []).forEach(function (k) {
      kept.appendChild(el('li', null, 'kept as written, read-only: ' + k.what + (k.line ? ' (line ' + k.line + ')' : '')));
    });
  }

  function showCode(state) {
    var code = state.code || {}, button = $('run-code');
    button.hidden = !code.needed;
    button.disabled = !code.allowed;
    button.title = code.message || button.title;
  }

  // -- the side panel -----------------------------------------------------------------------

  function nodeById(id) {
    return studio.state && studio.state.nodes.filter(function (n) { return n.id === id; })[0];
  }

  function select(id) {
    studio.selected = id;
    studio.cy.nodes(':selected').unselect();
    if (id) { studio.cy.getElementById(id).select(); }
    panel();
  }

  var paramTimers = {};
  function parameterEditor(node, param) {
    var box = el('div', 'param' + (param.error ? ' invalid' : ''));
    box.dataset.name = param.name;
    var head = el('div', 'head');
    head.appendChild(el('span', 'pname', param.name));
    head.appendChild(el('span', 'ptype', param.type + (param.read_only ? ', read-only' : '')));
    box.appendChild(head);
    var input = el('input');
    if (param.type === 'bool') {
      input.type = 'checkbox';
      input.checked = param.value === true;
    } else {
      input.type = 'text';
      input.value = param.text === null || param.text === undefined ? '' : param.text;
      input.placeholder = param.default_text === null || param.default_text === undefined
        ? 'no default: required' : 'default ' + param.default_text;
    }
    input.setAttribute('aria-label', param.name);
    input.disabled = !node.editable;
    var error = el('p', 'error-text', param.error || '');
    error.hidden = !param.error;
    function send() {
      var text = input.type === 'checkbox' ? (input.checked ? 'true' : 'false') : input.value;
      call('parameter', {node: node.id, name: param.name, value: text}).then(function (answer) {
        var problems = (answer.diagnostics || []).filter(function (d) { return d.severity === 'error'; });
        error.textContent = problems.map(function (d) { return d.message; }).join('; ') || answer.error || '';
        error.hidden = !error.textContent;
        box.classList.toggle('invalid', !error.hidden);
      });
    }
    input.addEventListener(input.type === 'checkbox' ? 'change' : 'input', function () {
      clearTimeout(paramTimers[param.name]);
      paramTimers[param.name] = setTimeout(send, input.type === 'checkbox' ? 0 : 200);
    });
    box.appendChild(input);
    if (param.constraints) { box.appendChild(el('div', 'constraints', param.constraints)); }
    if (param.description) { box.appendChild(el('div', 'description', param.description)); }
    box.appendChild(error);
    return box;
  }

  function remapRows(node) {
    var holder = $('remaps');
    clear(holder);
    node.remaps.forEach(function (r, i) {
      if (r.kept) { holder.appendChild(el('div', 'remap kept', r.text)); return; }
      var row = el('div', 'remap');
      var from = el('input'); from.type = 'text'; from.value = r.from; from.setAttribute('aria-label', 'from');
      var to = el('input'); to.type = 'text'; to.value = r.to; to.setAttribute('aria-label', 'to');
      var drop = el('button', null, '×'); drop.type = 'button'; drop.title = 'remove the rule';
      from.disabled = to.disabled = drop.disabled = !node.editable;
      row.appendChild(from); row.appendChild(el('span', null, ':=')); row.appendChild(to); row.appendChild(drop);
      from.addEventListener('change', sendRemaps); to.addEventListener('change', sendRemaps);
      drop.addEventListener('click', function () { row.remove(); sendRemaps(); });
      holder.appendChild(row);
    });
  }

  function sendRemaps() {
    var rules = [];
    Array.prototype.forEach.call($('remaps').querySelectorAll('.remap:not(.kept)'), function (row) {
      var inputs = row.querySelectorAll('input');
      if (inputs[0].value || inputs[1].value) { rules.push([inputs[0].value, inputs[1].value]); }
    });
    call('remaps', {node: studio.selected, remaps: rules}).then(function () { panel(); });
  }

  function panel() {
    var node = nodeById(studio.selected);
    $('panel-empty').hidden = !!node;
    $('panel-node').hidden = !node;
    if (!node) { return; }
    $('panel-title').textContent = node.name;
    $('panel-what').textContent = node.package + ' ' + (node.executable || node.plugin || '') +
      (node.kind !== 'node' ? ' (' + node.kind + ')' : '') + ' — ' + node.fqn;
    $('panel-readonly').hidden = node.editable;
    $('panel-readonly').textContent = node.editable ? '' : 'Read-only: ' + (node.read_only_reason || 'not declarative');
    $('node-name').value = node.name_given || '';
    $('node-name').placeholder = node.name;
    $('node-namespace').value = node.namespace_given || '';
    $('node-namespace').placeholder = node.namespace;
    $('node-name').disabled = $('node-namespace').disabled = !node.editable;
    $('rename-error').hidden = true;
    var params = $('parameters');
    clear(params);
    if (!node.parameters.length) { params.appendChild(el('p', 'muted', node.definition ? 'none declared' : 'no definition: unknown')); }
    node.parameters.forEach(function (p) { params.appendChild(parameterEditor(node, p)); });
    remapRows(node);
    var list = $('node-findings');
    clear(list);
    var fs = studio.state.findings.filter(function (f) { return (f.nodes || []).indexOf(node.fqn) >= 0; });
    if (!fs.length) { list.appendChild(el('li', 'muted', 'none')); }
    fs.forEach(function (f) { list.appendChild(findingLine(f)); });
    var kept = $('node-kept');
    clear(kept);
    $('kept-title').hidden = !node.kept.length;
    node.kept.forEach(function (k) { kept.appendChild(el('li', null, k.what + ': ' + k.text)); });
    $('remove-node').disabled = !node.editable;
  }

  function refreshPanelFindings() {
    // after a parameter edit: the findings of the node change, its editors stay as typed
    var node = nodeById(studio.selected);
    if (!node) { panel(); return; }
    var list = $('node-findings');
    clear(list);
    var fs = studio.state.findings.filter(function (f) { return (f.nodes || []).indexOf(node.fqn) >= 0; });
    if (!fs.length) { list.appendChild(el('li', 'muted', 'none')); }
    fs.forEach(function (f) { list.appendChild(findingLine(f)); });
  }

  function rename() {
    call('rename', {node: studio.selected, name: $('node-name').value, namespace: $('node-namespace').value})
      .then(function (answer) {
        var problems = (answer.diagnostics || []).filter(function (d) { return d.severity === 'error'; });
        $('rename-error').textContent = problems.map(function (d) { return d.message; }).join('; ') || answer.error || '';
        $('rename-error').hidden = !$('rename-error').textContent;
        if (answer.ok) { panel(); }
      });
  }

  // -- the palette --------------------------------------------------------------------------

  function portSummary(entry) {
    var counts = {};
    entry.ports.forEach(function (p) { counts[p.kind] = (counts[p.kind] || 0) + 1; });
    return Object.keys(SHORT).filter(function (k) { return counts[k]; })
      .map(function (k) { return counts[k] + ' ' + SHORT[k]; }).join(' · ') || 'no ports';
  }

  function showPalette() {
    var words = $('search').value.toLowerCase().split(/\s+/).filter(Boolean);
    var list = $('definitions'), shown = 0;
    clear(list);
    studio.palette.forEach(function (entry) {
      var hay = [entry.package, entry.executable].concat(entry.ports.map(function (p) { return p.type; }))
        .join(' ').toLowerCase();
      if (!words.every(function (w) { return hay.indexOf(w) >= 0; })) { return; }
      shown += 1;
      var li = el('li');
      li.dataset.package = entry.package;
      li.dataset.executable = entry.executable;
      li.title = entry.ports.map(function (p) { return SHORT[p.kind] + ' ' + p.name + ' (' + p.type + ')'; }).join('\n');
      li.appendChild(el('span', 'pkg', entry.package));
      li.appendChild(breakable(el('span', 'exe'), entry.executable));
      li.appendChild(el('span', 'ports', portSummary(entry)));
      if (entry.problems.length) { li.appendChild(el('span', 'problem', entry.problems[0])); }
      var add = el('button', 'add', '+');
      add.type = 'button';
      add.title = 'add ' + entry.package + ' ' + entry.executable + ' to the system';
      add.addEventListener('click', function (evt) { evt.stopPropagation(); addNode(entry); });
      li.addEventListener('dblclick', function () { addNode(entry); });
      li.appendChild(add);
      list.appendChild(li);
    });
    $('palette-count').textContent = shown + ' of ' + studio.palette.length + ' definitions';
  }

  function addNode(entry) {
    call('add', {package: entry.package, executable: entry.executable, name: entry.node_name,
                 namespace: $('add-namespace').value || '/'}).then(function (answer) {
      if (answer.ok && answer.node) { select(answer.node); status('added ' + entry.executable); savePositions(); }
    });
  }

  // -- the whole state ----------------------------------------------------------------------

  function show(state, fit) {
    var first = !studio.state;
    studio.state = state;
    $('file').textContent = state.file.split('/').slice(-2).join('/');
    $('file').title = state.file;
    $('dirty').hidden = !state.dirty;
    draw(state, fit || first);
    showCounts(state);
    showFindings(state);
    showCode(state);
    var active = document.activeElement;
    var editing = active && $('panel').contains(active) && active.tagName === 'INPUT';
    if (editing) { refreshPanelFindings(); } else { panel(); }
    studio.version += 1;
    document.body.dataset.version = String(studio.version);
  }

  function wire() {
    $('search').addEventListener('input', showPalette);
    $('fit').addEventListener('click', fitAll);
    $('save').addEventListener('click', function () {
      call('save', {}).then(function (answer) {
        if (answer.ok) { status('saved ' + answer.file); return; }
        if (answer.changed && window.confirm((answer.error || 'the file changed on disk') + '\nSave anyway?')) {
          call('save', {force: true}).then(function (a) { if (a.ok) { status('saved ' + a.file); } });
        }
      });
    });
    $('export').addEventListener('change', function () {
      var what = $('export').value;
      $('export').value = '';
      if (!what) { return; }
      call('export', {what: what}).then(function (answer) {
        if (answer.ok) { status('wrote ' + answer.written.join(', ')); }
      });
    });
    $('run-code').addEventListener('click', function () {
      if (window.confirm('Run the Python code of the launch files (in a sandboxed child process)?')) {
        call('run-code', {});
      }
    });
    $('node-name').addEventListener('change', rename);
    $('node-namespace').addEventListener('change', rename);
    $('add-remap').addEventListener('click', function () {
      var node = nodeById(studio.selected);
      if (!node) { return; }
      node.remaps.push({from: '', to: ''});
      remapRows(node);
    });
    $('remove-node').addEventListener('click', function () {
      var id = studio.selected;
      if (id) { select(null); call('remove', {node: id}); }
    });
  }

  studio.show = show;  // (the benchmark draws an answer it asked for itself)

  function start() {
    makeCanvas();
    wire();
    var t0 = performance.now();
    call('state', {}).then(function () {
      studio.ready = true;
      studio.shownAfter = performance.now() - t0;
      document.body.dataset.ready = 'true';
      return call('palette', {});
    }).then(function (answer) {
      studio.palette = answer.palette || [];
      showPalette();
      document.body.dataset.palette = 'true';
    });
  }

  start();
}());
