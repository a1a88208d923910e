"""Launch Python: read without running it, into items with the exact text of each.

The module is parsed (:mod:`ast`), never run.  The items are the elements of the list a
``generate_launch_description`` returns as ``LaunchDescription([...])``: ``Node(...)``,
``ComposableNodeContainer(...)`` and ``GroupAction([...])`` calls are understood, every
other element is kept verbatim, and so is everything outside the list (imports, code,
comments).  A call's keywords with literal values (``package='...'``, ``parameters=[{...}]``,
``remappings=[('a', 'b')]``) are editable; every other keyword (a ``condition``, a value
computed by code) is kept verbatim.  A file that does not return such a list literally is
kept whole: it can be shown and analysed, not edited.
"""

from __future__ import annotations

import ast
from typing import Any

from nodl.composer.model import ComposedNode, Document, Group, Item, Kept, Param, Remap
from nodl.composer.rendering import reindent
from nodl.composer.values import python_value
from nodl.composer.xml_format import ReadError

__all__ = [
    'group_python',
    'imports_needed',
    'new_python',
    'node_python',
    'push_python',
    'read_python',
]

_NODE_KEYS = {'package': 'package', 'executable': 'executable', 'name': 'name',
              'namespace': 'namespace'}
_COMPOSABLE_KEYS = {'package': 'package', 'plugin': 'plugin', 'name': 'name',
                    'namespace': 'namespace'}
#: The names a written file needs, by the module they are imported from.
_IMPORTS = {'Node': 'launch_ros.actions', 'ComposableNodeContainer': 'launch_ros.actions',
            'PushRosNamespace': 'launch_ros.actions', 'GroupAction': 'launch.actions',
            'ComposableNode': 'launch_ros.descriptions', 'LaunchDescription': 'launch'}


def _call_name(node: ast.AST) -> str:
    if isinstance(node, ast.Call):
        func = node.func
        if isinstance(func, ast.Name):
            return func.id
        if isinstance(func, ast.Attribute):
            return func.attr
    return ''


class _Reader:
    def __init__(self, text: str) -> None:
        self.source = text
        self.lines = text.splitlines(keepends=True)
        self.starts = [0]
        for line in self.lines:
            self.starts.append(self.starts[-1] + len(line))
        self.count = 0

    def next_id(self, prefix: str) -> str:
        self.count += 1
        return f'{prefix}{self.count}'

    def offset(self, line: int, column: int) -> int:
        """The character index of ast's (line, UTF-8 byte column)."""
        text = self.lines[line - 1] if line - 1 < len(self.lines) else ''
        return self.starts[line - 1] + len(text.encode('utf-8')[:column].decode('utf-8', 'replace'))

    def span(self, node: ast.AST) -> tuple[int, int]:
        return (self.offset(node.lineno, node.col_offset),  # type: ignore[attr-defined]
                self.offset(node.end_lineno, node.end_col_offset))  # type: ignore[attr-defined]

    def text(self, node: ast.AST) -> str:
        start, end = self.span(node)
        return self.source[start:end]

    def column(self, node: ast.AST) -> int:
        start, _ = self.span(node)
        return start - (self.source.rfind('\n', 0, start) + 1)

    def items(self, elements: list[ast.expr], after: int) -> tuple[list[Item], int, bool]:
        """The items of a list's elements, the index after the last, and whether the list
        ends with a comma (separators are not part of the gaps)."""
        out: list[Item] = []
        for index, element in enumerate(elements):
            start, end = self.span(element)
            gap = self.source[after:start]
            if index:
                gap = _drop_comma(gap)
            item = self.item(element)
            item.gap = gap
            out.append(item)
            after = end
        return out, after, False

    def item(self, element: ast.expr) -> Item:
        name = _call_name(element)
        line, column = element.lineno, self.column(element)
        if name == 'Node':
            return self.node(element, 'node')  # type: ignore[arg-type]
        if name == 'ComposableNodeContainer':
            return self.node(element, 'container')  # type: ignore[arg-type]
        if name == 'GroupAction' and isinstance(element, ast.Call) and element.args \
                and isinstance(element.args[0], ast.List):
            return self.group(element)
        return Kept(self.text(element), 'Python code', line, column=column)

    def group(self, call: ast.Call) -> Item:
        listed = call.args[0]
        assert isinstance(listed, ast.List)
        if not listed.elts:
            return Kept(self.text(call), 'GroupAction', call.lineno, column=self.column(call))
        start, end = self.span(call)
        list_start, list_end = self.span(listed)
        group = Group(self.next_id('g'), None, line=call.lineno,
                      indent=' ' * self.column(call), original=self.source[start:end])
        group.conditional = any(k.arg == 'condition' for k in call.keywords)
        group.open_text = self.source[start:list_start + 1]
        group.items, last, _ = self.items(list(listed.elts), list_start + 1)
        tail = self.source[last:list_end - 1]
        trailing = tail.lstrip().startswith(',')
        group.style['trailing_separator'] = trailing
        group.close_gap = _drop_comma(tail) if trailing else tail
        group.close_text = self.source[list_end - 1:end]
        for element in listed.elts:
            if _call_name(element) == 'PushRosNamespace' and isinstance(element, ast.Call):
                value = element.args[0] if element.args else next(
                    (k.value for k in element.keywords if k.arg == 'namespace'), None)
                if isinstance(value, ast.Constant) and isinstance(value.value, str):
                    group.namespace = value.value
                else:
                    group.namespace_unknown = True
        return group

    def node(self, call: ast.Call, kind: str) -> ComposedNode:
        keys = _COMPOSABLE_KEYS if kind == 'composable' else _NODE_KEYS
        fields: dict[str, str] = {}
        node = ComposedNode(self.next_id('n'), kind, '', None, line=call.lineno,
                            indent=' ' * self.column(call))
        node.original = self.text(call)
        node.style['call'] = self.text(call.func)
        reasons: list[str] = []
        # written back in this order
        node.style['keys'] = [keyword.arg or '**' for keyword in call.keywords]
        for argument in call.args:
            node.extra.append(Kept(self.text(argument), 'a positional argument',
                                   argument.lineno, column=self.column(argument)))
        for keyword in call.keywords:
            value = keyword.value
            whole = Kept(self.source[self.span(keyword)[0]:self.span(value)[1]]
                         if keyword.arg is not None else self.text(keyword),
                         f'{keyword.arg or "**"}=', keyword.lineno,
                         column=self.column(keyword))
            if keyword.arg in keys:
                if isinstance(value, ast.Constant) and isinstance(value.value, str):
                    fields[keyword.arg] = value.value
                else:
                    reasons.append(f'its {keyword.arg} is computed by code')
                    node.extra.append(whole)
            elif keyword.arg == 'parameters' and isinstance(value, ast.List):
                for element in value.elts:
                    node.params.extend(self.params(element))
                node.style['params_written'] = True
            elif keyword.arg == 'remappings' and isinstance(value, ast.List):
                for element in value.elts:
                    node.remaps.append(self.remap(element))
            elif keyword.arg == 'composable_node_descriptions' and kind == 'container' \
                    and isinstance(value, ast.List):
                for element in value.elts:
                    if _call_name(element) == 'ComposableNode' and isinstance(element, ast.Call):
                        node.children.append(self.node(element, 'composable'))
                    else:
                        node.extra.append(Kept(self.text(element), 'a composable node',
                                               element.lineno, column=self.column(element)))
            else:
                if keyword.arg == 'remappings':
                    node.style['remaps_computed'] = True
                if keyword.arg == 'condition':
                    reasons.append('a condition decides whether it is launched')
                node.extra.append(whole)
        node.package = fields.get('package', '')
        node.executable = fields.get('executable') if kind != 'composable' else None
        node.plugin = fields.get('plugin') if kind == 'composable' else None
        node.name, node.namespace = fields.get('name'), fields.get('namespace')
        if not node.package or not (node.executable or node.plugin):
            reasons.append('it gives no literal package or executable')
        if reasons:
            node.editable, node.read_only_reason = False, '; '.join(reasons)
        return node

    def params(self, element: ast.expr) -> list[Param | Kept]:
        if isinstance(element, ast.Dict) and all(
                isinstance(k, ast.Constant) and isinstance(k.value, str) for k in element.keys):
            try:
                values = [ast.literal_eval(v) for v in element.values]
            except ValueError:
                values = None
            if values is not None and all(_parameter_value(v) for v in values):
                return [Param(k.value, v, None) for k, v in  # type: ignore[union-attr]
                        zip(element.keys, values, strict=True)]
        return [Kept(self.text(element), 'a parameter source computed by code',
                     element.lineno, column=self.column(element))]

    def remap(self, element: ast.expr) -> Remap | Kept:
        if isinstance(element, ast.Tuple) and len(element.elts) == 2 and all(
                isinstance(e, ast.Constant) and isinstance(e.value, str) for e in element.elts):
            first, second = element.elts
            return Remap(first.value, second.value, None)  # type: ignore[attr-defined]
        return Kept(self.text(element), 'a remapping rule computed by code', element.lineno,
                    column=self.column(element))


def _parameter_value(value: Any) -> bool:
    if isinstance(value, list):
        return all(isinstance(v, (bool, int, float, str)) for v in value)
    return isinstance(value, (bool, int, float, str))


def _drop_comma(gap: str) -> str:
    stripped = gap.lstrip()
    if stripped.startswith(','):
        at = len(gap) - len(stripped)
        return gap[:at] + gap[at + 1:]
    return gap


def _description_list(tree: ast.Module) -> ast.List | None:
    """The list of ``return LaunchDescription([...])`` in ``generate_launch_description``."""
    for statement in tree.body:
        if isinstance(statement, ast.FunctionDef) and statement.name == 'generate_launch_description':
            returns = [n for n in ast.walk(statement) if isinstance(n, ast.Return)]
            if len(returns) != 1:
                return None
            value = returns[0].value
            if value is not None and _call_name(value) == 'LaunchDescription' and isinstance(value, ast.Call) \
                    and len(value.args) == 1 and isinstance(value.args[0], ast.List) \
                    and not value.keywords:
                return value.args[0]
    return None


def read_python(text: str) -> Document:
    """The items of a Python launch file (ReadError for a syntax error or no
    ``generate_launch_description``); never runs it."""
    try:
        tree = ast.parse(text)
    except SyntaxError as exc:
        raise ReadError(f'a Python syntax error: {exc.msg}', exc.lineno or 0,
                        exc.offset or 0) from None
    if not any(isinstance(s, ast.FunctionDef) and s.name == 'generate_launch_description'
               for s in tree.body):
        raise ReadError('a Python launch file defines generate_launch_description()', 1, 1)
    reader = _Reader(text)
    listed = _description_list(tree)
    doc_style: dict[str, Any] = {'imported': _imported(tree)}
    imports = [s for s in tree.body if isinstance(s, (ast.Import, ast.ImportFrom))]
    if imports:
        doc_style['import_at'] = reader.span(imports[-1])[1]
    if listed is None:
        doc = Document('python', text, [], '', '')
        doc.style.update(doc_style, opaque=True)
        return doc
    start, end = reader.span(listed)
    items, last, _ = reader.items(list(listed.elts), start + 1)
    tail = text[last:end - 1]
    trailing = tail.lstrip().startswith(',')
    doc = Document('python', text[:start + 1], items, _drop_comma(tail) if trailing else tail,
                   text[end - 1:])
    # an empty list has no separator to follow: the items written into it end with a comma,
    # as in a new file
    doc.style.update(doc_style, trailing_separator=trailing or not items)
    first = next(iter(items), None)
    if first is not None:
        doc.indent = first.indent if not isinstance(first, Kept) else ' ' * first.column
    else:  # one level deeper than the line the list opens on (not than the bracket's column)
        line = text[text.rfind('\n', 0, start) + 1:start]
        doc.indent = ' ' * (len(line) - len(line.lstrip()) + 4)
    doc.style['next_id'] = reader.count
    return doc


def _imported(tree: ast.Module) -> list[str]:
    names = []
    for statement in tree.body:
        if isinstance(statement, ast.ImportFrom):
            names += [a.asname or a.name for a in statement.names]
    return names


_NEW = '''"""A launch file written by nodl system."""

from launch import LaunchDescription
{imports}


def generate_launch_description():
    return LaunchDescription(['''


def new_python() -> Document:
    """An empty Python launch document."""
    doc = Document('python', _NEW, [], '\n    ', '])\n', indent='        ')
    doc.style.update(imported=['LaunchDescription'], trailing_separator=True, fresh=True)
    return doc


def imports_needed(doc: Document, used: set[str]) -> str:
    """The import lines of the names ``used`` that the module does not import yet."""
    missing = sorted(n for n in used if n not in doc.style.get('imported', []))
    by_module: dict[str, list[str]] = {}
    for name in missing:
        by_module.setdefault(_IMPORTS[name], []).append(name)
    return ''.join(f'from {module} import {", ".join(names)}\n'
                   for module, names in sorted(by_module.items()))


def _literal_text(value: Any) -> str:
    return python_value(value)


def node_python(node: ComposedNode, indent: str) -> str:
    """A ``Node(...)``, ``ComposableNodeContainer(...)`` or ``ComposableNode(...)`` call, written
    anew from the model; its kept arguments as read, and its keywords in the order the file gave
    them (an edit moves nothing else)."""
    inner = indent + '    '
    call = node.style.get('call') or {'node': 'Node', 'container': 'ComposableNodeContainer',
                                      'composable': 'ComposableNode'}[node.kind]
    fields: list[tuple[str, str | None]] = [('package', node.package)]
    fields += [('plugin', node.plugin)] if node.kind == 'composable' else \
        [('executable', node.executable)]
    # (launch_ros's container takes its namespace as a required keyword)
    namespace = '' if node.namespace is None and node.kind == 'container' else node.namespace
    fields += [('name', node.name), ('namespace', namespace)]
    # keyword -> its text (without the line break, indentation and comma around it)
    chunks = {key: f'{key}={_literal_text(value)}' for key, value in fields if value is not None}
    if node.params or node.style.get('params_written'):
        parts: list[str] = []
        pending: list[Param] = []

        def flush() -> None:
            if pending:
                parts.append('{' + ', '.join(f'{_literal_text(p.name)}: {_literal_text(p.value)}'
                                             for p in pending) + '}')
                pending.clear()
        for param in node.params:
            if isinstance(param, Kept):
                flush()
                parts.append(reindent(param.text, param.column, inner + '    '))
            else:
                pending.append(param)
        flush()
        chunks['parameters'] = 'parameters=[' + ', '.join(parts) + ']'
    if node.remaps:
        chunks['remappings'] = 'remappings=[' + ', '.join(
            reindent(r.text, r.column, inner) if isinstance(r, Kept)
            else f'({_literal_text(r.source)}, {_literal_text(r.target)})'
            for r in node.remaps) + ']'
    positional = [reindent(k.text, k.column, inner) for k in node.extra
                  if k.what == 'a positional argument']
    in_list = [k for k in node.extra if k.what == 'a composable node']
    keywords = [(k.what[:-1], reindent(k.text, k.column, inner)) for k in node.extra
                if k.what not in ('a positional argument', 'a composable node')]
    listed = bool(node.children or in_list)
    order = [k for k in node.style.get('keys', [])
             if k in chunks or any(key == k for key, _ in keywords)
             or (k == 'composable_node_descriptions' and listed)]
    order += [k for k in ('package', 'plugin', 'executable', 'name', 'namespace', 'parameters',
                          'remappings') if k in chunks and k not in order]
    order += [key for key, _ in keywords if key not in order]
    if listed and 'composable_node_descriptions' not in order:
        order.append('composable_node_descriptions')
    if not listed:
        compact = _compact(node, indent, call, positional + [
            text for key in dict.fromkeys(order)
            for text in ([chunks[key]] if key in chunks else []) +
            [t for what, t in keywords if what == key]])
        if compact is not None:
            return compact
    out = [f'{call}(']
    for text in positional:
        out.append(f'\n{inner}{text},')
    for key in dict.fromkeys(order):
        if key == 'composable_node_descriptions':
            _children_python(node, inner, in_list, out)
            continue
        if key in chunks:
            out.append(f'\n{inner}{chunks[key]},')
        out.extend(f'\n{inner}{text},' for what, text in keywords if what == key)
    out.append(f'\n{indent})')
    return ''.join(out)


#: The longest line a call written as the file wrote it (arguments on its first line) may have,
#: unless the file's own call has longer ones.
_WIDTH = 99


def _compact(node: ComposedNode, indent: str, call: str, arguments: list[str]) -> str | None:
    """The call as the file wrote it when its arguments began on its first line (``Node(package=
    ..., name=...,`` wrapped under the parenthesis): the arguments filled in that way; None when
    the file wrote it one argument a line, or never (a new node), or an argument spans lines."""
    original = node.original
    if original is None or original.startswith(f'{call}(\n') or \
            any('\n' in text for text in arguments):
        return None
    first, *rest = original.splitlines()
    width = max(_WIDTH, len(indent) + len(first), *(len(line) for line in rest))
    hanging = indent + ' ' * (len(call) + 1)
    lines, line = [], f'{indent}{call}('
    for index, text in enumerate(arguments):
        piece = text + (', ' if index < len(arguments) - 1 else ')')
        if line.strip() and not line.endswith('(') and len(line + piece.rstrip()) > width:
            lines.append(line.rstrip())
            line = hanging
        line += piece
    lines.append(line if arguments else line + ')')
    return '\n'.join(lines)[len(indent):]


def _children_python(node: ComposedNode, inner: str, kept: list[Kept], out: list[str]) -> None:
    """A container's ``composable_node_descriptions=[...]`` appended to ``out`` (the call's
    text so far): its composable nodes, then those written by code, as read."""
    out.append(f'\n{inner}composable_node_descriptions=[')
    lines_before = ''.join(out).count('\n')
    child_indent = inner + '    '
    for child in node.children:
        if child.dirty or child.original is None:
            child_text = node_python(child, child_indent)
        else:
            child_text = reindent(child.original, len(child.indent), child_indent)
        child.style['written_at'] = lines_before + 1
        child.style['written_lines'] = child_text.count('\n')
        out.append(f'\n{child_indent}{child_text},')
        lines_before += 1 + child_text.count('\n')
    out.extend(f'\n{child_indent}{reindent(k.text, k.column, child_indent)},' for k in kept)
    out.append(f'\n{inner}],')


def group_python(group: Group, indent: str) -> tuple[str, str]:
    """A group's opening and closing text (a new group: ``GroupAction([`` ... ``])``)."""
    if group.original is not None:
        return group.open_text, group.close_text
    return 'GroupAction([', '])'


def push_python(namespace: str) -> str:
    """A ``PushRosNamespace(...)`` element."""
    return f'PushRosNamespace({_literal_text(namespace)})'
