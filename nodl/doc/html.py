"""Pages as self-contained HTML: one file each, readable offline.

The style sheet is in the page, the graph's SVG is inline, links are
relative; nothing is fetched.  Every text from a definition is escaped
(``&``, ``<``, ``>``, quotes) after control and bidirectional characters are
made visible (:func:`nodl.text_safety.visible`).
"""

from __future__ import annotations

from html import escape as _escape

from nodl.doc.blocks import (
    Code,
    Heading,
    Inline,
    Link,
    Literal,
    Note,
    Page,
    Paragraph,
    Picture,
    Table,
    href,
)
from nodl.text_safety import visible

__all__ = ['render_html', 'escape', 'STYLE']

#: The page's style sheet.
STYLE = """
body { font-family: system-ui, -apple-system, 'Segoe UI', sans-serif; margin: 2rem auto;
       max-width: 80rem; padding: 0 1.5rem; color: #1d2430; line-height: 1.45; }
h1 { border-bottom: 2px solid #2d6cdf; padding-bottom: .3rem; }
h2 { margin-top: 2rem; border-bottom: 1px solid #d5dbe3; padding-bottom: .2rem; }
table { border-collapse: collapse; margin: .6rem 0 1rem; width: 100%; font-size: .92rem; }
th, td { border: 1px solid #d5dbe3; padding: .3rem .5rem; text-align: left; vertical-align: top; }
th { background: #eef2f8; }
tr:nth-child(even) td { background: #f8fafc; }
code, pre { font-family: ui-monospace, 'DejaVu Sans Mono', monospace; font-size: .88rem; }
code { background: #eef2f8; padding: 0 .2rem; border-radius: 3px; overflow-wrap: break-word; }
pre { background: #f4f6fa; border: 1px solid #d5dbe3; padding: .7rem; overflow-x: auto; }
.warning { border-left: 4px solid #e08a00; background: #fff6e5; padding: .5rem .8rem; margin: .6rem 0; }
.note { border-left: 4px solid #2d6cdf; background: #eef4ff; padding: .5rem .8rem; margin: .6rem 0; }
figure { margin: 1rem 0; overflow-x: auto; }
figure svg { max-width: 100%; height: auto; }
a { color: #1f5bc4; }
""".strip()


def escape(text: str) -> str:
    """``text`` as HTML text (or attribute value)."""
    return _escape(visible(text), quote=True)


def _inline(parts: tuple[Inline, ...], here: str) -> str:
    out = []
    for part in parts:
        if isinstance(part, Link):
            out.append(f'<a href="{escape(href(here, part, ".html"))}">{escape(part.text)}</a>')
        elif isinstance(part, Literal):
            out.append(f'<code>{escape(part.text)}</code>')
        else:
            out.append(escape(part))
    return ''.join(out)


def _svg(svg: str) -> str:
    """The SVG document's ``<svg>`` element (no XML declaration or doctype inside HTML)."""
    start = svg.find('<svg')
    return svg[start:].strip() if start >= 0 else ''


def render_html(page: Page) -> str:
    """The page as one self-contained HTML document."""
    body: list[str] = []
    for block in page.blocks:
        if isinstance(block, Heading):
            body.append(f'<h{block.level} id="{block.label}">{escape(block.text)}</h{block.level}>')
        elif isinstance(block, Paragraph):
            body.append(f'<p>{_inline(block.parts, page.path)}</p>')
        elif isinstance(block, Table):
            head = ''.join(f'<th>{escape(c)}</th>' for c in block.columns)
            rows = ''.join('<tr>' + ''.join(f'<td>{_inline(cell, page.path)}</td>' for cell in row)
                           + '</tr>\n' for row in block.rows)
            body.append(f'<table>\n<thead><tr>{head}</tr></thead>\n<tbody>\n{rows}</tbody>\n</table>')
        elif isinstance(block, Code):
            body.append(f'<pre><code class="language-{escape(block.language)}">'
                        f'{escape(block.text.rstrip())}</code></pre>')
        elif isinstance(block, Note):
            body.append(f'<div class="{block.kind}" role="note">{_inline(block.parts, page.path)}</div>')
        elif isinstance(block, Picture):
            body.append(f'<figure role="img" aria-label="{escape(block.alt)}">\n{_svg(block.svg)}\n'
                        '</figure>')
    return ('<!DOCTYPE html>\n<html lang="en">\n<head>\n<meta charset="utf-8">\n'
            '<meta name="viewport" content="width=device-width, initial-scale=1">\n'
            f'<title>{escape(page.title)}</title>\n<style>\n{STYLE}\n</style>\n</head>\n<body>\n'
            + '\n'.join(body) + '\n</body>\n</html>\n')
