"""nodl_toolkit as a ROS package (ament_python): the library and the `nodl` command.

colcon builds this directory; ``pip install .`` at the repository root builds
the same library from the repository's pyproject.toml. That file stays the one
table of the project's metadata (version, dependencies, commands, entry points,
package data): this script reads it, so both builds install the same thing.
It only adds what a ROS package installs (the index marker and package.xml)
and leaves out the ``ros2cli.command`` entry point, which the ros2nodl package
registers.

``nodl`` here is a symbolic link to the library at the repository root.
This script runs with setuptools 59 and Python 3.10 (ROS 2 Humble) as well as
with newer ones: no pyproject-based metadata, and a small reader for the few
tables of pyproject.toml it needs where ``tomllib`` is missing.
"""

import ast
import os
import re

from setuptools import find_namespace_packages, setup

HERE = os.path.dirname(os.path.realpath(__file__))  # colcon --symlink-install links it
PYPROJECT = os.path.join(HERE, '..', '..', 'pyproject.toml')
PACKAGE = 'nodl_toolkit'
# The ros2nodl package registers the ros2cli command (see ros/ros2nodl/setup.py).
LEFT_TO_OTHER_PACKAGES = {'ros2cli.command'}


def _read_simple_toml(text):
    """Tables of ``key = "string"`` / ``key = ["string", ...]`` lines (enough for our pyproject).

    Values of any other shape (numbers, booleans, inline tables) are skipped:
    this script reads only string and string-array values.
    """
    data = {}
    table = data
    pending = None
    for raw in text.splitlines():
        line = raw.strip()
        if pending is not None:
            key, value = pending
            value += ' ' + _strip_comment(line)
            if _balanced(value):
                pending = None
                _store(table, key, value)
            else:
                pending = (key, value)
            continue
        if not line or line.startswith('#'):
            continue
        if line.startswith('[['):  # an array of tables: nothing this script reads
            table = {}
            continue
        header = re.fullmatch(r'\[([^\[\]]+)\]', line)
        if header:
            table = data
            for part in re.findall(r'"[^"]*"|[^.\s]+', header.group(1)):
                table = table.setdefault(part.strip('"'), {})
            continue
        match = re.fullmatch(r'("[^"]*"|[A-Za-z0-9_.-]+)\s*=\s*(.*)', line)
        if not match:
            continue
        key, value = match.group(1).strip('"'), _strip_comment(match.group(2))
        if value.startswith('[') and not _balanced(value):
            pending = (key, value)
        else:
            _store(table, key, value)
    return data


def _balanced(value):
    # brackets outside strings
    depth, in_string = 0, False
    for char in value:
        if char == '"':
            in_string = not in_string
        elif not in_string:
            depth += {'[': 1, ']': -1}.get(char, 0)
    return depth == 0


def _strip_comment(value):
    # a '#' outside a string starts a comment
    out, in_string = [], False
    for char in value:
        if char == '"':
            in_string = not in_string
        if char == '#' and not in_string:
            break
        out.append(char)
    return ''.join(out).strip()


def _store(table, key, value):
    try:
        parsed = ast.literal_eval(value)
    except (ValueError, SyntaxError):
        return
    if isinstance(parsed, str) or (isinstance(parsed, list)
                                   and all(isinstance(v, str) for v in parsed)):
        table[key] = parsed


def read_pyproject(path=PYPROJECT):
    """The parsed pyproject.toml (``tomllib`` where available, else the reader above)."""
    with open(path, 'rb') as f:
        raw = f.read()
    try:
        import tomllib
    except ImportError:
        try:
            import tomli as tomllib
        except ImportError:
            return _read_simple_toml(raw.decode('utf-8'))
    return tomllib.loads(raw.decode('utf-8'))


def setup_arguments(pyproject):
    """setup() keywords derived from pyproject.toml."""
    project = pyproject['project']
    entry_points = {'console_scripts': [f'{k} = {v}' for k, v in project.get('scripts', {}).items()]}
    for group, entries in project.get('entry-points', {}).items():
        if group not in LEFT_TO_OTHER_PACKAGES:
            entry_points[group] = [f'{k} = {v}' for k, v in entries.items()]
    setuptools_config = pyproject.get('tool', {}).get('setuptools', {})
    include = setuptools_config.get('packages', {}).get('find', {}).get('include', ['nodl', 'nodl.*'])
    return {
        'name': PACKAGE,
        'version': project['version'],
        'description': project.get('description', ''),
        'license': 'Apache-2.0',
        'maintainer': 'NoDL toolkit maintainers',
        'maintainer_email': 'maintainers@nodl-toolkit.example.org',
        'python_requires': project.get('requires-python', '>=3.10'),
        'install_requires': list(project.get('dependencies', [])),
        'packages': find_namespace_packages(HERE, include=include),
        'package_data': dict(setuptools_config.get('package-data', {})),
        'entry_points': entry_points,
        'zip_safe': False,
    }


if __name__ == '__main__':
    setup(
        data_files=[
            ('share/ament_index/resource_index/packages', ['resource/' + PACKAGE]),
            ('share/' + PACKAGE, ['package.xml']),
        ],
        **setup_arguments(read_pyproject()),
    )
