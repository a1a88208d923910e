"""The text of the documentation: README.md and the site's pages (ros/nodl_toolkit/doc)."""

from __future__ import annotations

from conftest import REPO

SITE = REPO / 'ros' / 'nodl_toolkit' / 'doc'


def page(name: str) -> str:
    """One page of the site, by its name without .md (``'guides/system-integrators'``)."""
    return (SITE / f'{name}.md').read_text(encoding='utf-8')


def pages() -> dict[str, str]:
    """README.md and every page of the site, by path relative to the repository."""
    paths = [REPO / 'README.md', *sorted(SITE.rglob('*.md'))]
    return {str(path.relative_to(REPO)): path.read_text(encoding='utf-8') for path in paths
            if 'examples/nodes' not in path.as_posix()}


def docs_text() -> str:
    """README.md and the site's pages, one after the other."""
    return '\n'.join(pages().values())
