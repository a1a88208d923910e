"""A self-contained HTML page: the SVG inline, the data as JSON, a little CSS and JS.

Nothing is fetched: no fonts, scripts or styles from the network.  Clicking a
node (or a topic, service or action) shows its interface and its findings in
the side panel; the findings list below links back to the picture.
"""

from __future__ import annotations

import html
import json
import re

from nodl_schema.analysis.graph.model import Graph
from nodl_schema.analysis.system import Analysis
from nodl_schema.text_safety import visible

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
    """The ``<svg>`` element alone (no XML declaration, DOCTYPE or comments)."""
    start = svg.find('<svg')
    svg = svg[start:] if start >= 0 else svg
    svg = re.sub(r'<!--.*?-->', '', svg, flags=re.S)
    # scale to the panel (the viewBox keeps the proportions), but never below 60% of the
    # natural size: a wide system scrolls instead of shrinking its labels to unreadable dots
    def sized(match: re.Match[str]) -> str:
        number = re.match(r'[\d.]+', match.group(2))
        least = f' style="min-width:{float(number.group()) * 0.6:.0f}pt"' if number else ''
        return f'<svg{match.group(1)}{least}'
    return re.sub(r'<svg([^>]*?)\swidth="([^"]*)"\s+height="[^"]*"', sized, svg, count=1)


_CSS = """
*{box-sizing:border-box}
body{margin:0;font:14px/1.45 system-ui,-apple-system,"Segoe UI",Roboto,Helvetica,Arial,sans-serif;color:#202124;background:#f8f9fa}
header{display:flex;align-items:center;gap:16px;padding:10px 20px;background:#fff;border-bottom:1px solid #dadce0}
header h1{font-size:17px;margin:0;font-weight:600}
header .file{color:#5f6368;font-family:ui-monospace,Menlo,Consolas,monospace;font-size:13px}
.counts{margin-left:auto;display:flex;gap:8px}
.pill{border-radius:12px;padding:2px 10px;font-size:12px;font-weight:600;background:#e8eaed}
.pill.error{background:#fce8e6;color:#c5221f}.pill.warning{background:#fef7e0;color:#b06000}.pill.info{background:#e8f0fe;color:#1967d2}
main{display:grid;grid-template-columns:1fr 380px;height:calc(100vh - 50px)}
#canvas{overflow:auto;background:#fff;position:relative}
#canvas svg{width:100%;height:auto;display:block}
#canvas g.node,#canvas g.edge{cursor:pointer}
#canvas g.node.selected polygon,#canvas g.node.selected ellipse{stroke:#1a73e8;stroke-width:3.5}
#canvas g.dim{opacity:.25}
aside{border-left:1px solid #dadce0;background:#fff;overflow:auto;padding:16px 18px}
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
  var svg = document.querySelector('#canvas svg');
  function el(tag, cls, text){var e=document.createElement(tag); if(cls) e.className=cls; if(text!==undefined) e.textContent=text; return e;}
  function row(t, k, v){var tr=el('tr'); tr.appendChild(el('td','k',k)); var td=el('td'); var c=el('code',null,v); td.appendChild(c); tr.appendChild(td); t.appendChild(tr);}
  function findingBox(f){
    var d=el('div','finding '+f.severity);
    d.appendChild(el('div','code',f.severity.toUpperCase()+' '+f.kind+' ['+f.code+']'));
    d.appendChild(el('div',null,f.message));
    if(f.file) d.appendChild(el('div','where',f.file+(f.line?':'+f.line+':'+f.column:'')));
    return d;
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
      var eps=d.endpoints||{};
      Object.keys(eps).forEach(function(section){
        panel.appendChild(el('h3',null,section.replace(/_/g,' ')));
        var t2=el('table'); eps[section].forEach(function(p){row(t2,p[0],p[1]);}); panel.appendChild(t2);
      });
      var ps=d.parameters||{}; var keys=Object.keys(ps);
      if(keys.length){panel.appendChild(el('h3',null,'parameters')); var t3=el('table'); keys.forEach(function(k){row(t3,k,JSON.stringify(ps[k]));}); panel.appendChild(t3);}
      if((d.remaps||[]).length){panel.appendChild(el('h3',null,'remaps')); var t4=el('table'); d.remaps.forEach(function(r){row(t4,r[0],r[1]);}); panel.appendChild(t4);}
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
  svg.querySelectorAll('g.node').forEach(function(g){ g.addEventListener('click', function(ev){ ev.stopPropagation(); show(g.id); }); });
  svg.addEventListener('click', function(){ svg.querySelectorAll('g').forEach(function(g){g.classList.remove('dim','selected');}); });
  document.querySelectorAll('#all a[data-id]').forEach(function(a){ a.addEventListener('click', function(){ show(a.getAttribute('data-id')); }); });
})();
"""


def format_html(graph: Graph, svg: str, analysis: Analysis) -> str:
    """The page."""
    from nodl_schema.analysis.report import summary

    counts = analysis.counts()
    data = {'vertices': {vid: {'kind': v.kind, 'name': v.name, 'details': v.details,
                               'findings': v.findings, 'defined': v.defined}
                         for vid, v in graph.vertices.items()},
            'edges': [[e.source, e.target] for e in graph.edges]}
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
<span class="hint">{_h(summary(analysis))}</span><div class="counts">{pills}</div></header>
<main>
<div id="canvas">{_inline_svg(svg)}</div>
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
