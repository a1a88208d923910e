"""The files every scaffolded package has, whatever its build type.

``package.xml`` with the dependencies the definitions imply, the definitions
under ``nodl/`` (with their relative mixins), a parameter file per node with
the defaults, a launch file, the conformance test (the toolkit's pytest
plugin against each installed executable), lint tests as ``ros2 pkg create``
adds them (ament_python) and a README with each node's interface.
"""

from __future__ import annotations

import os
import posixpath
import re
from collections.abc import Iterable

from nodl.composition.entities import EntityKind, InterfaceType, Provider
from nodl.files import describe_os_error
from nodl.model import Base
from nodl.model.parameter_types import TypeSpec
from nodl.naming import join_name
from nodl.plan.defaults_file import defaults_yaml
from nodl.plan.parameter_plan import plan_parameters
from nodl.scaffold.model import Authorship, NodeSource, PlannedFile, ScaffoldError
from nodl.scaffold.text import (
    markdown,
    markdown_code,
    python_string,
    xml_attribute,
    xml_text,
)

__all__ = ['common_files', 'interface_packages', 'definition_path', 'is_lifecycle',
           'params_path', 'required_placeholders', 'required_parameters', 'generated_base_path']

#: What a placeholder value of each element kind is, for required parameters in tests.
_PLACEHOLDERS = {'bool': 'false', 'int': '0', 'double': '0.0', 'string': "''", 'byte': '0'}


def is_lifecycle(node: NodeSource) -> bool:
    """True for a lifecycle node."""
    return node.node.base is Base.LIFECYCLE_NODE


def interface_packages(nodes: Iterable[NodeSource]) -> list[str]:
    """Every interface package the nodes' own endpoints use."""
    found = set()
    for node in nodes:
        for entity in node.node.implementation_entities():
            if isinstance(entity.type, InterfaceType):
                found.add(entity.type.package)
    return sorted(found)


def _referenced_packages(nodes: Iterable[NodeSource]) -> list[str]:
    found = set()
    for node in nodes:
        for mixin in node.node.node.mixins or []:
            if isinstance(mixin, str) and mixin.startswith('nodl://'):
                found.add(mixin[len('nodl://'):].split('/', 1)[0])
    return sorted(found)


def definition_path(node: NodeSource) -> str:
    """Where the node's definition goes in the package (``nodl/<file name>``)."""
    return 'nodl/' + os.path.basename(node.definition)


def params_path(node: NodeSource) -> str:
    """``config/<exe>.params.yaml``."""
    return f'config/{node.executable}.params.yaml'


def required_placeholders(node: NodeSource) -> list[tuple[str, str]]:
    """``(name, placeholder value)`` for each parameter without a default (tests must give one)."""
    out = []
    for entity in node.node.implementation_entities():
        spec = entity.type
        if entity.is_parameter and entity.default_value is None and isinstance(spec, TypeSpec):
            if spec.base == 'none':
                continue
            value = '[]' if spec.is_array else _PLACEHOLDERS[spec.element]
            out.append((entity.name, value))
    return sorted(out)


def required_parameters(node: NodeSource) -> list[tuple[str, str]]:
    """``(name, type)`` of each parameter the node must be given (no default), in declaration
    order (as the parameter file lists them)."""
    entities = node.node.provided_by(Provider.IMPLEMENTATION, Provider.OTHER_CODE)
    plan = plan_parameters([e for e in entities if e.is_parameter])
    return [(p.name, p.type_name) for p in plan.parameters if p.required]


def generated_base_path(package: str, node: NodeSource) -> str:
    """Where an ament_python package keeps the node's generated base (``<pkg>/<exe>_base.py``)."""
    return f'{package}/{node.executable}_base.py'


def _definitions(nodes: list[NodeSource]) -> list[PlannedFile]:
    files: dict[str, tuple[str, str]] = {}
    for node in nodes:
        folder = os.path.dirname(node.definition)
        entries = [(definition_path(node), node.definition)]
        for mixin in node.mixins:
            target = posixpath.normpath(posixpath.join('nodl', mixin))
            if target.startswith('../') or target == '..':
                raise ScaffoldError(f'{node.definition}: mixin {mixin!r} lies outside the folder '
                                    'above the definition; register it in a package of its own '
                                    'and refer to it as nodl://<package>/<name>')
            entries.append((target, os.path.join(folder, mixin)))
        for target, source in entries:
            earlier = files.get(target)
            if earlier is not None and os.path.abspath(earlier[0]) != os.path.abspath(source):
                raise ScaffoldError(f'{earlier[0]} and {source} would both be {target}; rename one')
            try:
                with open(source, encoding='utf-8', newline='') as f:
                    files[target] = (source, f.read())
            except OSError as exc:
                raise ScaffoldError(f'{source}: {describe_os_error(exc)}') from None
    return [PlannedFile(target, text, generated=True) for target, (_, text) in files.items()]


def _package_xml(package: str, nodes: list[NodeSource], build_type: str, component: bool = False,
                 author: Authorship = Authorship()) -> str:
    descriptions = [n.node.node.main.description for n in nodes if n.node.node.main.description]
    description = ' '.join(descriptions) or f'The nodes {", ".join(n.executable for n in nodes)}.'
    lines = ['<?xml version="1.0"?>',
             '<?xml-model href="http://download.ros.org/schema/package_format3.xsd" '
             'schematypens="http://www.w3.org/2001/XMLSchema"?>',
             '<package format="3">',
             f'  <name>{package}</name>',
             '  <version>0.0.0</version>',
             f'  <description>{xml_text(description)}</description>',
             _maintainer_xml(author), f'  <license>{xml_text(author.license or "TODO: License declaration")}</license>',
             '']
    if build_type == 'ament_cmake':
        lines.append('  <buildtool_depend>ament_cmake</buildtool_depend>')
    lines += ['  <!-- ament_nodl registers the definitions and, for C++, generates the bases -->',
              '  <buildtool_depend>ament_nodl</buildtool_depend>', '']
    if build_type == 'ament_cmake':
        depends = {'rclcpp', 'rcl_interfaces'}
        if any(is_lifecycle(n) for n in nodes):
            depends.add('rclcpp_lifecycle')
        if any(e.kind in (EntityKind.ACTION_SERVER, EntityKind.ACTION_CLIENT)
               for n in nodes for e in n.node.implementation_entities()):
            depends.add('rclcpp_action')
        if component:
            depends.add('rclcpp_components')
        depends.update(interface_packages(nodes))
        lines += [f'  <depend>{d}</depend>' for d in sorted(depends)]
    else:
        depends = {'rclpy', 'rcl_interfaces'}
        if any(is_lifecycle(n) for n in nodes):
            depends.add('lifecycle_msgs')
        depends.update(interface_packages(nodes))
        lines += [f'  <exec_depend>{d}</exec_depend>' for d in sorted(depends)]
    referenced = [p for p in _referenced_packages(nodes) if p != package]
    if referenced:
        lines += ['  <!-- packages whose definitions the nodes compose (nodl://) -->']
        lines += [f'  <exec_depend>{p}</exec_depend>' for p in referenced]
    lines += ['']
    if build_type == 'ament_cmake':
        lines += ['  <test_depend>ament_lint_auto</test_depend>',
                  '  <test_depend>ament_lint_common</test_depend>',
                  '  <test_depend>ament_cmake_pytest</test_depend>']
    else:
        lines += ['  <test_depend>ament_copyright</test_depend>',
                  '  <test_depend>ament_flake8</test_depend>',
                  '  <test_depend>ament_pep257</test_depend>',
                  '  <test_depend>python3-pytest</test_depend>']
    lines += ['  <!-- the conformance test: the nodl_conformance pytest fixture -->',
              '  <test_depend>nodl_toolkit</test_depend>',
              '  <test_depend>lifecycle_msgs</test_depend>' if any(is_lifecycle(n) for n in nodes)
              else '', '',
              '  <export>', f'    <build_type>{build_type}</build_type>', '  </export>',
              '</package>']
    return '\n'.join(line for i, line in enumerate(lines) if line or (i and lines[i - 1])) + '\n'


def _maintainer_xml(author: Authorship) -> str:
    if author.maintainer is None:
        return '  <maintainer email="todo@todo.todo">TODO</maintainer>'
    name, email = author.maintainer
    return f'  <maintainer email="{xml_attribute(email)}">{xml_text(name)}</maintainer>'


def _xml_comment(text: str) -> str:
    """``text`` inside an XML comment (which cannot hold ``--``)."""
    while '--' in text:
        text = text.replace('--', '-\u2010')
    return f'<!-- {text} -->'


def _launch(package: str, nodes: list[NodeSource]) -> str:
    lines = ['<launch>',
             f'  <!-- Starts the nodes of {xml_text(package)}, each with its parameter file. -->']
    for node in nodes:
        lines += [f'  <node pkg="{xml_attribute(package)}" exec="{xml_attribute(node.executable)}" '
                  f'name="{xml_attribute(node.executable)}" output="screen">',
                  f'    <param from="$(find-pkg-share {xml_attribute(package)})/'
                  f'{xml_attribute(params_path(node))}"/>']
        for name, type_name in required_parameters(node):
            placeholder = f'<param name="{xml_attribute(name)}" value="<{type_name}>"/>'
            lines.append('    ' + _xml_comment(
                f'{placeholder}  required: set it here or in {params_path(node)}; '
                f'{node.executable} does not start without it'))
        lines += ['  </node>']
    lines.append('</launch>')
    return '\n'.join(lines) + '\n'


def _params(node: NodeSource) -> str:
    text = defaults_yaml(node.node, join_name('/', node.executable))
    # the parameter file's note on a required parameter becomes a placeholder to uncomment
    required = iter(required_parameters(node))
    lines = []
    for line in text.split('\n'):
        match = _REQUIRED_NOTE.fullmatch(line)
        if match:
            name, type_name = next(required)
            line = (f'{match[1]}# {match[2]}: <{type_name}>  # required: set it here (uncomment) '
                    f'or with --ros-args -p {name}:=VALUE')
        lines.append(line)
    return '\n'.join(lines)


#: How ``nodl params`` notes a parameter without a default: indent, key.
_REQUIRED_NOTE = re.compile(r'( *)# (.+): required \(.+\): no default, give a value')


def _conformance_test(package: str, nodes: list[NodeSource], author: Authorship) -> str:
    entries = []
    for node in nodes:
        arguments = [f'{name}:={value}' for name, value in required_placeholders(node)]
        entries.append(f'    ({python_string(node.executable)}, {is_lifecycle(node)}, '
                       f'{arguments!r}),')
    return author.header('#') + f'''"""
The nodes of {package} conform to their NoDL definitions.

Each installed executable is started with its parameter file; the
nodl_conformance fixture (the NoDL toolkit's pytest plugin) then checks the
running node against the definition registered for it, as `nodl check` does.
A lifecycle node is configured and activated first.
"""

import os
import subprocess
import time

from ament_index_python.packages import get_package_prefix, get_package_share_directory
import pytest

PACKAGE = {python_string(package)}
#: (executable, lifecycle node, -p NAME:=VALUE for parameters without a default)
NODES = [
{chr(10).join(entries)}
]


def _transition(node, label, timeout=10.0):
    import rclpy
    from lifecycle_msgs.msg import Transition
    from lifecycle_msgs.srv import ChangeState

    ids = {{'configure': Transition.TRANSITION_CONFIGURE,
           'activate': Transition.TRANSITION_ACTIVATE}}
    context = rclpy.Context()
    rclpy.init(context=context)
    try:
        client_node = rclpy.create_node('conformance_lifecycle_client', context=context)
        client = client_node.create_client(ChangeState, node + '/change_state')
        assert client.wait_for_service(timeout_sec=timeout), f'{{node}}/change_state is not served'
        future = client.call_async(ChangeState.Request(transition=Transition(id=ids[label])))
        executor = rclpy.executors.SingleThreadedExecutor(context=context)
        executor.add_node(client_node)
        executor.spin_until_future_complete(future, timeout_sec=timeout)
        assert future.result() is not None and future.result().success, f'{{label}} failed'
    finally:
        rclpy.shutdown(context=context)


@pytest.mark.parametrize('executable, lifecycle, overrides', NODES)
def test_node_conforms(nodl_conformance, executable, lifecycle, overrides):
    program = os.path.join(get_package_prefix(PACKAGE), 'lib', PACKAGE, executable)
    params = os.path.join(get_package_share_directory(PACKAGE), 'config',
                          executable + '.params.yaml')
    arguments = ['--ros-args', '--params-file', params]
    for override in overrides:  # TODO: give real values
        arguments += ['-p', override]
    process = subprocess.Popen([program] + arguments)
    try:
        if lifecycle:
            deadline = time.monotonic() + 20
            while True:
                try:
                    _transition('/' + executable, 'configure')
                    break
                except AssertionError:
                    if time.monotonic() > deadline:
                        raise
            _transition('/' + executable, 'activate')
        nodl_conformance('/' + executable, (PACKAGE, executable), timeout=20)
    finally:
        process.terminate()
        try:
            process.wait(timeout=10)
        except subprocess.TimeoutExpired:
            process.kill()
            process.wait(timeout=10)
'''


def _interface_rows(node: NodeSource) -> list[str]:
    rows = ['| Kind | Name | Type | Description |', '| --- | --- | --- | --- |']
    for entity in node.node.implementation_entities():
        rows.append(f'| {entity.kind.word} | {markdown_code(entity.name)} | '
                    f'{markdown_code(entity.type_name)} | {markdown(entity.description)} |')
    return rows


def _readme(package: str, nodes: list[NodeSource], build_type: str) -> str:
    lines = [f'# {markdown(package)}', '',
             f'Created by `nodl new` ({build_type}) from NoDL node definitions. The definitions '
             'under `nodl/` are the source of truth: after editing one, run '
             f'`nodl new {package} --from ... --build-type {build_type} --update` to regenerate '
             'the generated code (your own files are kept).', '',
             '| Executable | Definition | Description |', '| --- | --- | --- |']
    for node in nodes:
        lines.append(f'| {markdown_code(node.executable)} | {markdown_code(definition_path(node))} '
                     f'| {markdown(node.node.node.main.description)} |')
    for node in nodes:
        kind = 'lifecycle node' if is_lifecycle(node) else 'node'
        lines += ['', f'## {markdown(node.executable)}', '',
                  f'A {kind}. Run it with `ros2 run {package} {node.executable}`, or all of them '
                  f'with `ros2 launch {package} {package}.launch.xml`; its parameters and their '
                  f'defaults are in `{params_path(node)}`. Check a running instance with '
                  f'`nodl check /{node.executable} {package} {node.executable}`.', '']
        lines += _interface_rows(node)
    return '\n'.join(lines) + '\n'


_LINT_TESTS = {
    'test/test_flake8.py': ('ament_flake8', 'main_with_errors', 'flake8', '[]',
                            'Found {} code style errors / warnings'),
    'test/test_pep257.py': ('ament_pep257', 'main', 'pep257', "['.', 'test']",
                            'Found code style errors / warnings'),
}


def _copyright_test(package: str, nodes: list[NodeSource], author: Authorship) -> str:
    bases = ''.join(f'    {python_string(generated_base_path(package, n))},\n' for n in nodes)
    skip = ''
    if author.license is None:
        skip = ("\n# Remove the skip once the files carry a license and copyright notice\n"
                "# (nodl new --license SPDX --maintainer NAME EMAIL writes them).\n"
                "@pytest.mark.skip(reason='no copyright notice in the created files yet')")
    return (author.header('#') + 'import os\n\nfrom ament_copyright.main import main\nimport pytest\n\n'
            '# The generated bases carry no notice of their own: `nodl generate --check` keeps them\n'
            '# exactly as generated from the definitions (excluded as paths, and as file names\n'
            '# for ament_copyright releases that match --exclude against names).\n'
            'PACKAGE = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))\n'
            f'GENERATED = [\n{bases}]\n\n{skip}\n'
            '@pytest.mark.copyright\n@pytest.mark.linter\ndef test_copyright():\n'
            "    excluded = [os.path.join(PACKAGE, path) for path in GENERATED]\n"
            "    excluded += [os.path.basename(path) for path in GENERATED]\n"
            "    rc = main(argv=['.', 'test', '--exclude', *excluded])\n"
            "    assert rc == 0, 'Found errors'\n")


def _lint_test(module: str, function: str, marker: str, argv: str, message: str,
               author: Authorship) -> str:
    if function == 'main_with_errors':
        return author.header('#') + (f'from {module}.main import main_with_errors\nimport pytest\n\n\n'
                f'@pytest.mark.{marker}\n@pytest.mark.linter\ndef test_{marker}():\n'
                f'    rc, errors = main_with_errors(argv={argv})\n'
                f"    assert rc == 0, \\\n        '{message}'.format(len(errors)) + \\\n"
                "        '\\n'.join(errors)\n")
    return author.header('#') + (f'from {module}.main import main\nimport pytest\n\n\n'
            f'@pytest.mark.{marker}\n@pytest.mark.linter\ndef test_{marker}():\n'
            f"    rc = main(argv={argv})\n    assert rc == 0, '{message}'\n")


def common_files(package: str, nodes: list[NodeSource], build_type: str,
                 component: bool = False, author: Authorship = Authorship()) -> list[PlannedFile]:
    """The files of the package that do not depend on its build type's build files."""
    files = _definitions(nodes)
    files += [PlannedFile('package.xml', _package_xml(package, nodes, build_type, component, author),
                          False),
              PlannedFile(f'launch/{package}.launch.xml', _launch(package, nodes), False),
              PlannedFile('README.md', _readme(package, nodes, build_type), False),
              PlannedFile('test/test_conformance.py', _conformance_test(package, nodes, author),
                          False)]
    files += [PlannedFile(params_path(n), _params(n), False) for n in nodes]
    if build_type == 'ament_python':
        files += [PlannedFile(path, _lint_test(*spec, author), False)
                  for path, spec in _LINT_TESTS.items()]
        files.append(PlannedFile('test/test_copyright.py', _copyright_test(package, nodes, author),
                                 False))
    return files
