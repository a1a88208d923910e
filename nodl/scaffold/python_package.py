"""The files of an ament_python package: setup.py, setup.cfg, the module, the node stubs.

The generated base (``<package>/<exe>_base.py``) is committed with the
package, so that it can be read, reviewed and type-checked like the rest of
the code; ``test/test_generated.py`` fails when it is stale (``nodl generate
--check``).  The user's subclass (``<package>/<exe>.py``) is derived from the
generated module itself: every abstract method is overridden with the same
signature and a placeholder body, so the node runs right away.
"""

from __future__ import annotations

import ast
import re
import sys
import textwrap

from nodl.generate import GenerateOptions, default_class_name
from nodl.generate.python import generate_python
from nodl.scaffold.common import definition_path
from nodl.scaffold.model import Authorship, NodeSource, PlannedFile, ScaffoldError
from nodl.scaffold.text import one_line, python_string
from nodl.text_safety import visible

__all__ = ['python_files', 'user_module', 'generate_base']


def generate_base(package: str, node: NodeSource) -> tuple[str, str]:
    """``(file name, text)`` of the node's generated rclpy base."""
    options = GenerateOptions(default_class_name(node.executable), node.executable)
    files = generate_python(node.node, options)
    if len(files) != 1:
        raise ScaffoldError(f'the Python generator wrote {len(files)} files for {node.executable}')
    return files[0].path, files[0].text


def _placeholder(method: ast.FunctionDef, returns: str) -> list[str]:
    names = [a.arg for a in method.args.args[1:]]
    if returns == 'None':
        return ['pass  # TODO: handle ' + (names[0] if names else 'the call')]
    if returns == 'GoalResponse':
        return ['return GoalResponse.ACCEPT']
    if returns == 'CancelResponse':
        return ['return CancelResponse.ACCEPT']
    if returns.endswith('.Response') and 'response' in names:
        return ['return response  # TODO: fill the response']
    if returns.endswith('.Result'):
        return ['# TODO: execute the goal, publishing feedback through goal_handle',
                'goal_handle.succeed()', f'return {returns}()']
    raise ScaffoldError(f'no placeholder for a callback returning {returns}')


def user_module(package: str, node: NodeSource, base_module: str, base_text: str,
                author: Authorship = Authorship()) -> str:
    """The user's subclass of the generated base, with ``main``.

    ``main`` reports a parameter the node cannot start without (the base's
    ``ParameterError``) on one line and returns 1, the exit status of the
    installed executable.
    """
    tree = ast.parse(base_text)
    lines = base_text.splitlines()
    class_name = default_class_name(node.executable)
    base_class = class_name + 'Base'
    cls = next((n for n in tree.body if isinstance(n, ast.ClassDef) and n.name == base_class), None)
    if cls is None:
        raise ScaffoldError(f'the generated module has no class {base_class}')
    methods: list[str] = []
    custom = '_CUSTOM_VALIDATORS' in base_text and not _empty_custom(tree)
    for item in cls.body:
        if not isinstance(item, ast.FunctionDef):
            continue
        if not any(ast.unparse(d) in ('abc.abstractmethod', 'abstractmethod')
                   for d in item.decorator_list):
            continue
        header = lines[item.lineno - 1:item.body[0].lineno - 1]
        returns = ast.unparse(item.returns) if item.returns is not None else 'None'
        methods += [''] + header + ['        ' + line for line in _placeholder(item, returns)]
    if custom:
        methods += ['', '    def on_custom_validator(self, function: str, name: str, value: Any,',
                    '                            arguments: Any) -> str | None:',
                    '        return None  # TODO: check value with function; return why it fails']
    text = '\n'.join(methods)
    doc = f'The implementation of the {node.executable} node (written once by nodl new: yours).'
    out = [f'"""{doc}"""', '', 'from __future__ import annotations', '']
    stdlib, third_party = _imports(tree, text)
    out += sorted(stdlib + ['import sys'], key=_import_key) + ['']
    # one group, sorted by module (flake8-import-order's google style, as ament_flake8 sets it)
    third_party += ['import rclpy', 'from rclpy.executors import ExternalShutdownException',
                    f'from {package}.{base_module} import '
                    + ', '.join(sorted([base_class, 'ParameterError'], key=str.lower))]
    out += sorted(third_party, key=_import_key)
    out += ['', '', f'class {class_name}({base_class}):',
            f'    """The {node.executable} node: implement its callbacks here."""']
    out += methods if methods else ['']
    out += ['', '', 'def main(args: list[str] | None = None) -> int:',
            f'    """Run the {node.executable} node until it is shut down; return the exit status."""',
            '    rclpy.init(args=args)',
            '    try:',
            f'        node = {class_name}()',
            '    except ParameterError as exc:  # a parameter it needs is missing or invalid',
            '        print(exc, file=sys.stderr)',
            '        rclpy.try_shutdown()',
            '        return 1',
            '    except (KeyboardInterrupt, ExternalShutdownException):',
            '        rclpy.try_shutdown()',
            '        return 0',
            '    except Exception:',
            '        if rclpy.ok():',
            '            raise',
            '        return 0  # shut down (Ctrl-C, SIGTERM) while it was starting',
            '    try:',
            '        rclpy.spin(node)',
            '    except (KeyboardInterrupt, ExternalShutdownException):',
            '        pass',
            '    finally:',
            '        node.destroy_node()',
            '        rclpy.try_shutdown()',
            '    return 0', '', '',
            "if __name__ == '__main__':", '    sys.exit(main())']
    return author.header('#') + '\n'.join(out) + '\n'


def _import_key(line: str) -> tuple[str, int]:
    """Sort key of an import line: its module, case-insensitively (``import`` and ``from`` mixed)."""
    return line.split()[1].lower(), 0 if line.startswith('import ') else 1


def _empty_custom(tree: ast.Module) -> bool:
    for item in tree.body:
        if isinstance(item, ast.AnnAssign) and ast.unparse(item.target) == '_CUSTOM_VALIDATORS':
            return isinstance(item.value, ast.Dict) and not item.value.keys
    return True


def _imports(tree: ast.Module, text: str) -> tuple[list[str], list[str]]:
    """The generated module's imports that ``text`` uses (names, or dotted modules): those of the
    standard library, and the others."""
    used = set(re.findall(r'[A-Za-z_][A-Za-z0-9_.]*', text))
    roots = {u.split('.')[0] for u in used}
    out: list[str] = []
    stdlib: list[str] = []
    for item in tree.body:
        if isinstance(item, ast.Import):
            names = [a for a in item.names if (a.asname or a.name).split('.')[0] in roots]
            out += [f'import {a.name}' + (f' as {a.asname}' if a.asname else '') for a in names]
        elif isinstance(item, ast.ImportFrom) and item.module and item.module != '__future__':
            names = [a for a in item.names if (a.asname or a.name) in roots]
            if names:
                line = f'from {item.module} import ' + ', '.join(
                    a.name + (f' as {a.asname}' if a.asname else '') for a in names)
                (stdlib if item.module.split('.')[0] in sys.stdlib_module_names else out).append(line)
    return stdlib, out


def _setup_py(package: str, nodes: list[NodeSource], author: Authorship) -> str:
    registered = ',\n'.join(f'                {python_string(n.executable)}: '
                            f'{python_string(definition_path(n))}' for n in nodes)
    name, email = author.maintainer or ('TODO', 'todo@todo.todo')
    scripts = ',\n'.join(f'            {python_string(f"{n.executable} = {package}.{n.executable}:main")}'
                         for n in nodes)
    definitions = _wrapped_comment(f'The definitions: validated now, installed to share/{package}/nodl, registered '
                                   f'in the ament index (nodl show / nodl check {package} EXECUTABLE find them).',
                                   '        ')
    docstring = f'"""Build and install {package}: its module, its node definitions and their registration."""'
    return author.header('#') + docstring + f'''

from glob import glob

from nodl.packaging import nodl_data_files
from setuptools import find_packages, setup

package_name = {python_string(package)}

setup(
    name=package_name,
    version='0.0.0',
    packages=find_packages(exclude=['test']),
    data_files=[
        ('share/ament_index/resource_index/packages', ['resource/' + package_name]),
        ('share/' + package_name, ['package.xml']),
        ('share/' + package_name + '/config', glob('config/*.yaml')),
        ('share/' + package_name + '/launch', glob('launch/*.launch.xml')),
{definitions}
        *nodl_data_files(
            package_name,
            nodes={{
{registered},
            }}),
    ],
    install_requires=['setuptools'],
    zip_safe=True,
    maintainer={python_string(name)},
    maintainer_email={python_string(email)},
    description={_string_lines(_description(nodes), '    description=')},
    license={python_string(author.license or 'TODO: License declaration')},
    extras_require={{
        'test': ['pytest'],
    }},
    entry_points={{
        'console_scripts': [
{scripts},
        ],
    }},
)
'''


def _description(nodes: list[NodeSource]) -> str:
    """The package's one-line description (setup.py's ``description``, the package metadata's
    Summary): control and bidi characters as visible escapes, so the installed metadata holds
    none of them (pip, PyPI and terminals show the summary as it is)."""
    text = ' '.join(visible(one_line(n.node.node.main.description), one_line=True) for n in nodes
                    if n.node.node.main.description)
    return text or f'The nodes {", ".join(n.executable for n in nodes)}.'


def _string_lines(text: str, head: str) -> str:
    """A string literal of ``text`` after ``head``, split into parenthesized adjacent literals
    when the line would pass 99 columns."""
    if len(head) + len(python_string(text)) + 1 <= 99:
        return python_string(text)
    chunks = textwrap.wrap(text, 99 - 8 - 4, break_long_words=True, drop_whitespace=False)
    indent = ' ' * 8
    return '(\n' + ''.join(f'{indent}{python_string(c)}\n' for c in chunks) + '    )'


def _setup_cfg(package: str) -> str:
    # [tool:pytest]: colcon test runs pytest over test/ (the lint tests, the staleness test and
    # the conformance test), with JUnit results for colcon test-result
    return (f'[develop]\nscript_dir=$base/lib/{package}\n'
            f'[install]\ninstall_scripts=$base/lib/{package}\n'
            '[tool:pytest]\ntestpaths = test\njunit_family = xunit2\n')


def _wrapped(text: str, width: int = 95) -> str:
    """``text`` as lines of at most ``width`` characters (ament_flake8 allows 99; a docstring's
    first line has three quotes before it)."""
    return textwrap.fill(text, width, break_long_words=False, break_on_hyphens=False)


def _wrapped_comment(text: str, indent: str) -> str:
    """``text`` as ``# `` comment lines at ``indent``, within ament_flake8's 99 columns."""
    return '\n'.join(f'{indent}# {line}' for line in _wrapped(text, 99 - len(indent) - 2).splitlines())


def _staleness_test(package: str, nodes: list[NodeSource], author: Authorship) -> str:
    entries = '\n'.join(f'    ({python_string(n.executable)}, '
                        f'{python_string(default_class_name(n.executable))}, '
                        f'{python_string(definition_path(n))}),' for n in nodes)
    doc = _wrapped(f'The generated bases of {package} are up to date with the definitions under nodl/.')
    how = _wrapped(f'They are committed with the package; after changing a definition, regenerate them '
                   f'with `nodl new {package} --from ... --build-type ament_python --update` or '
                   f'`nodl generate nodl/FILE --language python -o {package}`.')
    return author.header('#') + f'''"""
{doc}

{how}
"""

import os
import shutil
import subprocess

import pytest

HERE = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
#: (executable, class name, definition)
NODES = [
{entries}
]


@pytest.mark.parametrize('executable, class_name, definition', NODES)
def test_generated_base_is_up_to_date(executable, class_name, definition):
    nodl = shutil.which('nodl')
    assert nodl, 'the nodl command (NoDL toolkit) is not on PATH'
    result = subprocess.run(
        [nodl, 'generate', os.path.join(HERE, definition), '--language', 'python',
         '--node-name', executable, '--class-name', class_name,
         '-o', os.path.join(HERE, {python_string(package)}), '--check'],
        capture_output=True, text=True, timeout=120)
    assert result.returncode == 0, result.stderr
'''


def python_files(package: str, nodes: list[NodeSource],
                 author: Authorship = Authorship()) -> list[PlannedFile]:
    """setup.py, setup.cfg, the index marker, the module: generated bases and user stubs."""
    files = [PlannedFile('setup.py', _setup_py(package, nodes, author), False),
             PlannedFile('setup.cfg', _setup_cfg(package), False),
             PlannedFile(f'resource/{package}', '', False),
             PlannedFile(f'{package}/__init__.py', '', False),
             PlannedFile('test/test_generated.py', _staleness_test(package, nodes, author), False)]
    for node in nodes:
        name, text = generate_base(package, node)
        files.append(PlannedFile(f'{package}/{name}', text, True))
        module = name[:-len('.py')] if name.endswith('.py') else name
        files.append(PlannedFile(f'{package}/{node.executable}.py',
                                 user_module(package, node, module, text, author), False))
    return files
