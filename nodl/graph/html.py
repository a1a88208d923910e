"""A self-contained HTML page: the SVG inline, the data as JSON, a little CSS and JS.

Nothing is fetched: no fonts, scripts or styles from the network.  The inlined
script fits the drawing to the window (its ``viewBox``), zooms and pans it, searches
names, and folds a namespace (a cluster) to one box.  Clicking a node (or a topic,
service or action) shows its interface (the node's own first, then what its client
library gives it) and its findings in the side panel; the findings list below links
back to the picture.
"""

from __future__ import annotations

import html
import json
import re

from nodl.graph.model import Graph
from nodl.system.run import Analysis
from nodl.text_safety import visible

__all__ = ['format_html', 'json_for_script']


def _shown(data: object) -> object:
    # every string as the page shows it: control and bidi characters as visible escapes
    if isinstance(data, str):
        return visible(data)
    if isinstance(data, dict):
        return {_shown(k): _shown(v) for k, v in data.items()}
    if isinstance(data, (list, tuple)):
        return [_shown(v) for v in data]
    return data


def _h(text: str) -> str:
    """``text`` as HTML text, control and bidi characters shown as escapes, never rendered."""
    return html.escape(visible(text))


def json_for_script(data: object) -> str:
    """JSON that is safe inside a ``<script>`` element (no ``</script>``, no ``<!--``), its
    strings as the page shows them (no control or bidi character to render)."""
    text = json.dumps(_shown(data), default=str, separators=(',', ':'))
    return text.replace('<', '\\u003c').replace('>', '\\u003e').replace('&', '\\u0026') \
        .replace('\u2028', '\\u2028').replace('\u2029', '\\u2029')


def _inline_svg(svg: str) -> str:
    """The ``<svg>`` element alone (no XML declaration, DOCTYPE or comments), filling the
    canvas: the page's script fits the drawing to it, zooms and pans with the ``viewBox``."""
    start = svg.find('<svg')
    svg = svg[start:] if start >= 0 else svg
    svg = re.sub(r'<!--.*?-->', '', svg, flags=re.DOTALL)
    return re.sub(r'<svg([^>]*?)\swidth="[^"]*"\s+height="[^"]*"',
                  r'<svg\1 width="100%" height="100%" preserveAspectRatio="xMidYMid meet"',
                  svg, count=1)


_CSS = """
*{box-sizing:border-box}
body{margin:0;font:14px/1.45 system-ui,-apple-system,"Segoe UI",Roboto,Helvetica,Arial,sans-serif;color:#202124;background:#f8f9fa}
header{display:flex;align-items:center;gap:16px;padding:10px 20px;background:#fff;border-bottom:1px solid #dadce0}
header h1{font-size:17px;margin:0;font-weight:600}
header .file{color:#5f6368;font-family:ui-monospace,Menlo,Consolas,monospace;font-size:13px}
.counts{margin-left:auto;display:flex;gap:8px}
.pill{border-radius:12px;padding:2px 10px;font-size:12px;font-weight:600;background:#e8eaed}
.pill.error{background:#fce8e6;color:#c5221f}.pill.warning{background:#fef7e0;color:#b06000}.pill.info{background:#e8f0fe;color:#1967d2}
html,body{height:100%;overflow:hidden}
body{display:flex;flex-direction:column}
header{flex:none;min-width:0;overflow:hidden;white-space:nowrap}
main{flex:1;min-height:0;display:grid;grid-template-columns:minmax(0,1fr) 380px}
#canvas{overflow:hidden;background:#fff;position:relative;min-width:0;min-height:0}
#canvas svg{position:absolute;inset:0;width:100%;height:100%;display:block;touch-action:none;cursor:grab;user-select:none}
#canvas svg.panning{cursor:grabbing}
#canvas g.node,#canvas g.edge{cursor:pointer}
#canvas g.node.selected polygon,#canvas g.node.selected ellipse{stroke:#1a73e8;stroke-width:3.5}
#canvas g.dim{opacity:.25}
#canvas svg.searching g.node:not(.match),#canvas svg.searching g.edge{opacity:.2}
#canvas g.node.match polygon,#canvas g.node.match ellipse{stroke:#1a73e8;stroke-width:4}
#canvas g.cluster>text{cursor:pointer}
#canvas g.cluster>text:hover{text-decoration:underline}
#canvas g.fold{cursor:pointer}
#canvas g.fold rect{fill:#e8eaed;stroke:#5f6368;stroke-width:1.5}
#canvas g.fold.match rect{stroke:#1a73e8;stroke-width:4}
#canvas g.fold text{font:14px Helvetica,Arial,sans-serif;fill:#202124}
#tools{position:absolute;top:8px;left:8px;right:8px;display:flex;gap:6px;align-items:center;flex-wrap:wrap;pointer-events:none;z-index:1}
#tools>*{pointer-events:auto}
#tools input{font:inherit;padding:4px 8px;border:1px solid #dadce0;border-radius:6px;width:240px;background:#fff}
#tools button{font:inherit;font-size:13px;padding:3px 9px;border:1px solid #dadce0;border-radius:6px;background:#fff;cursor:pointer}
#tools button:hover{background:#f1f3f4}
#found{font-size:12px;color:#5f6368;background:rgba(255,255,255,.85);padding:1px 4px;border-radius:4px}
#help{position:absolute;bottom:6px;left:8px;font-size:11.5px;color:#5f6368;background:rgba(255,255,255,.85);padding:1px 4px;border-radius:4px;pointer-events:none}
details.base summary{cursor:pointer;color:#5f6368;font-size:12.5px;margin-top:12px}
.by{color:#5f6368;font-size:11px}
aside{border-left:1px solid #dadce0;background:#fff;overflow:auto;padding:16px 18px;min-height:0}
aside h2{font-size:15px;margin:0 0 4px;word-break:break-all}
aside h3{font-size:12px;text-transform:uppercase;letter-spacing:.04em;color:#5f6368;margin:16px 0 6px}
.kind{font-size:12px;color:#5f6368}
table{border-collapse:collapse;width:100%;font-size:12.5px}
td{padding:3px 4px;border-bottom:1px solid #f1f3f4;vertical-align:top;word-break:break-all}
td.k{color:#5f6368;white-space:nowrap;word-break:normal}
code{font-family:ui-monospace,Menlo,Consolas,monospace;font-size:12px}
.finding{border-left:4px solid #dadce0;background:#f8f9fa;padding:6px 8px;margin:6px 0;border-radius:0 6px 6px 0;font-size:12.5px}
.finding.error{border-color:#d93025;background:#fce8e6}.finding.warning{border-color:#e37400;background:#fef7e0}.finding.info{border-color:#1a73e8;background:#e8f0fe}
.finding .code{font-weight:600;font-size:11px;color:#5f6368}
.finding{overflow-wrap:anywhere}
.finding .where{color:#5f6368;font-size:11px;font-family:ui-monospace,Menlo,Consolas,monospace;word-break:break-all}
.hint{color:#5f6368}
.legend{display:flex;gap:14px;flex-wrap:wrap;font-size:12px;color:#5f6368;margin-top:8px}
.legend span::before{content:"";display:inline-block;width:14px;height:10px;margin-right:5px;vertical-align:-1px;border:1.5px solid #5f6368;background:#fff}
.legend .l-node::before{border-radius:50%;background:#e8f0fe}.legend .l-topic::before{background:#f1f3f4}
.legend .l-service::before{background:#e6f4ea;border-radius:3px}.legend .l-action::before{background:#fef7e0;border-style:double;border-width:3px}
.legend .l-err::before{border-color:#d93025;border-width:2.5px}.legend .l-undef::before{border-style:dashed;border-radius:50%}
#all a{color:#1a73e8;cursor:pointer;text-decoration:none}
"""

_JS = r"""
(function(){
  var data = JSON.parse(document.getElementById('nodl-data').textContent);
  var panel = document.getElementById('panel');
  var canvas = document.getElementById('canvas');
  var svg = canvas.querySelector('svg');
  var NS = 'http://www.w3.org/2000/svg';
  var root = svg.querySelector('g.graph') || svg;
  var clusters = data.clusters || {};
  function el(tag, cls, text){var e=document.createElement(tag); if(cls) e.className=cls; if(text!==undefined) e.textContent=text; return e;}
  function row(t, k, v, by){var tr=el('tr'); tr.appendChild(el('td','k',k)); var td=el('td'); td.appendChild(el('code',null,v)); if(by) {td.appendChild(document.createTextNode(' ')); td.appendChild(el('span','by',by));} tr.appendChild(td); t.appendChild(tr);}
  function byId(id){ return document.getElementById(id); }

  /* ---- the view: the viewBox, kept to the canvas's proportions ---- */
  var home = (function(){ var b = svg.viewBox.baseVal; return {x:b.x, y:b.y, w:b.width || 1, h:b.height || 1}; })();
  var view = null;
  function size(){ return {w: Math.max(svg.clientWidth, 1), h: Math.max(svg.clientHeight, 1)}; }
  function setView(v){ view = v; svg.setAttribute('viewBox', [v.x, v.y, v.w, v.h].map(function(n){return +n.toFixed(2);}).join(' ')); }
  /* the part of the canvas left free by the tool bar (top) and the help line (bottom), px */
  var TOP = 48, BOTTOM = 26, SIDE = 10;
  function fitBox(b, least){
    var c = size(), free = {w: Math.max(c.w - 2*SIDE, 1), h: Math.max(c.h - TOP - BOTTOM, 1)};
    var s = Math.max(b.w / free.w, b.h / free.h);
    if(least) s = Math.max(s, least);
    setView({x: b.x + (b.w - c.w*s)*0.5, y: b.y + b.h*0.5 - (TOP + free.h*0.5)*s, w: c.w*s, h: c.h*s});
  }
  function fit(){ fitBox(home); }
  function natural(){ return 0.75; }  /* viewBox units (pt) per CSS pixel at 100% */
  function zoom(f, px, py){
    var c = size(), s = view.w / c.w * f;
    var most = Math.max(home.w / c.w, home.h / c.h) * 4, least = natural() / 8;
    s = Math.min(Math.max(s, least), most); f = s * c.w / view.w;
    if(px === undefined){ px = c.w/2; py = c.h/2; }
    var x = view.x + px * view.w / c.w, y = view.y + py * view.h / c.h;
    setView({x: x - (x - view.x) * f, y: y - (y - view.y) * f, w: view.w * f, h: view.h * f});
  }
  function pan(dx, dy){ var c = size(); setView({x: view.x - dx * view.w / c.w, y: view.y - dy * view.h / c.h, w: view.w, h: view.h}); }
  function boxOf(g){
    /* g's bounding box in viewBox units */
    var b = g.getBBox(), m = svg.getScreenCTM().inverse().multiply(g.getScreenCTM());
    var pts = [[b.x, b.y], [b.x + b.width, b.y + b.height]].map(function(p){ var q = svg.createSVGPoint(); q.x = p[0]; q.y = p[1]; return q.matrixTransform(m); });
    return {x: pts[0].x, y: pts[0].y, w: pts[1].x - pts[0].x, h: pts[1].y - pts[0].y};
  }
  function union(boxes){
    var x0 = Infinity, y0 = Infinity, x1 = -Infinity, y1 = -Infinity;
    boxes.forEach(function(b){ x0 = Math.min(x0, b.x); y0 = Math.min(y0, b.y); x1 = Math.max(x1, b.x + b.w); y1 = Math.max(y1, b.y + b.h); });
    return {x: x0, y: y0, w: x1 - x0, h: y1 - y0};
  }
  function centreOn(boxes){
    /* the boxes in view, at least at 100% (never zoomed out past the whole drawing) */
    var c = size(), b = union(boxes);
    var pad = {x: b.x - 40, y: b.y - 40, w: b.w + 80, h: b.h + 80};
    fitBox(pad, Math.min(natural(), Math.max(home.w / (c.w - 2*SIDE), home.h / (c.h - TOP - BOTTOM))));
  }
  svg.addEventListener('wheel', function(ev){
    ev.preventDefault();
    var r = svg.getBoundingClientRect();
    zoom(Math.exp(ev.deltaY * (ev.deltaMode ? 0.05 : 0.0015)), ev.clientX - r.left, ev.clientY - r.top);
  }, {passive: false});
  var drag = null, dragged = false;
  svg.addEventListener('pointerdown', function(ev){
    if(ev.button !== 0) return;
    drag = {x: ev.clientX, y: ev.clientY, id: ev.pointerId}; dragged = false;
  });
  svg.addEventListener('pointermove', function(ev){
    if(!drag) return;
    var dx = ev.clientX - drag.x, dy = ev.clientY - drag.y;
    if(!dragged && Math.abs(dx) + Math.abs(dy) < 4) return;
    if(!dragged){ dragged = true; svg.classList.add('panning'); try { svg.setPointerCapture(drag.id); } catch(e) {} }
    pan(dx, dy); drag.x = ev.clientX; drag.y = ev.clientY;
  });
  function endDrag(){ drag = null; svg.classList.remove('panning'); }
  svg.addEventListener('pointerup', endDrag);
  svg.addEventListener('pointercancel', endDrag);
  /* a drag ends in a click: it must not select or fold what the pointer was released over */
  svg.addEventListener('click', function(ev){ if(dragged){ ev.stopPropagation(); ev.preventDefault(); dragged = false; } }, true);
  window.addEventListener('resize', function(){
    if(!view) return fit();
    var c = size(), s = view.w / lastSize.w, cx = view.x + view.w/2, cy = view.y + view.h/2;
    setView({x: cx - c.w*s/2, y: cy - c.h*s/2, w: c.w*s, h: c.h*s}); lastSize = c;
  });

  /* ---- namespaces: fold to one box, unfold on click ---- */
  var folded = {}, clusterOf = {}, boxes = {};
  Object.keys(clusters).forEach(function(k){ clusters[k].vertices.forEach(function(v){ clusterOf[v] = k; }); });
  function chain(k){ var out = []; while(k){ out.push(k); k = clusters[k].parent; } return out; }
  function outerFolded(k){ var hit = null; chain(k).forEach(function(c){ if(folded[c]) hit = c; }); return hit; }
  function foldedHome(vid){ return clusterOf[vid] ? outerFolded(clusterOf[vid]) : null; }
  function members(k){
    var out = {vertices: clusters[k].vertices.slice()};
    clusters[k].children.forEach(function(c){ out.vertices = out.vertices.concat(members(c).vertices); });
    return out;
  }
  function foldLabel(k){
    var counts = {}; members(k).vertices.forEach(function(v){ var kind = data.vertices[v].kind; counts[kind] = (counts[kind] || 0) + 1; });
    var words = ['node', 'topic', 'service', 'action'].filter(function(w){ return counts[w]; }).map(function(w){ return counts[w] + ' ' + w + (counts[w] > 1 ? 's' : ''); });
    return '\u25b8 ' + clusters[k].name + '  (' + words.join(', ') + ')';
  }
  function foldBox(k){
    if(boxes[k]) return boxes[k];
    var g = byId(k); if(!g) return null;
    var b = g.getBBox(), box = document.createElementNS(NS, 'g');
    box.setAttribute('class', 'fold'); box.setAttribute('data-cluster', k);
    var r = document.createElementNS(NS, 'rect');
    ['x', 'y', 'width', 'height'].forEach(function(a, i){ r.setAttribute(a, [b.x, b.y, b.width, b.height][i]); });
    r.setAttribute('rx', 8);
    var t = document.createElementNS(NS, 'text');
    /* the label across the box, as large as the box allows (a big namespace folded is read
       zoomed out) */
    t.textContent = foldLabel(k);
    var font = Math.max(14, Math.min(b.width * 0.9 / (t.textContent.length * 0.6), b.height * 0.25, 200));
    t.setAttribute('x', b.x + b.width * 0.5); t.setAttribute('y', b.y + Math.min(b.height * 0.5, font * 2));
    t.setAttribute('text-anchor', 'middle'); t.style.fontSize = font + 'px';
    var title = document.createElementNS(NS, 'title'); title.textContent = clusters[k].name + ': click to unfold';
    box.appendChild(title); box.appendChild(r); box.appendChild(t);
    box.addEventListener('click', function(ev){ ev.stopPropagation(); unfold(k); });
    root.appendChild(box);   /* last: drawn over the edges that lead into the namespace */
    boxes[k] = box; return box;
  }
  function applyFolds(){
    Object.keys(data.vertices).forEach(function(v){ var g = byId(v); if(g) g.style.display = foldedHome(v) ? 'none' : ''; });
    data.edges.forEach(function(e){
      var g = byId(e[0] + '-' + e[1]); if(!g) return;
      var a = foldedHome(e[0]), b = foldedHome(e[1]);
      g.style.display = (a && a === b) ? 'none' : '';
    });
    Object.keys(clusters).forEach(function(k){
      var above = clusters[k].parent ? outerFolded(clusters[k].parent) : null;
      var g = byId(k); if(g) g.style.display = (above || folded[k]) ? 'none' : '';
      var box = folded[k] ? foldBox(k) : boxes[k];
      if(box) box.style.display = (folded[k] && !above) ? '' : 'none';
    });
    search();
  }
  function fold(k){ folded[k] = true; applyFolds(); }
  function unfold(k){ delete folded[k]; applyFolds(); }
  function reveal(vid){ chain(clusterOf[vid]).forEach(function(k){ delete folded[k]; }); applyFolds(); }
  Object.keys(clusters).forEach(function(k){
    var g = byId(k); if(!g) return;
    var label = g.querySelector('text');
    if(label){
      /* the name, after a fold mark, from the box's left edge */
      var frame = g.querySelector('path, polygon');
      label.textContent = '\u25be ' + label.textContent;
      if(frame){ label.setAttribute('text-anchor', 'start'); label.setAttribute('x', frame.getBBox().x + 7); }
      var hint = document.createElementNS(NS, 'title'); hint.textContent = clusters[k].name + ': click to fold'; label.appendChild(hint);
      label.addEventListener('click', function(ev){ ev.stopPropagation(); fold(k); });
    }
  });

  /* ---- details ---- */
  function findingBox(f){
    var d=el('div','finding '+f.severity);
    d.appendChild(el('div','code',f.severity.toUpperCase()+' '+f.kind+' ['+f.code+']'));
    d.appendChild(el('div',null,f.message));
    if(f.file) d.appendChild(el('div','where',f.file+(f.line?':'+f.line+':'+f.column:'')));
    return d;
  }
  function sections(parent, list){
    var bySection = {}, order = [];
    list.forEach(function(e){ if(!bySection[e.section]){ bySection[e.section] = []; order.push(e.section); } bySection[e.section].push(e); });
    order.forEach(function(section){
      parent.appendChild(el('h3',null,section.replace(/_/g,' ')));
      var t = el('table');
      bySection[section].forEach(function(e){ row(t, e.declared, e.name + '  ' + e.type, e.provider === 'other_code' ? '(other code: a mixin)' : ''); });
      parent.appendChild(t);
    });
  }
  function show(id){
    var v = data.vertices[id]; if(!v) return;
    panel.textContent='';
    panel.appendChild(el('div','kind',v.defined?v.kind:v.kind+' (no definition)'));
    panel.appendChild(el('h2',null,v.name));
    var d=v.details||{};
    if(v.kind==='node'){
      var t=el('table');
      row(t,'runs',d.package+' '+d.executable);
      row(t,'definition',d.definition||'none');
      if(d.source) row(t,'launched at',d.source.file+':'+d.source.line);
      panel.appendChild(t);
      var iface = d.interface || [];
      var own = iface.filter(function(e){ return e.provider !== 'client_library'; });
      var base = iface.filter(function(e){ return e.provider === 'client_library'; });
      if(v.defined && !own.length) panel.appendChild(el('div','hint','no endpoints of its own'));
      sections(panel, own);
      var ps=d.parameters||{}; var keys=Object.keys(ps);
      if(keys.length){panel.appendChild(el('h3',null,'parameters')); var t3=el('table'); keys.forEach(function(k){row(t3,k,JSON.stringify(ps[k]));}); panel.appendChild(t3);}
      if((d.remaps||[]).length){panel.appendChild(el('h3',null,'remaps')); var t4=el('table'); d.remaps.forEach(function(r){row(t4,r[0],r[1]);}); panel.appendChild(t4);}
      if(base.length){
        var more = el('details','base');
        more.appendChild(el('summary',null,'given by the client library ('+(d.client_library||'')+'): '+base.length+' endpoints'));
        sections(more, base); panel.appendChild(more);
      }
    } else {
      var t5=el('table'); (d.types||[]).forEach(function(ty){row(t5,'type',ty);}); panel.appendChild(t5);
    }
    panel.appendChild(el('h3',null,'findings ('+v.findings.length+')'));
    if(!v.findings.length) panel.appendChild(el('div','hint','none'));
    v.findings.forEach(function(f){panel.appendChild(findingBox(f));});
    select(id);
  }
  function select(id){
    var near={}; near[id]=true;
    data.edges.forEach(function(e){ if(e[0]===id) near[e[1]]=true; if(e[1]===id) near[e[0]]=true; });
    svg.querySelectorAll('g.node').forEach(function(g){ g.classList.toggle('selected', g.id===id); g.classList.toggle('dim', !near[g.id]); });
    svg.querySelectorAll('g.edge').forEach(function(g){ var p=g.id.split('-'); g.classList.toggle('dim', !(p[0]===id||p[1]===id)); });
  }
  function goTo(id){ reveal(id); var g = byId(id); if(g) centreOn([boxOf(g)]); show(id); }
  svg.querySelectorAll('g.node').forEach(function(g){ g.addEventListener('click', function(ev){ ev.stopPropagation(); show(g.id); }); });
  svg.addEventListener('click', function(){ svg.querySelectorAll('g').forEach(function(g){g.classList.remove('dim','selected');}); });
  document.querySelectorAll('#all a[data-id]').forEach(function(a){ a.addEventListener('click', function(){ goTo(a.getAttribute('data-id')); }); });

  /* ---- search: highlight what matches, centre on it; Enter goes from one to the next ---- */
  var input = byId('search'), found = byId('found'), matches = [], current = -1;
  function search(move){
    var q = input.value.trim().toLowerCase();
    svg.querySelectorAll('.match').forEach(function(g){ g.classList.remove('match'); });
    matches = q ? Object.keys(data.vertices).filter(function(v){ return data.vertices[v].name.toLowerCase().indexOf(q) >= 0; }) : [];
    svg.classList.toggle('searching', !!q);
    found.textContent = q ? (matches.length ? matches.length + ' found' : 'nothing found') : '';
    var shown = [];
    matches.forEach(function(v){
      var home = foldedHome(v), g = home ? foldBox(home) : byId(v);
      if(g){ g.classList.add('match'); shown.push(g); }
    });
    if(move && shown.length) centreOn(shown.map(boxOf));
  }
  input.addEventListener('input', function(){ current = -1; search(true); });
  input.addEventListener('keydown', function(ev){
    if(ev.key === 'Enter' && matches.length){ ev.preventDefault(); current = (current + (ev.shiftKey ? -1 : 1) + matches.length) % matches.length; goTo(matches[current]); found.textContent = (current + 1) + ' of ' + matches.length; }
    if(ev.key === 'Escape'){ input.value = ''; search(); fit(); input.blur(); }
  });

  /* ---- buttons and keys ---- */
  var actions = {
    fit: fit,
    'zoom-in': function(){ zoom(1/1.25); },
    'zoom-out': function(){ zoom(1.25); },
    'fold-all': function(){ Object.keys(clusters).forEach(function(k){ folded[k] = true; }); applyFolds(); },
    'unfold-all': function(){ folded = {}; applyFolds(); }
  };
  document.querySelectorAll('#tools button[data-do]').forEach(function(b){ b.addEventListener('click', function(){ actions[b.getAttribute('data-do')](); }); });
  document.addEventListener('keydown', function(ev){
    if(ev.target === input || ev.ctrlKey || ev.metaKey || ev.altKey) return;
    var step = 60, keys = {'+': actions['zoom-in'], '=': actions['zoom-in'], '-': actions['zoom-out'], '0': fit,
      ArrowLeft: function(){ pan(step, 0); }, ArrowRight: function(){ pan(-step, 0); }, ArrowUp: function(){ pan(0, step); }, ArrowDown: function(){ pan(0, -step); },
      '/': function(){ input.focus(); }};
    if(keys[ev.key]){ ev.preventDefault(); keys[ev.key](); }
  });
  var lastSize = size();
  fit();
})();
"""


def format_html(graph: Graph, svg: str, analysis: Analysis) -> str:
    """The page."""

    counts = analysis.counts()
    data = {'vertices': {vid: {'kind': v.kind, 'name': v.name, 'details': v.details,
                               'findings': v.findings, 'defined': v.defined}
                         for vid, v in graph.vertices.items()},
            'edges': [[e.source, e.target] for e in graph.edges],
            'clusters': {cid: {'name': c.name, 'parent': c.parent, 'vertices': c.vertices,
                               'children': c.children} for cid, c in graph.clusters.items()}}
    ids_by_name = {v.name: vid for vid, v in graph.vertices.items() if v.kind == 'node'}
    items = []
    for finding in analysis.findings:
        target = ids_by_name.get(finding.nodes[0]) if finding.nodes else None
        link = (f' <a data-id="{_h(target)}">{_h(finding.nodes[0])}</a>'
                if target else '')
        d = finding.diagnostic
        where = f'{d.file}:{d.line}:{d.column}' if d.line else d.file
        items.append(f'<div class="finding {d.severity.value}"><div class="code">'
                     f'{_h(d.severity.value.upper())} {_h(finding.kind)} '
                     f'[{_h(d.code)}]{link}</div><div>{_h(d.message)}</div>'
                     f'<div class="where">{_h(where)}</div></div>')
    pills = ''.join(f'<span class="pill {k}">{n} {k}{"s" if n != 1 and k != "info" else ""}</span>'
                    for k, n in counts.items())
    title = _h(graph.title)
    return f"""<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<title>nodl analyse: {title}</title>
<style>{_CSS}</style>
</head>
<body>
<header><h1>System analysis</h1><span class="file">{title}</span>
<span class="hint">{_h(analysis.summary())}</span><div class="counts">{pills}</div></header>
<main>
<div id="canvas">{_inline_svg(svg)}
<div id="tools"><input id="search" type="search" placeholder="Search names (/)"
 aria-label="Search" autocomplete="off" spellcheck="false"><span id="found"></span>
<button data-do="fit" title="Fit the whole system in the window (0)">Fit</button>
<button data-do="zoom-in" title="Zoom in (+)">+</button><button data-do="zoom-out" title="Zoom out (-)">&minus;</button>
<button data-do="fold-all" title="Fold every namespace to one box">Fold all</button>
<button data-do="unfold-all" title="Unfold every namespace">Unfold all</button></div>
<div id="help">Drag to pan, wheel to zoom; click a namespace&#39;s name to fold it, a folded box to unfold it; Enter in the search goes to the next match</div>
</div>
<aside>
<div id="panel"><h2>Click a node</h2><div class="hint">Click a node, topic, service or action
to see its interface and its findings.</div>
<div class="legend"><span class="l-node">node</span><span class="l-topic">topic</span>
<span class="l-service">service</span><span class="l-action">action</span>
<span class="l-err">has an error</span><span class="l-undef">no definition</span></div></div>
<h3>All findings ({len(analysis.findings)})</h3>
<div id="all">{''.join(items) or '<div class="hint">none</div>'}</div>
</aside>
</main>
<script type="application/json" id="nodl-data">{json_for_script(data)}</script>
<script>{_JS}</script>
</body>
</html>
"""
