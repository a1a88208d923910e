"""Sphinx extension of the toolkit's documentation: pages generated at build time.

A page asks for generated text with a MyST comment line of its own::

    % nodl:generate verbs
    % nodl:generate schema node
    % nodl:generate codes

and the line is replaced, when Sphinx reads the page, by Markdown made from the
toolkit itself: the ``nodl`` argument parsers (``nodl.cli.main.build_parser``),
the JSON Schemas shipped in ``nodl/schemas/`` and the code catalogue of
``nodl/codes.py``. Nothing generated is kept in the source tree, so none of it can
go stale.  The node pages of the examples are written by ``nodl doc`` itself into
``examples/nodes/`` of the source folder when the build starts (that folder is
cleared first): build from a copy of this folder, as ``make docs`` and rosdoc2 do.
"""

from __future__ import annotations

import argparse
import json
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path
from typing import Any

MARKER = re.compile(r'^% nodl:generate (\w+)(?: (\S+))?[ \t]*$', re.M)
#: The examples whose node pages ``nodl doc`` writes into the site (relative to the repository).
EXAMPLES = ('examples/laser_driver.nodl.yaml', 'examples/camera_lifecycle.nodl.yaml')


def escape(text: str) -> str:
    """``text`` as literal Markdown text (no emphasis, links, roles or HTML)."""
    return re.sub(r'([\\`*_{}\[\]<>()#+!|$~])', r'\\\1', text)


def _one_line(text: str) -> str:
    return ' '.join(text.split())


# -- the verbs ---------------------------------------------------------------------------------


def _subcommands(parser: argparse.ArgumentParser) -> dict[str, argparse.ArgumentParser]:
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            return dict(action.choices)
    return {}


def _option_help(parser: argparse.ArgumentParser, action: argparse.Action) -> str:
    formatter = parser._get_formatter()
    text = formatter._expand_help(action) if action.help else ''
    return _one_line(text)


def _invocation(action: argparse.Action) -> str:
    if not action.option_strings:
        return action.metavar if isinstance(action.metavar, str) else action.dest
    if action.nargs == 0:
        return ', '.join(action.option_strings)
    metavar = action.metavar if isinstance(action.metavar, str) else action.dest.upper()
    return ', '.join(f'{option} {metavar}' for option in action.option_strings)


def verbs_markdown() -> str:
    """A section per verb of ``nodl``: its usage, description, arguments and epilog."""
    from nodl.cli.main import build_parser

    root = build_parser()
    verbs = _subcommands(root)
    by_parser: dict[int, list[str]] = {}
    for name, sub in verbs.items():
        by_parser.setdefault(id(sub), []).append(name)
    out: list[str] = []
    seen: set[int] = set()
    for name in sorted(verbs):
        sub = verbs[name]
        if id(sub) in seen:
            continue
        seen.add(id(sub))
        names = by_parser[id(sub)]
        primary = names[0]
        out += [f'(verb-{primary})=', f'## `nodl {primary}`', '']
        if len(names) > 1:
            out += ['Also spelt ' + ', '.join(f'`nodl {alias}`' for alias in names[1:]) + '.', '']
        usage = sub.format_usage().strip()
        if usage.startswith('usage: '):
            usage = usage[len('usage: '):]
        out += ['```text', usage, '```', '']
        if sub.description:
            out += [escape(paragraph) + '\n' for paragraph in
                    [_one_line(p) for p in sub.description.split('\n\n') if p.strip()]]
        for group in sub._action_groups:
            actions = [a for a in group._group_actions if a.help != argparse.SUPPRESS]
            if not actions:
                continue
            out += [f'**{escape(group.title or "arguments").capitalize()}**', '']
            for action in actions:
                help_text = _option_help(sub, action)
                out.append(f'- `{_invocation(action)}`' + (f': {escape(help_text)}' if help_text else ''))
            out.append('')
        if sub.epilog:
            out += ['```text', sub.epilog.strip('\n'), '```', '']
    return '\n'.join(out)


# -- the file formats --------------------------------------------------------------------------


def _type_of(schema: dict[str, Any], kind: str) -> str:
    if '$ref' in schema:
        document, _, pointer = schema['$ref'].partition('#')
        target = pointer.rsplit('/', 1)[-1]
        if document:
            kind = document.split('.', 1)[0]
        return f'{{ref}}`{target} <schema-{kind}-{target.replace("_", "-")}>`'
    if 'const' in schema:
        return '`' + json.dumps(schema['const']) + '`'
    if 'enum' in schema:
        return 'one of ' + ', '.join('`' + json.dumps(value) + '`' for value in schema['enum'])
    for key in ('oneOf', 'anyOf'):
        if key in schema:
            return ' or '.join(_type_of(choice, kind) for choice in schema[key])
    json_type = schema.get('type')
    if json_type == 'array':
        items = schema.get('items')
        return 'array of ' + (_type_of(items, kind) if isinstance(items, dict) else 'values')
    if json_type == 'object' and 'additionalProperties' in schema and \
            isinstance(schema['additionalProperties'], dict):
        return 'map of names to ' + _type_of(schema['additionalProperties'], kind)
    if isinstance(json_type, list):
        return ' or '.join(json_type)
    return str(json_type or 'any')


def _constraints(schema: dict[str, Any]) -> str:
    words = []
    for key, word in (('pattern', 'pattern'), ('minimum', 'at least'), ('maximum', 'at most'),
                      ('minLength', 'length at least'), ('maxLength', 'length at most'),
                      ('minItems', 'items at least'), ('maxItems', 'items at most'),
                      ('default', 'default')):
        if key in schema:
            words.append(f'{word} `{json.dumps(schema[key])}`')
    return '; '.join(words)


def _object_table(schema: dict[str, Any], kind: str) -> list[str]:
    properties = schema.get('properties', {})
    if not properties:
        return []
    required = set(schema.get('required', ()))
    out = ['| field | type | required | description |', '| --- | --- | --- | --- |']
    for name, prop in properties.items():
        description = escape(_one_line(prop.get('description', '')))
        extra = _constraints(prop)
        if extra:
            description = f'{description} ({extra})' if description else extra
        out.append(f'| `{name}` | {_type_of(prop, kind)} | {"yes" if name in required else "no"} | '
                   f'{description} |')
    out.append('')
    if schema.get('additionalProperties') is False:
        out += ['No other field is allowed.', '']
    patterns = schema.get('patternProperties', {})
    for pattern, prop in patterns.items():
        out += [f'Fields named like `{pattern}`: {_type_of(prop, kind)}.', '']
    return out


def _definition(name: str, schema: dict[str, Any], level: str, kind: str) -> list[str]:
    out = [f'(schema-{kind}-{name.replace("_", "-")})=', f'{level} `{name}`', '']
    if schema.get('description'):
        out += [escape(_one_line(schema['description'])), '']
    table = _object_table(schema, kind)
    if table:
        out += table
    else:
        out += [f'Type: {_type_of(schema, kind)}.', '']
        extra = _constraints(schema)
        if extra:
            out += [extra[0].upper() + extra[1:] + '.', '']
    return out


def schema_markdown(kind: str) -> str:
    """The fields of one kind of document, from ``nodl/schemas/KIND.schema.json``."""
    from nodl.schemas import load_schema

    schema = load_schema(kind)
    out = [f'Generated from `nodl/schemas/{kind}.schema.json` ({escape(schema.get("$id", ""))}); '
           f'`nodl schema {kind}` prints it bundled.', '']
    if schema.get('description'):
        out += [escape(_one_line(schema['description'])), '']
    if 'properties' in schema:
        out += ['## The document', '']
        out += _object_table(schema, kind)
    elif '$ref' in schema:
        out += [f'The document is one {_type_of(schema, kind)}.', '']
    definitions = schema.get('definitions') or schema.get('$defs') or {}
    for name, definition in definitions.items():
        out += _definition(name, definition, '##', kind)
    return '\n'.join(out)


# -- the codes ---------------------------------------------------------------------------------


def codes_markdown() -> str:
    """The code catalogue (the text of docs/diagnostics.md), its title left to the page."""
    from nodl.codes import catalogue_markdown

    text = catalogue_markdown()
    body = text.split('\n', 1)[1]  # the page has its own title
    # one level down, under the page's title; comments are not Markdown that MyST keeps
    body = re.sub(r'^(#+) ', lambda m: '#' * len(m.group(1)) + ' ', body, flags=re.M)
    return body


GENERATORS = {'verbs': lambda argument: verbs_markdown(),
              'schema': schema_markdown,
              'codes': lambda argument: codes_markdown()}


def _generate(app: Any, docname: str, source: list[str]) -> None:
    def replace(match: re.Match[str]) -> str:
        kind, argument = match.group(1), match.group(2)
        if kind not in GENERATORS:
            raise ValueError(f'{docname}: unknown generated text {kind!r} '
                             f'(known: {", ".join(GENERATORS)})')
        return GENERATORS[kind](argument)

    source[0] = MARKER.sub(replace, source[0])


# -- the examples' node pages ------------------------------------------------------------------


def repository_root(confdir: str) -> Path:
    """The repository the site documents: ``$NODL_REPOSITORY``, or the one above the site's folder
    (``ros/nodl_toolkit/doc``, or its copy in ``build/``), or, when rosdoc2 builds the site from
    a copy, the one its wrapping conf.py names."""
    if os.environ.get('NODL_REPOSITORY'):
        return Path(os.environ['NODL_REPOSITORY']).resolve()
    here = Path(confdir).resolve()
    for candidate in (here, *here.parents):
        if (candidate / 'nodl' / 'cli').is_dir() and (candidate / 'examples').is_dir():
            return candidate
    wrapper = here / 'conf.py'
    if wrapper.is_file():
        named = re.search(r'exec\(open\("([^"]+)"\)', wrapper.read_text(encoding='utf-8'))
        if named:
            return repository_root(str(Path(named.group(1)).parent))
    raise RuntimeError(f'no NoDL toolkit repository above {confdir}')


def write_example_pages(app: Any) -> None:
    """``nodl doc`` writes the node pages of the examples into ``examples/nodes/``."""
    root = repository_root(app.confdir)
    out = Path(app.srcdir) / 'examples' / 'nodes'
    if out.exists():
        shutil.rmtree(out)
    env = {'AMENT_PREFIX_PATH': sys.prefix, **os.environ,
           'PYTHONPATH': os.pathsep.join([str(root), os.environ.get('PYTHONPATH', '')])}
    written = subprocess.run([sys.executable, '-m', 'nodl', 'doc', *EXAMPLES, '-o', str(out),
                              '--format', 'md'],
                             cwd=root, env=env, text=True, capture_output=True, timeout=120)
    if written.returncode != 0:
        raise RuntimeError(f'nodl doc failed on the examples:\n{written.stdout}{written.stderr}')


def setup(app: Any) -> dict[str, Any]:
    app.connect('source-read', _generate)
    app.connect('builder-inited', write_example_pages)
    return {'version': '1', 'parallel_read_safe': True, 'parallel_write_safe': True}
