"""What a file given as a launch file is, when it plainly is something else.

``nodl analyse`` reads launch files; given a NoDL node definition, a parameter file, a
``package.xml`` or any other text, the user should hear what the file is rather than a
launch-syntax error about its first line.  :func:`not_a_launch_file` says it, or returns
None for a file that is (or may be) a launch file: its own reader then reports what is wrong.
"""

from __future__ import annotations

from typing import Any

__all__ = ['not_a_launch_file']

#: Names a launch file has (anything else is read by content).
_LAUNCH_NAMES = ('.launch.xml', '.launch.yaml', '.launch.yml', '.launch.py', '.launch')
#: The root element of an XML file that is not a launch file -> what the file is.
_XML_ROOTS = {'package': 'a package manifest (package.xml)',
              'policy': 'an SROS 2 policy',
              'interface': 'a legacy NoDL XML file',
              'node': 'a legacy NoDL XML file'}


def not_a_launch_file(path: str) -> str | None:
    """``'a NoDL node definition'`` (and the like) when the file at ``path`` is plainly not a
    launch file; None when it is, may be, or cannot be read (the reader says why)."""
    from nodl.frontends.source import decode, read_limited

    try:
        data = read_limited(path)
    except OSError:
        return None
    text, _ = decode(data, path)
    if text is None:
        return None
    named = path.lower().endswith(_LAUNCH_NAMES)
    stripped = text.lstrip('\ufeff \t\r\n')
    if path.lower().endswith('.py'):
        if 'generate_launch_description' in text:
            return None
        return 'a Python file without generate_launch_description()'
    if stripped.startswith('<'):
        return _xml_kind(path, text, named)
    return _yaml_kind(path, text, named)


def _xml_kind(path: str, text: str, named: bool) -> str | None:
    import re

    # the first element (after the declaration, comments and a doctype): its name decides
    body = re.sub(r'<\?.*?\?>|<!--.*?-->|<!DOCTYPE[^>]*>', '', text, flags=re.S).lstrip()
    found = re.match(r'<([A-Za-z_][\w.:-]*)', body)
    root = found.group(1).rpartition(':')[2] if found else ''
    if root == 'launch' or named:
        return None
    return _XML_ROOTS.get(root, f'an XML file whose root element is <{root}>, not <launch>'
                          if root else None)


def _yaml_kind(path: str, text: str, named: bool) -> str | None:
    from nodl.frontends.source import SourceText
    from nodl.frontends.yaml_json import parse_document

    doc = parse_document(SourceText(text, path))
    data: Any = doc.data
    if doc.diagnostics or not isinstance(data, dict):
        if named:
            return None  # a launch file with an error: its reader says which
        return 'neither an XML, a YAML nor a Python launch file'
    if 'launch' in data:
        return None
    if 'nodl_version' in data:
        from nodl.validation.kinds import Kind, detect_kind

        kind = detect_kind(data)
        return {Kind.NODE: 'a NoDL node definition',
                Kind.INTERFACE: 'a NoDL interface definition'}.get(kind, 'a NoDL parameter definition')
    if data and all(_parameter_key(value) for value in data.values()):
        return 'a ROS parameter file'
    if named:
        return None
    keys = ', '.join(repr(str(k)) for k in list(data)[:3])
    return f"a YAML file without the key 'launch' (its keys: {keys})"


def _parameter_key(value: Any) -> bool:
    """True for a parameter file's node entry (``ros__parameters`` here or nested)."""
    if not isinstance(value, dict):
        return False
    return 'ros__parameters' in value or any(_parameter_key(v) for v in value.values())
