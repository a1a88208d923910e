"""The YAML launch frontend: ``launch:`` holding a list of one-key mappings (entities).

The text is first read by the toolkit's YAML frontend (libyaml events, duplicate keys, the
depth and alias limits, the 10 MB limit); then the node tree gives each entity and
attribute its line and column.  A key whose value is a list of mappings (``param``,
``remap``, ``arg``...) is a nested entity list; ``children`` (or a list as the entity's
whole value) holds child actions.
"""

from __future__ import annotations

from typing import Any

from nodl.diagnostics import Diagnostic, Severity
from nodl.launch.actions import LaunchDescription
from nodl.launch.markup_actions import FrontendEntity, build_description

__all__ = ['read_yaml_launch']


def read_yaml_launch(path: str) -> tuple[LaunchDescription | None, list[Diagnostic]]:
    """Read a YAML launch file (problems as diagnostics)."""
    from yaml.nodes import MappingNode, ScalarNode, SequenceNode

    from nodl.frontends.source import SourceText, decode, read_limited
    from nodl.frontends.yaml_json import parse_document

    try:
        text, problem = decode(read_limited(path), path)
    except OSError as exc:
        return None, [Diagnostic(Severity.ERROR, f'cannot read the launch file: {exc.strerror}', (), path,
                                 code='NODL515')]
    if text is None:
        assert problem is not None
        return None, [problem]
    doc = parse_document(SourceText(text, path))
    if doc.diagnostics:
        return None, list(doc.diagnostics)
    problems: list[Diagnostic] = []
    root = doc._node_tree()
    if not isinstance(root, MappingNode) or len(root.value) != 1:
        return None, [Diagnostic(Severity.ERROR, "a YAML launch file is one mapping with the key 'launch'",
                                 (), path, 1, 1, code='NODL501')]

    def at(node: Any) -> tuple[int, int]:
        return node.start_mark.line + 1, node.start_mark.column + 1

    def entity(tag: str, key_node: Any, value_node: Any, data: Any) -> FrontendEntity:
        line, column = at(key_node)
        result = FrontendEntity(tag, path, line, column, yaml=True)
        if isinstance(value_node, SequenceNode):  # the entity's value is its child list
            result.children = entities(value_node, data)
            return result
        if not isinstance(value_node, MappingNode):
            if not (isinstance(value_node, ScalarNode) and value_node.value in ('', '~', 'null')):
                problems.append(Diagnostic(Severity.ERROR, f"'{tag}' must hold a mapping of attributes",
                                           (), path, *at(value_node), code='NODL504'))
            return result
        for k, v in value_node.value:
            name = k.value
            value = data.get(name) if isinstance(data, dict) else None
            if name == 'children' and isinstance(v, SequenceNode):
                result.children = entities(v, value)
            elif isinstance(v, SequenceNode) and v.value and isinstance(v.value[0], MappingNode):
                result.nested[name] = [entity(name, item, item, d) for item, d in
                                       zip(v.value, value if isinstance(value, list) else [], strict=False)]
            else:
                result.values[name] = value
                result.positions[name] = at(k)
        return result

    def entities(sequence: Any, data: Any) -> list[FrontendEntity]:
        out = []
        for item, item_data in zip(sequence.value, data if isinstance(data, list) else [], strict=False):
            if not isinstance(item, MappingNode) or len(item.value) != 1:
                problems.append(Diagnostic(Severity.ERROR, 'an entity is a mapping with exactly one key, '
                                           'its tag (- node: {...})', (), path, *at(item), code='NODL504'))
                continue
            (k, v), = item.value
            out.append(entity(str(k.value), k, v, item_data.get(k.value) if isinstance(item_data, dict) else None))
        return out

    (key, value), = root.value
    top = FrontendEntity(str(key.value), path, *at(key), yaml=True)
    if isinstance(value, SequenceNode):
        top.children = entities(value, doc.data.get(key.value) if isinstance(doc.data, dict) else None)
    elif not (isinstance(value, ScalarNode) and value.value in ('', '~', 'null')):
        problems.append(Diagnostic(Severity.ERROR, "'launch' must hold a list of entities", (), path,
                                   *at(value), code='NODL504'))
    return build_description(top, problems), problems
