"""The scaffold library: which files a package gets, their kinds, dependencies, escaping, and
the ament_cmake variant in a real CMake configure and g++ compile (rclcpp stand-ins).

Golden files of the ament_cmake package are under tests/fixtures/scaffold/cmake/
(``pytest --update-golden`` rewrites them).
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from conftest import FIXTURES
from nodl.scaffold import ScaffoldError, load_nodes, plan_package, write_package
from nodl.writing import WriteError, mark, marker_state

GENERATE = FIXTURES / 'generate'
GOLDEN = FIXTURES / 'scaffold' / 'cmake'
VENV = Path(sys.prefix)
SOURCES = [[str(GENERATE / f'{n}.nodl.yaml')] for n in ('talker', 'managed_camera', 'everything')]


def plan(build_type: str, package: str = 'demo_nodes'):  # type: ignore[no-untyped-def]
    return plan_package(package, load_nodes(SOURCES, build_type), build_type)


def test_python_package_files_and_kinds() -> None:
    files = {f.path: f for f in plan('ament_python').files}
    generated = sorted(p for p, f in files.items() if f.generated)
    assert generated == ['demo_nodes/everything_base.py', 'demo_nodes/managed_camera_base.py',
                         'demo_nodes/talker_base.py', 'nodl/everything.nodl.yaml',
                         'nodl/managed_camera.nodl.yaml', 'nodl/talker.nodl.yaml']
    for path in ('setup.py', 'setup.cfg', 'package.xml', 'README.md', 'resource/demo_nodes',
                 'demo_nodes/__init__.py', 'demo_nodes/talker.py', 'config/talker.params.yaml',
                 'launch/demo_nodes.launch.xml', 'test/test_conformance.py',
                 'test/test_generated.py', 'test/test_flake8.py', 'test/test_pep257.py',
                 'test/test_copyright.py'):
        assert path in files and not files[path].generated, path


def test_cmake_package_files_and_kinds() -> None:
    files = {f.path: f for f in plan('ament_cmake').files}
    assert sorted(p for p, f in files.items() if f.generated) == [
        'nodl/everything.nodl.yaml', 'nodl/managed_camera.nodl.yaml', 'nodl/talker.nodl.yaml']
    for path in ('CMakeLists.txt', 'package.xml', 'src/talker.cpp', 'src/everything.cpp',
                 'src/managed_camera.cpp', 'test/test_conformance.py'):
        assert path in files
    assert 'setup.py' not in files


@pytest.mark.parametrize('path', ['CMakeLists.txt', 'package.xml', 'README.md',
                                  'src/talker.cpp', 'src/managed_camera.cpp', 'src/everything.cpp',
                                  'launch/demo_nodes.launch.xml', 'test/test_conformance.py'])
def test_cmake_package_golden(path: str, golden) -> None:  # type: ignore[no-untyped-def]
    files = {f.path: f.text for f in plan('ament_cmake').files}
    golden.check(files[path], GOLDEN / path)


@pytest.mark.parametrize('build_type, expected', [
    ('ament_python', {'exec_depend': ['lifecycle_msgs', 'rcl_interfaces', 'rclpy', 'std_msgs',
                                      'std_srvs', 'test_msgs']}),
    ('ament_cmake', {'build_depend': ['rcl_interfaces', 'rclcpp', 'rclcpp_action', 'rclcpp_lifecycle',
                                'std_msgs', 'std_srvs', 'test_msgs']}),
])
def test_package_xml_is_valid_and_derives_the_dependencies(build_type: str,
                                                           expected: dict[str, list[str]],
                                                           tmp_path: Path) -> None:
    from catkin_pkg.package import parse_package_string

    text = next(f.text for f in plan(build_type).files if f.path == 'package.xml')
    package = parse_package_string(text)
    package.validate()
    assert package.get_build_type() == build_type
    for kind, names in expected.items():
        assert sorted(d.name for d in getattr(package, f'{kind}s')) == names
    assert 'ament_nodl' in [d.name for d in package.buildtool_depends]
    assert 'nodl_toolkit' in [d.name for d in package.test_depends]


def test_names_and_descriptions_are_escaped_in_readme_and_xml(tmp_path: Path) -> None:
    definition = tmp_path / 'odd.nodl.yaml'
    definition.write_text('''nodl_version: 2
base: node
main:
  nodl_version: 2
  description: "A </description> <b>bold</b> | pipe & *star* `tick`"
  parameters:
    "x_y": {type: int, default_value: 1, description: "a | b\\n# not a heading"}
  publishers:
    - name: ~/out
      type: std_msgs/msg/String
      description: "[link](javascript:alert(1)) <script>"
      qos: {history: KEEP_LAST, depth: 1, reliability: RELIABLE}
''', encoding='utf-8')
    result = plan_package('odd_pkg', load_nodes([[str(definition)]], 'ament_python'),
                          'ament_python')
    files = {f.path: f.text for f in result.files}
    from catkin_pkg.package import parse_package_string

    parsed = parse_package_string(files['package.xml'])  # still well-formed XML
    assert parsed.name == 'odd_pkg'
    assert parsed.description.startswith('A &lt;/description&gt; &lt;b&gt;bold')
    readme = files['README.md']
    assert '<script>' not in readme and '<b>' not in readme
    assert '\\[link\\](javascript:alert(1)) \\<script\\>' in readme
    table = [line for line in readme.splitlines() if 'x_y' in line and 'parameter' in line]
    assert table and all(line.count(' | ') == 3 for line in table), table
    assert '\n# not a heading' not in readme


def test_write_refuses_an_existing_folder_and_update_keeps_user_files(tmp_path: Path) -> None:
    result = plan('ament_python')
    write_package(result, str(tmp_path))
    with pytest.raises(ScaffoldError, match='--update'):
        write_package(result, str(tmp_path))
    user = tmp_path / 'demo_nodes' / 'demo_nodes' / 'talker.py'
    base = tmp_path / 'demo_nodes' / 'demo_nodes' / 'talker_base.py'
    user.write_text('mine\n', encoding='utf-8')
    generated = base.read_text(encoding='utf-8')
    assert marker_state(generated) == 'valid'  # generated files carry the marker
    base.write_text(mark('stale\n', '#'), encoding='utf-8')  # as an older nodl generated it
    report = write_package(result, str(tmp_path), update=True)
    assert user.read_text(encoding='utf-8') == 'mine\n'
    assert base.read_text(encoding='utf-8') == generated
    assert 'demo_nodes/demo_nodes/talker.py' in report.kept
    assert report.written == ['demo_nodes/demo_nodes/talker_base.py']
    base.write_text(generated + '# my fix\n', encoding='utf-8')  # a generated file, edited
    (tmp_path / 'demo_nodes' / 'package.xml').unlink()
    with pytest.raises(WriteError) as refused:
        write_package(result, str(tmp_path), update=True)
    assert (refused.value.diagnostic.code, refused.value.diagnostic.file) == ('NODL032', str(base))
    assert base.read_text(encoding='utf-8').endswith('# my fix\n')
    assert not (tmp_path / 'demo_nodes' / 'package.xml').exists()  # refused before writing any
    forced = write_package(result, str(tmp_path), update=True, force=True)
    assert base.read_text(encoding='utf-8') == generated and user.read_text(encoding='utf-8') != 'mine\n'
    assert 'demo_nodes/package.xml' in forced.written
    # regenerating again writes nothing: the output is byte-identical
    assert write_package(plan('ament_python'), str(tmp_path), update=True).written == []


@pytest.mark.parametrize('package', ['Demo', '1pkg', 'my-pkg', ''])
def test_invalid_package_names(package: str) -> None:
    with pytest.raises(ScaffoldError, match='not a valid ROS package name'):
        plan('ament_python', package)


def test_a_registered_definition_names_its_executable(tmp_path: Path) -> None:
    """PACKAGE EXECUTABLE: the executable keeps the registered name."""
    prefix = tmp_path / 'prefix'
    index = prefix / 'share' / 'ament_index' / 'resource_index'
    (index / 'packages').mkdir(parents=True)
    (index / 'packages' / 'other').write_text('', encoding='utf-8')
    (index / 'nodl_nodes').mkdir()
    (index / 'nodl_nodes' / 'other__my_talker').write_text('nodl/talker.nodl.yaml',
                                                            encoding='utf-8')
    (prefix / 'share' / 'other' / 'nodl').mkdir(parents=True)
    shutil.copy(GENERATE / 'talker.nodl.yaml', prefix / 'share' / 'other' / 'nodl')
    old = os.environ.get('AMENT_PREFIX_PATH', '')
    os.environ['AMENT_PREFIX_PATH'] = os.pathsep.join([str(prefix), old])
    try:
        nodes = load_nodes([['other', 'my_talker']], 'ament_python')
    finally:
        os.environ['AMENT_PREFIX_PATH'] = old
    assert [n.executable for n in nodes] == ['my_talker']
    files = {f.path for f in plan_package('pkg', nodes, 'ament_python').files}
    assert {'pkg/my_talker.py', 'pkg/my_talker_base.py', 'nodl/talker.nodl.yaml'} <= files


def test_the_cmake_package_configures_and_compiles(tmp_path: Path) -> None:
    """A real CMake configure of the ament_cmake package (rclcpp from the stand-ins) and a
    compile of every generated base and every user source with the system's compiler."""
    write_package(plan('ament_cmake'), str(tmp_path / 'src'))
    source, build = tmp_path / 'src' / 'demo_nodes', tmp_path / 'build'
    env = dict(os.environ)
    env.pop('MAKEFLAGS', None)
    env.update(AMENT_PREFIX_PATH=str(VENV),
               CMAKE_PREFIX_PATH=os.pathsep.join([str(GENERATE / 'cpp_stub_packages'), str(VENV)]),
               PATH=os.pathsep.join([str(VENV / 'bin'), env.get('PATH', '')]))
    configure = subprocess.run(['cmake', '-S', str(source), '-B', str(build), '-G', 'Unix Makefiles',
                                '-DBUILD_TESTING=OFF', f'-DPython3_EXECUTABLE={sys.executable}'],
                               env=env, text=True, capture_output=True, timeout=300)
    assert configure.returncode == 0, configure.stdout + configure.stderr
    targets = ['talker_base', 'managed_camera_base', 'everything_base',
               'src/talker.cpp.o', 'src/managed_camera.cpp.o', 'src/everything.cpp.o']
    compiled = subprocess.run(['make', '-C', str(build), *targets], env=env, text=True,
                              capture_output=True, timeout=600)
    assert compiled.returncode == 0, compiled.stdout + compiled.stderr
    assert 'warning' not in compiled.stderr, compiled.stderr


def test_component_packages_register_each_node_and_compile(tmp_path: Path) -> None:
    """``nodl new --component``: each node a library whose class registers itself as a component,
    run alone by the executable rclcpp_components_register_node makes (real configure, stand-ins)."""
    with pytest.raises(ScaffoldError, match='--component needs --build-type ament_cmake'):
        plan_package('demo_nodes', load_nodes(SOURCES, 'ament_python'), 'ament_python', component=True)
    result = plan_package('demo_nodes', load_nodes(SOURCES[:2], 'ament_cmake'), 'ament_cmake',
                          component=True)
    files = {f.path: f.text for f in result.files}
    assert '<depend>rclcpp_components</depend>' in files['package.xml']
    assert 'rclcpp_components' not in {f.path: f.text for f in plan('ament_cmake').files}['package.xml']
    for exe, cls in (('talker', 'Talker'), ('managed_camera', 'ManagedCamera')):
        assert files[f'src/{exe}.cpp'].endswith(f'RCLCPP_COMPONENTS_REGISTER_NODE(demo_nodes::{cls})\n')
        assert 'int main(' not in files[f'src/{exe}.cpp']
    write_package(result, str(tmp_path / 'src'))
    source, build = tmp_path / 'src' / 'demo_nodes', tmp_path / 'build'
    env = dict(os.environ)
    env.pop('MAKEFLAGS', None)
    env.update(AMENT_PREFIX_PATH=str(VENV),
               CMAKE_PREFIX_PATH=os.pathsep.join([str(GENERATE / 'cpp_stub_packages'), str(VENV)]),
               PATH=os.pathsep.join([str(VENV / 'bin'), env.get('PATH', '')]))
    configure = subprocess.run(['cmake', '-S', str(source), '-B', str(build), '-G', 'Unix Makefiles',
                                '-DBUILD_TESTING=OFF', f'-DPython3_EXECUTABLE={sys.executable}'],
                               env=env, text=True, capture_output=True, timeout=300)
    assert configure.returncode == 0, configure.stdout + configure.stderr
    assert (build / 'rclcpp_components_registered.txt').read_text().splitlines() == [
        'demo_nodes::Talker talker_component talker',
        'demo_nodes::ManagedCamera managed_camera_component managed_camera']
    compiled = subprocess.run(['make', '-C', str(build), 'src/talker.cpp.o', 'src/managed_camera.cpp.o'],
                              env=env, text=True, capture_output=True, timeout=600)
    assert compiled.returncode == 0, compiled.stdout + compiled.stderr
    assert 'warning' not in compiled.stderr, compiled.stderr


def test_python_package_files_keep_ament_flake8s_line_length(tmp_path: Path) -> None:
    """The lint test the package carries (ament_flake8: 99 columns) passes on every file
    `nodl new` writes, generated bases included (checked with ruff's pycodestyle rules)."""
    write_package(plan('ament_python'), str(tmp_path))
    ruff = shutil.which('ruff', path=str(VENV / 'bin')) or shutil.which('ruff')
    assert ruff, 'ruff is part of the test extra'
    lint = subprocess.run([ruff, 'check', '--isolated', '--no-cache', '--select', 'E,W,F',
                           '--line-length', '99', str(tmp_path / 'demo_nodes')],
                          capture_output=True, text=True, timeout=120)
    assert lint.returncode == 0, lint.stdout + lint.stderr


# -- package names, --license, --maintainer ---------------------------------------------------

@pytest.mark.parametrize('package, why', [
    ('class', 'Python and a C++ keyword'), ('def', 'a Python keyword'), ('lambda', 'a Python keyword'),
    ('int', 'a C++ keyword'), ('namespace', 'a C++ keyword'), ('new', 'a C++ keyword'),
    ('a__b', 'not a valid ROS package name'), ('a', 'not a valid ROS package name')])
def test_package_names_that_are_keywords_or_break_rep_144_are_refused(package: str, why: str) -> None:
    import re

    with pytest.raises(ScaffoldError, match=re.escape(why)):
        plan('ament_python', package)


AUTHOR = ('Jane Doe', 'jane.doe@example.com')
TEMPLATES = FIXTURES / 'scaffold' / 'ament_copyright'
#: SPDX id -> ament_copyright's template of the license's file header.
SPDX_TEMPLATES = {'Apache-2.0': 'apache2', 'BSD-2-Clause': 'bsd_2clause', 'BSD-3-Clause': 'bsd_3clause',
                  'BSL-1.0': 'boost1', 'GPL-3.0-or-later': 'gplv3', 'LGPL-3.0-or-later': 'lgplv3',
                  'MIT': 'mit', 'MIT-0': 'mit0'}


def ament_copyright_accepts(text: str, template: str) -> tuple[str, str] | None:
    """``(years, holder)`` when ``text`` passes ament_copyright's documented rules, else None.

    The rules: past a shebang or coding line and empty lines, a block of comment
    lines with one token (``#`` or ``//``), the token and one character cut from
    each line; in it a ``copyright [(c)] YEARS HOLDER`` line; the text after it
    holds every part of the license's header template (split at its
    placeholders), in order, once runs of white space are one space.
    """
    import re

    lines = text.splitlines()
    while lines and (lines[0].startswith('#!') or 'coding' in lines[0] or not lines[0].strip()):
        lines.pop(0)
    if not lines:
        return None
    token = '//' if lines[0].startswith('//') else '#' if lines[0].startswith('#') else None
    if token is None:
        return None
    block = []
    for line in lines:
        if not line.startswith(token):
            break
        block.append(line[len(token) + 1:])
    body = '\n'.join(block)
    found = re.search(r'^\s*copyright(?:\s+\(c\))?\s+(\d{4}(?:-\d{4})?(?:,\s*\d{4}(?:-\d{4})?)*),?'
                      r'\s+([^\n]+)$', body, re.IGNORECASE | re.MULTILINE)
    if not found:
        return None
    rest = ' '.join(body[found.end():].split())
    at = -1
    for part in re.split(r'\{copyright_holder\}|\{copyright\}', template):
        part = ' '.join(part.split())
        if not part:
            continue
        index = rest.find(part)
        if index <= at:
            return None
        at = index
    return found[1], found[2]


@pytest.mark.parametrize('spdx', sorted(SPDX_TEMPLATES))
def test_license_and_maintainer_go_into_package_xml_and_headers_ament_copyright_accepts(
        spdx: str) -> None:
    from catkin_pkg.package import parse_package_string

    from nodl.scaffold import authorship

    template = (TEMPLATES / f'{SPDX_TEMPLATES[spdx]}_header.txt').read_text(encoding='utf-8')
    author = authorship(spdx.lower(), AUTHOR, year=2025)  # any case of the SPDX id
    for build_type in ('ament_python', 'ament_cmake'):
        result = plan_package('demo_nodes', load_nodes(SOURCES, build_type), build_type, author=author)
        files = {f.path: f for f in result.files}
        package = parse_package_string(files['package.xml'].text)
        package.validate()
        assert package.licenses == [spdx]
        assert [(m.name, m.email) for m in package.maintainers] == [AUTHOR]
        sources = [f for f in result.files if f.path.endswith(('.py', '.cpp')) and f.text.strip()
                   and not f.path.endswith('_base.py')]
        assert sources
        for item in sources:
            assert ament_copyright_accepts(item.text, template) == ('2025', 'Jane Doe'), item.path
        # the checker is no pushover: another license's notice, or none, fails it
        other = (TEMPLATES / ('mit_header.txt' if spdx != 'MIT' else 'apache2_header.txt')).read_text()
        assert ament_copyright_accepts(sources[0].text, other) is None
        assert ament_copyright_accepts('"""No header."""\n', template) is None
        if build_type == 'ament_python':
            assert f'license={spdx!r}' in files['setup.py'].text
            assert "maintainer_email='jane.doe@example.com'" in files['setup.py'].text
            assert '@pytest.mark.skip' not in files['test/test_copyright.py'].text
        else:
            assert 'ament_cmake_copyright_FOUND' not in files['CMakeLists.txt'].text


def test_without_a_license_the_copyright_test_says_how_to_get_one() -> None:
    files = {f.path: f.text for f in plan('ament_python').files}
    assert '@pytest.mark.skip' in files['test/test_copyright.py']
    assert '--license SPDX --maintainer NAME EMAIL' in files['test/test_copyright.py']
    assert 'Copyright' not in files['demo_nodes/talker.py']


@pytest.mark.parametrize('license, maintainer, message', [
    ('GPL-2.0-only', AUTHOR, "is not a license whose file headers ament_copyright checks; use one of: "
                             "Apache-2.0, BSD-2-Clause"),
    ('apache2', AUTHOR, r'\(give the SPDX id\)'),
    ('MIT', None, '--license needs --maintainer NAME EMAIL'),
    (None, ('Jane Doe', 'jane@localhost'), 'with a full domain'),
    (None, ('Jane Doe', 'jane.example.com'), 'with a full domain'),
    (None, ('Jane\nDoe', 'jane@example.com'), 'on one line'),
    (None, ('', 'jane@example.com'), 'give a name'),
])
def test_unknown_licenses_and_bad_maintainers_are_refused(license: str | None,
                                                          maintainer: tuple[str, str] | None,
                                                          message: str) -> None:
    from nodl.scaffold import authorship

    with pytest.raises(ScaffoldError, match=message):
        authorship(license, maintainer)


# -- required parameters -----------------------------------------------------------------------

def test_a_required_parameter_gets_a_commented_placeholder_in_the_parameter_and_launch_files() -> None:
    import xml.etree.ElementTree as ET

    import yaml

    files = {f.path: f.text for f in plan('ament_python').files}
    params = files['config/everything.params.yaml']
    assert ('    # required_scale: <double>  # required: set it here (uncomment) or with '
            '--ros-args -p required_scale:=VALUE') in params.splitlines()
    assert 'required_scale' not in str(yaml.safe_load(params))  # only a comment
    launch = files['launch/demo_nodes.launch.xml']
    parser = ET.XMLParser(target=ET.TreeBuilder(insert_comments=True))
    root = ET.fromstring(launch, parser=parser)
    everything = root.find("node[@exec='everything']")
    assert everything is not None
    comments = [c.text for c in everything if c.tag is ET.Comment]
    assert comments == [' <param name="required_scale" value="<double>"/>  required: set it here or '
                        'in config/everything.params.yaml; everything does not start without it ']
    talker = root.find("node[@exec='talker']")
    assert talker is not None and not [c for c in talker if c.tag is ET.Comment]


# -- the linters the package's own tests run -------------------------------------------------------

BUILTINS = FIXTURES / 'scaffold' / 'builtin_names.nodl.yaml'


def _lint(tool: str, cwd: Path) -> subprocess.CompletedProcess[str]:
    """Run ament's linter ``tool`` (its console script: its own configuration and plugins)."""
    return subprocess.run([str(VENV / 'bin' / tool)], cwd=cwd, capture_output=True, text=True,
                          timeout=300)


@pytest.mark.parametrize('license', [None, 'Apache-2.0'])
def test_python_packages_pass_ament_flake8_and_ament_pep257(license: str | None,
                                                            tmp_path: Path) -> None:
    """The real ament_flake8 (its ament_flake8.ini, every flake8 plugin it expects) and
    ament_pep257 (pydocstyle) pass on every file of a created package, the generated bases
    included; a parameter named like a builtin (``id``, ``list``, ``type``) included."""
    from nodl.scaffold import authorship

    plugins = subprocess.run([str(VENV / 'bin' / 'flake8'), '--version'], capture_output=True,
                             text=True, timeout=60).stdout.replace('-\n', '-')
    for plugin in ('flake8-blind-except', 'flake8-builtins', 'flake8-class-newline',
                   'flake8-comprehensions', 'flake8-deprecated', 'flake8-docstrings',
                   'flake8-import-order', 'flake8-quotes'):
        assert plugin in plugins, plugins
    author = authorship(license, AUTHOR if license else None)
    nodes = load_nodes(SOURCES + [[str(BUILTINS)]], 'ament_python')
    write_package(plan_package('demo_nodes', nodes, 'ament_python', author=author), str(tmp_path))
    package = tmp_path / 'demo_nodes'
    for tool in ('ament_flake8', 'ament_pep257'):
        result = _lint(tool, package)
        assert result.returncode == 0, tool + '\n' + result.stdout + result.stderr
    assert 'demo_nodes/builtin_names_base.py' in _lint('ament_flake8', package).stdout
    # and they are no pushovers: a builtin as an argument, a docstring out of style, fail them
    (package / 'demo_nodes' / 'extra.py').write_text(
        '"""Extra."""\n\n\ndef twice(id):\n    """Returns twice the id."""\n    return 2 * id\n',
        encoding='utf-8')
    flake8 = _lint('ament_flake8', package)
    assert flake8.returncode == 1 and 'A002' in flake8.stdout, flake8.stdout
    assert _lint('ament_pep257', package).returncode == 1


def _hostile_nodes(build_type: str) -> list:  # type: ignore[type-arg]
    """tests/fixtures/scaffold/hostile_text.nodl.yaml resolved with its validation bypassed (its
    NODL219/NODL220 errors dropped), as a running node's descriptors give such text."""
    from nodl.composition.resolved import resolve_report
    from nodl.loading import CheckedSource, check_source
    from nodl.scaffold import BUILD_TYPES, NodeSource
    from nodl.validation.kinds import Kind

    path = str(FIXTURES / 'scaffold' / 'hostile_text.nodl.yaml')
    report = check_source(Path(path), kind=Kind.NODE, file=path)
    assert {d.code for d in report.diagnostics} == {'NODL219', 'NODL220'}
    node, _ = resolve_report(CheckedSource(path, Kind.NODE, report.data, []),
                             client_library=BUILD_TYPES[build_type])
    assert node is not None
    return [NodeSource('hostile', path, node, [])]


@pytest.mark.parametrize('build_type', ['ament_python', 'ament_cmake'])
def test_hostile_descriptions_reach_no_written_file_raw(build_type: str) -> None:
    """Descriptions holding control and bidi characters, line separators and what ends a
    comment or string (*/, -->, ''', ${...}, ]=]) in every file nodl new writes: none holds
    one raw; each still parses (Python, XML, YAML); comments stay on one line; setup.py's
    description (the package metadata) shows them as visible escapes."""
    import ast
    import re
    import xml.etree.ElementTree as ET

    import yaml

    from nodl.text_safety import UNSAFE

    files = {f.path: f.text for f in plan_package('hostile_pkg', _hostile_nodes(build_type),
                                                    build_type).files}
    for path, text in files.items():
        if path.startswith('nodl/'):
            continue  # the definition, copied as written (its escapes are YAML's)
        assert UNSAFE.search(text) is None and not re.search('[\u2028\u2029]', text), path
        if path.endswith('.py'):
            ast.parse(text, path)
        elif path.endswith('.xml'):
            ET.fromstring(text.encode('utf-8'))
        elif path.endswith('.yaml'):
            yaml.safe_load(text)
    params = files['config/hostile.params.yaml']
    assert "# Gain \\u2066 \\x1b]0;title\\x07 ''' \"\"\" # not: a key" in params
    assert yaml.safe_load(params) == {'/hostile': {'ros__parameters': {'gain': 1.0}}}
    launch = ET.fromstring(files['launch/hostile_pkg.launch.xml'].encode('utf-8'))
    assert [n.get('name') for n in launch.iter('node')] == ['hostile']
    assert 'Reads \\x1b[2J a laser &#x202E; txt.exe */ --&gt; ${CMAKE_X} ") ]=]' in files['package.xml']
    if build_type == 'ament_python':
        (setup,) = [n for n in ast.walk(ast.parse(files['setup.py'])) if isinstance(n, ast.keyword)
                    and n.arg == 'description']
        assert ast.literal_eval(setup.value) == \
            'Reads \\x1b[2J a laser \\u202e txt.exe */ --> ${CMAKE_X} ") ]=] \\ end'
        assert files['setup.cfg'].count('\n') < 10
    else:
        cmake = files['CMakeLists.txt']
        assert 'a laser' not in cmake and '"nodl/hostile_text.nodl.yaml"' in cmake


def test_cmake_strings_escape_what_cmake_reads() -> None:
    """CMake quoted arguments: backslash, quote, $ (a variable) and line breaks escaped; a control
    or bidi character CMake has no escape for is refused (no name nodl new writes holds one)."""
    from nodl.scaffold.cmake_package import _cmake_string

    assert _cmake_string('a"b${X}c\\d\te\nf') == '"a\\"b\\${X}c\\\\d\\te\\nf"'
    for bad in ('x\u202e', 'x\x1b', 'x\x85'):
        with pytest.raises(ValueError, match='cannot be written in CMakeLists.txt'):
            _cmake_string(bad)
