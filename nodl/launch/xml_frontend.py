"""The XML launch frontend, read with the toolkit's safe XML parser.

:func:`~nodl.frontends.xml_reader.load_xml` (expat, positions for every element and
attribute, no DTDs and no entities, the 10 MB size limit and UTF-8) gives the tree; this module
turns elements into :class:`~nodl.launch.markup_actions.FrontendEntity` objects: the child elements a
tag lists as nested (``param``, ``remap``, ``arg``...) go to ``nested``, the others are actions.
"""

from __future__ import annotations

from pathlib import Path

from nodl.diagnostics import Diagnostic, Severity
from nodl.frontends.xml_reader import XmlElement, load_xml
from nodl.launch.actions import LaunchDescription
from nodl.launch.errors import MAX_XML_DEPTH
from nodl.launch.markup_actions import NESTED, TAGS, FrontendEntity, build_description

__all__ = ['read_xml_launch']

#: Tag -> the child tags it holds as nested entity lists (the others are actions).
_LISTS = {tag: TAGS.get(tag, (None, (), None))[1] or NESTED.get(tag, ((), ()))[1] for tag in (*TAGS, *NESTED)}


def read_xml_launch(path: str) -> tuple[LaunchDescription | None, list[Diagnostic]]:
    """Read an XML launch file (problems as diagnostics, never an exception for its content)."""
    problems: list[Diagnostic] = []
    try:
        tree = load_xml(Path(path), path)
    except OSError as exc:
        return None, [Diagnostic(Severity.ERROR, f'cannot read the launch file: {exc.strerror}', (), path,
                                 code='NODL515')]
    problems.extend(tree.diagnostics)
    if tree.root is None or any(d.severity is Severity.ERROR for d in tree.diagnostics):
        return None, problems

    too_deep: list[XmlElement] = []
    root = _convert(tree.root, 1, path, too_deep)
    if too_deep:
        # One diagnostic, at the last element too deep (where it has always been reported: the
        # former separate depth check walked the tree from its end).
        element = too_deep[-1]
        problems.append(Diagnostic(Severity.ERROR, f'the launch file nests deeper than {MAX_XML_DEPTH} '
                                   'levels', (), path, element.line, element.column, code='NODL009'))
        return None, problems
    if root is None:
        return None, problems
    return build_description(root, problems), problems


def _convert(element: XmlElement, depth: int, path: str, too_deep: list[XmlElement]) -> FrontendEntity | None:
    """The entity of ``element`` and its children (the elements too deep to enter are noted in
    ``too_deep``).  Recursive, but never deeper than MAX_XML_DEPTH + 1 (expat itself reads any
    depth): an element below that is noted, not entered."""
    if depth > MAX_XML_DEPTH:
        too_deep.append(element)
        return None
    entity = FrontendEntity(element.tag, path, element.line, element.column)
    # The values by name; the element places an attribute only when the entity asks where
    # it is (a problem, a recorded place), so a launch file without problems places none.
    pairs = iter(element.pairs)
    entity.values = dict(zip(pairs, pairs, strict=False))
    entity.element = element
    if element.children:
        lists = _LISTS.get(element.tag, ())
        for child in element.children:
            converted = _convert(child, depth + 1, path, too_deep)
            if converted is None:
                continue
            if child.tag in lists:
                entity.nested.setdefault(child.tag, []).append(converted)
            else:
                entity.children.append(converted)
    return entity
