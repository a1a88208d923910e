"""Expanding ROS names against a node (as rcl does) and the reverse, for describe."""

from __future__ import annotations

import itertools

import pytest

from nodl.naming import (
    InvalidNameError,
    InvalidRemapRuleError,
    NodeNames,
    RemapRule,
    expand,
    expand_name,
    full_name_error,
    fully_qualified,
    join_name,
    namespace_error,
    node_fqn,
    node_name_after_remaps,
    node_name_error,
    node_namespace_after_remaps,
    parse_remap_rule,
    parse_remap_rules,
    relativize,
    resolve_name,
    split_name,
    topic_name_error,
)


@pytest.mark.parametrize('namespace, name, fqn', [
    ('/', 'driver', '/driver'),
    ('', 'driver', '/driver'),
    ('/robot', 'driver', '/robot/driver'),
    ('/robot/', 'driver', '/robot/driver'),
    ('robot', 'driver', '/robot/driver'),
    ('/a/b', 'driver', '/a/b/driver'),
])
def test_fully_qualified(namespace: str, name: str, fqn: str) -> None:
    assert fully_qualified(namespace, name) == fqn


@pytest.mark.parametrize('name, namespace, expected', [
    # private names
    ('~', '/robot', '/robot/driver'),
    ('~', '/', '/driver'),
    ('~/scan', '/robot', '/robot/driver/scan'),
    ('~/scan', '/', '/driver/scan'),
    ('~/a/b', '/x/y', '/x/y/driver/a/b'),
    # relative names
    ('scan', '/robot', '/robot/scan'),
    ('scan', '/', '/scan'),
    ('a/b', '/x/y', '/x/y/a/b'),
    ('driver', '/robot', '/robot/driver'),
    # absolute names stay
    ('/scan', '/robot', '/scan'),
    ('/scan', '/', '/scan'),
    ('/robot/driver/scan', '/other', '/robot/driver/scan'),
    # substitutions
    ('{node}', '/robot', '/robot/driver'),
    ('{node}/scan', '/robot', '/robot/driver/scan'),
    ('{node}/scan', '/', '/driver/scan'),
    ('/{node}/scan', '/robot', '/driver/scan'),
    ('{ns}/scan', '/robot', '/robot/scan'),
    ('{namespace}/scan', '/a/b', '/a/b/scan'),
    ('{ns}', '/robot', '/robot'),
    ('scan/{node}', '/robot', '/robot/scan/driver'),
    ('{namespace}/{node}/x', '/r', '/r/driver/x'),
])
def test_expand(name: str, namespace: str, expected: str) -> None:
    assert expand(name, 'driver', namespace) == expected


def test_expand_tolerates_namespaces_written_without_or_with_extra_slashes() -> None:
    assert expand('scan', 'driver', 'robot') == '/robot/scan'
    assert expand('scan', 'driver', '/robot/') == '/robot/scan'
    assert expand('~/scan', 'driver', 'robot/') == '/robot/driver/scan'


_NAMES = ['x', 'x/y', '/x', '/x/y', '~', '~/x', '~/x/y', '{node}', '{node}/x', 'x/{node}',
          '{ns}/x', '{namespace}/x', '{namespace}/{node}', 'drv', 'drv/x', 'a/x']
_NAMESPACES = ['/', '/a', '/a/b']


@pytest.mark.parametrize('name, namespace', list(itertools.product(_NAMES, _NAMESPACES)))
def test_expand_agrees_with_rcl(name: str, namespace: str) -> None:
    """rcl itself (through rclpy) is the reference for every valid namespace."""
    from rclpy.expand_topic_name import expand_topic_name

    assert expand(name, 'drv', namespace) == expand_topic_name(name, 'drv', namespace)


@pytest.mark.parametrize('name, namespace, expected', [
    ('/robot/driver', '/robot', '~'),
    ('/robot/driver/scan', '/robot', '~/scan'),
    ('/robot/driver/a/b', '/robot', '~/a/b'),
    ('/robot/scan', '/robot', 'scan'),
    ('/robot/sub/scan', '/robot', 'sub/scan'),
    ('/scan', '/robot', '/scan'),
    ('/other/scan', '/robot', '/other/scan'),
    # a sibling whose name merely starts with the node's name is not under the node
    ('/robot/driver2/scan', '/robot', 'driver2/scan'),
    ('/robotics/scan', '/robot', '/robotics/scan'),
    # the namespace itself is not "under" it
    ('/robot', '/robot', '/robot'),
    # root namespace: names under the node are private, the rest stays absolute
    ('/driver', '/', '~'),
    ('/driver/scan', '/', '~/scan'),
    ('/scan', '/', '/scan'),
    ('/a/b', '/', '/a/b'),
    ('/x/y/driver/scan', '/x/y', '~/scan'),
    ('/x/y/scan', '/x/y', 'scan'),
    ('/x/scan', '/x/y', '/x/scan'),
])
def test_relativize(name: str, namespace: str, expected: str) -> None:
    assert relativize(name, 'driver', namespace) == expected


@pytest.mark.parametrize('name', ['/driver', '/driver/scan', '/scan', '/robot/driver',
                                  '/robot/driver/scan', '/robot/scan', '/robot/driver2/x',
                                  '/robotics/x', '/a/b/c', '/robot'])
@pytest.mark.parametrize('namespace', ['/', '/robot', '/robot/', 'robot'])
def test_relativize_then_expand_gives_the_name_back(name: str, namespace: str) -> None:
    short = relativize(name, 'driver', namespace)
    assert expand(short, 'driver', namespace) == name
    assert len(short) <= len(name)


# -- expand_name: rcl's expansion with rcl's validation --------------------------------------

@pytest.mark.parametrize('name, namespace', list(itertools.product(_NAMES, _NAMESPACES)))
def test_expand_name_agrees_with_rcl(name: str, namespace: str) -> None:
    from rclpy.expand_topic_name import expand_topic_name

    assert expand_name(name, 'drv', namespace) == expand_topic_name(name, 'drv', namespace)


@pytest.mark.parametrize('name, node_name, namespace', [
    ('', 'drv', '/'), ('a b', 'drv', '/'), ('x/', 'drv', '/'), ('1x', 'drv', '/'),
    ('a/1b', 'drv', '/'), ('~xy', 'drv', '/'), ('a/~', 'drv', '/'), ('{foo}', 'drv', '/'),
    ('{1a}', 'drv', '/'), ('{a', 'drv', '/'), ('a}', 'drv', '/'), ('{a/b}', 'drv', '/'),
    ('{}', 'drv', '/'), ('{a{b}}', 'drv', '/'), ('x', '1drv', '/'), ('x', 'd-rv', '/'),
    ('x', '', '/'), ('x', 'drv', '/a/'), ('x', 'drv', '/a//b'), ('x', 'drv', '/1a'),
    ('x', 'drv', '/a b'),
])
def test_expand_name_refuses_what_rcl_refuses_with_its_reason(name: str, node_name: str,
                                                              namespace: str) -> None:
    from rclpy.expand_topic_name import expand_topic_name

    with pytest.raises(ValueError) as by_rcl:
        expand_topic_name(name, node_name, namespace)
    with pytest.raises(InvalidNameError) as ours:
        expand_name(name, node_name, namespace)
    assert ours.value.reason in str(by_rcl.value)
    assert str(ours.value).startswith(f"{ours.value.what} '{ours.value.name}' is invalid: ")


def test_expand_name_takes_the_namespace_as_a_node_does() -> None:
    # rcl_node_init: '' is '/', a relative namespace gets its leading '/'
    assert expand_name('x', 'drv', '') == '/x'
    assert expand_name('~/x', 'drv', 'a/b') == '/a/b/drv/x'


@pytest.mark.parametrize('name', ['/x', '/a/b_c/d', '/_x', '/x1/y2'])
def test_full_names_that_rmw_accepts(name: str) -> None:
    from rclpy.validate_full_topic_name import validate_full_topic_name

    assert validate_full_topic_name(name) and full_name_error(name) is None


@pytest.mark.parametrize('name', ['', 'x', '/x/', '//x', '/a//b', '/1a', '/a/1b', '/a-b', '/~',
                                  '/{x}', '/' + 'x' * 300])
def test_full_names_that_rmw_refuses(name: str) -> None:
    from rclpy.exceptions import InvalidTopicNameException
    from rclpy.validate_full_topic_name import validate_full_topic_name

    with pytest.raises(InvalidTopicNameException) as by_rmw:
        validate_full_topic_name(name)
    problem = full_name_error(name)
    # the same rule (rmw prints its length limit as the macro's text, '255U - 8U')
    assert problem is not None and problem.split(',')[0].split("'")[0] in str(by_rmw.value)


def test_full_name_error_accepts_exactly_what_rmw_accepts() -> None:
    # full_name_error accepts the common valid name by a pattern before its rule-by-rule
    # checks: both must accept exactly what rmw accepts, at every length around the limit.
    import random

    from rclpy.exceptions import InvalidTopicNameException
    from rclpy.validate_full_topic_name import validate_full_topic_name

    rng = random.Random(5)
    names = [''.join(rng.choice('//aZ_1.~') for _ in range(rng.randint(0, 8))) for _ in range(5000)]
    names += ['/' + 'x' * n for n in (245, 246, 247, 248)] + ['/a\n', '/é']
    for name in names:
        try:
            accepted = bool(validate_full_topic_name(name))
        except InvalidTopicNameException:
            accepted = False
        assert (full_name_error(name) is None) == accepted, name


@pytest.mark.parametrize('namespace', ['/', '/a', '/a/b', '', 'a', '/a/', '//', '/1', '/a b'])
def test_namespaces_as_rmw_validates_them(namespace: str) -> None:
    from rclpy.exceptions import InvalidNamespaceException
    from rclpy.validate_namespace import validate_namespace

    try:
        validate_namespace(namespace)
    except InvalidNamespaceException as exc:
        problem = namespace_error(namespace)
        assert problem is not None and problem.split(',')[0] in str(exc)
    else:
        assert namespace_error(namespace) is None


@pytest.mark.parametrize('node_name', ['drv', '_d', 'd1', '', '1d', 'd-x', 'd/x', 'x' * 256])
def test_node_names_as_rmw_validates_them(node_name: str) -> None:
    from rclpy.exceptions import InvalidNodeNameException
    from rclpy.validate_node_name import validate_node_name

    try:
        validate_node_name(node_name)
    except InvalidNodeNameException as exc:
        problem = node_name_error(node_name)
        assert problem is not None and problem.split("'")[0] in str(exc)
    else:
        assert node_name_error(node_name) is None


def test_tilde_quirk_of_rcl_is_kept() -> None:
    # rcl's check skips the last character, so '~x' passes (and expands oddly); '~xy' does not
    assert topic_name_error('~x') is None
    assert expand_name('~x', 'drv', '/ns') == '/ns/drvx'
    assert topic_name_error('~xy') is not None


# -- remapping rules ---------------------------------------------------------------------------


@pytest.mark.parametrize('text, rule', [
    ('a:=b', RemapRule('name', 'a', 'b', None, 'a:=b')),
    ('/a/b:=~/c', RemapRule('name', '/a/b', '~/c', None, '/a/b:=~/c')),
    ('~/x:=/y', RemapRule('name', '~/x', '/y', None, '~/x:=/y')),
    ('drv:a:=b', RemapRule('name', 'a', 'b', 'drv', 'drv:a:=b')),
    ('rostopic://a:=b', RemapRule('topic', 'a', 'b', None, 'rostopic://a:=b')),
    ('drv:rosservice://a:=b', RemapRule('service', 'a', 'b', 'drv', 'drv:rosservice://a:=b')),
    ('__ns:=/x/y', RemapRule('namespace', None, '/x/y', None, '__ns:=/x/y')),
    ('__ns:=/', RemapRule('namespace', None, '/', None, '__ns:=/')),
    ('drv:__node:=n', RemapRule('node', None, 'n', 'drv', 'drv:__node:=n')),
    ('__name:=n', RemapRule('node', None, 'n', None, '__name:=n')),
    ('ros:a:=b', RemapRule('name', 'a', 'b', 'ros', 'ros:a:=b')),
    ('rostopic:a:=b', RemapRule('name', 'a', 'b', 'rostopic', 'rostopic:a:=b')),
    ('a_b/_c:=d_', RemapRule('name', 'a_b/_c', 'd_', None, 'a_b/_c:=d_')),
])
def test_parse_remap_rule(text: str, rule: RemapRule) -> None:
    assert parse_remap_rule(text) == rule
    assert str(rule) == text


def test_a_rule_built_in_code_prints_as_a_rule() -> None:
    assert str(RemapRule('service', 'a', 'b', 'drv')) == 'drv:rosservice://a:=b'
    assert str(RemapRule('namespace', None, '/x')) == '__ns:=/x'
    assert str(RemapRule('node', None, 'n', 'drv')) == 'drv:__node:=n'
    assert RemapRule('name', 'a', 'b', 'drv').applies_to('drv')
    assert not RemapRule('name', 'a', 'b', 'drv').applies_to('other')
    assert RemapRule('name', 'a', 'b').applies_to('anyone')


def test_parse_remap_rules_from_a_command_line() -> None:
    argv = ['prog', 'x:=old', '--ros-args', '-p', 'p:=1', '--params-file', 'f.yaml', '-r', 'a:=b',
            '--log-level', 'debug', '--enable-rosout-logs', '--remap', '__ns:=/n', '-e', '/e',
            '--', 'not_a_rule', 'y:=old', '--ros-args', '-r', 'c:=d']
    assert [str(r) for r in parse_remap_rules(argv)] == ['x:=old', 'a:=b', '__ns:=/n', 'y:=old',
                                                          'c:=d']
    # a parameter value that looks like a rule is not one
    assert parse_remap_rules(['--ros-args', '-p', 'a:=b']) == []


def test_parse_remap_rules_passes_rules_through_and_takes_none() -> None:
    rule = RemapRule('name', 'a', 'b')
    assert parse_remap_rules([rule, 'c:=d']) == [rule, parse_remap_rule('c:=d')]
    assert parse_remap_rules(None) == [] and parse_remap_rules([]) == []


@pytest.mark.parametrize('args, message', [
    (['--ros-args', '-r'], '-r at the end of the arguments has no rule'),
    (['--ros-args', '--remap', 'a'], "invalid remapping 'a'"),
    (['a'], "invalid remapping 'a'"),
    (['a*:=b'], 'wildcards are not implemented'),
    (['a:=\\1'], 'backreferences are not implemented'),
    (['__ns:=x'], 'must be fully qualified'),
    (['__x:=y'], 'only __ns, __node and __name'),
])
def test_malformed_rules_say_what_is_expected(args: list[str], message: str) -> None:
    with pytest.raises(InvalidRemapRuleError, match=message.replace('\\', '\\\\')) as info:
        parse_remap_rules(args)
    assert isinstance(info.value, ValueError)
    assert 'expected [NODE:]FROM:=TO' in str(info.value)


# -- the node's own name and resolution --------------------------------------------------------


def test_the_issue_example() -> None:
    """__ns and __node change the node's own name; they are not topic remaps."""
    rules = ['__ns:=/robot', '__node:=foo']
    assert node_fqn('driver', '/ns', rules) == '/robot/foo'
    assert resolve_name('scan', 'driver', '/ns', rules) == '/robot/scan'
    assert resolve_name('~/scan', 'driver', '/ns', rules) == '/robot/foo/scan'
    assert resolve_name('__ns', 'driver', '/ns', rules) == '/robot/__ns'


def test_ns_rule_scope_is_the_renamed_node() -> None:
    rules = ['drv:__node:=foo', 'drv:__ns:=/not_me', 'foo:__ns:=/me']
    assert node_name_after_remaps('drv', rules) == 'foo'
    assert node_namespace_after_remaps('drv', '/ns', rules) == '/me'
    assert node_namespace_after_remaps('other', '', rules) == '/'


def test_node_names_from_a_running_node_resolve_without_renaming_again() -> None:
    # a:__node:=b, b:__node:=c makes node 'a' into 'b' (one rule applies); the running 'b'
    # resolves with its final name
    rules = tuple(parse_remap_rules(['a:__node:=b', 'b:__node:=c', 'b:x:=y']))
    assert node_fqn('a', '/', rules) == '/b'
    running = NodeNames('b', '/', rules)
    assert running.fqn == '/b' and running.resolve('x') == '/y'
    assert NodeNames.create('a', '/', rules) == running


def test_rule_for_names_the_rule_that_applies() -> None:
    names = NodeNames.create('drv', '/ns', ['rostopic://a:=t', 'a:=both'])
    rule = names.rule_for('a')
    assert rule is not None and str(rule) == 'rostopic://a:=t'
    rule = names.rule_for('a', service=True)
    assert rule is not None and str(rule) == 'a:=both'
    assert names.rule_for('b') is None


def test_resolve_name_refuses_a_name_rmw_would_refuse() -> None:
    with pytest.raises(InvalidNameError, match="resolved name '//x' is invalid: .*repeated '/'"):
        resolve_name('{ns}/x', 'drv', '/')
    with pytest.raises(InvalidNameError, match="node namespace '/a/' is invalid"):
        node_fqn('drv', '/ns', ['__ns:=/a/'])


@pytest.mark.parametrize('namespace, name, fqn', [('/', 'n', '/n'), ('/a', 'n', '/a/n'),
                                                   ('/a/b', 'n', '/a/b/n'), ('', 'n', '/n')])
def test_join_and_split(namespace: str, name: str, fqn: str) -> None:
    assert join_name(namespace, name) == fqn
    assert split_name(fqn) == (namespace or '/', name)


# -- no other module joins ROS names by hand ---------------------------------------------------

#: A string concatenation or f-string that glues a name, node or namespace to a '/'.
_HAND_JOIN = (r"""(\+\s*['"]/['"]|['"]/['"]\s*\+|rstrip\(['"]/['"]\)\s*\+|"""
              r"""f['"][^'"]*\{[^}]*(namespace|ns|node|name)[^}]*\}/\{|f['"]/\{[^}]*(namespace|node|name))""")
#: Lines that join with '/' but do not compute a ROS name the way rcl does, and why.
_NOT_ROS_NAMES = {
    # interface types (package/msg/Name) and the C++ header of one
    ('nodl/composition/entities.py', "return f'{self.package}/{self.namespace}/{self.name}'"),
    ('nodl/generate/cpp/text.py', "return f'{package}/{namespace}/{rosidl_file_stem(name)}.hpp'"),
    # a parameter file's node key as rcl_yaml_param_parser normalizes it (a pattern, not a name)
    ('nodl/launch/rcl_yaml.py', "name = key if key.startswith('/') else '/' + key"),
    # launch_ros's prefix_namespace: a pushed namespace may stay relative until the node is made
    ('nodl/launch/ros_actions.py', "combined = ('' if base == '/' else base) + '/' + namespace"),
    # SROS 2's own resolution of the names written in a policy profile (its XSL templates)
    ('nodl/policy/names.py', "return namespace if namespace.endswith('/') else namespace + '/'"),
    ('nodl/policy/names.py', "own = _delimited(namespace) + node + '/'"),
    # type names (pkg/msg/T), file paths in messages, a node's own prefix to test names against,
    # the diagnostic aggregator's status paths: not ROS graph names being built
    ('nodl/analysis/checks/definitions.py',
     "f'as DIR/{node.match.package}/{node.match.key}.nodl.yaml and give --definitions DIR)',"),
    ('nodl/analysis/checks/names.py',
     "return expanded.startswith(names.fqn.rstrip('/') + '/') or expanded in _CONTAINER_GLOBALS"),
    ('nodl/system/checks/definitions.py',
     "f'as DIR/{node.match.package}/{node.match.key}.nodl.yaml and give --definitions DIR)',"),
    ('nodl/system/checks/names.py',
     "return expanded.startswith(names.fqn.rstrip('/') + '/') or expanded in _CONTAINER_GLOBALS"),
    ('nodl/extract/targets.py',
     'Severity.INFO, f"component {node.plugin} is not recorded in {node.package}/{NODES_FILE}: a "'),
    ('nodl/interface_types/resolve.py', "return f'{self.package}/{self.namespace}/{self.name}'"),
    ('nodl/interface_types/resolve.py', "return sorted(f'{self.name}/{ns}/{name}' for ns, name in self.types"),
    ('nodl/interface_types/resolve.py', "files += [f'{namespace}/{e.name}' for e in entries if e.is_file()]"),
    ('nodl/interface_types/resolve.py', "tuple(f'{package_name}/{namespace}/{c}' for c in close), package)"),
    ('nodl/interface_types/tree.py', "raise UnknownTypeError(f'{package}/{namespace}/{name}')"),
    ('nodl/interface_types/tree.py', "raise InterfaceFileError(f'does not define {package}/{namespace}/{name}', path)"),
    ('nodl/interface_types/tree.py',
     "data = {'pkg_name': package, 'relative_input_file': f'{namespace}/{os.path.basename(path)}',"),
    ('nodl/interface_types/tree.py',
     'file = index.file(f\'{package}/{namespace}/{type_name.split("_", 1)[0]}\') or \'\''),
    ('nodl/interface_types/tree.py', "prefix = f'{package}/{namespace}/{base}'"),
    ('nodl/live/type_skew.py', "own = observed.fully_qualified_name + '/'  # the base's services (parameters...) last"),
    ('nodl/monitor/aggregator.py', "prefix = PREFIX + namespace.rstrip('/') + '/'"),
}


def test_no_module_outside_naming_joins_ros_names_by_hand() -> None:
    import re
    from pathlib import Path

    root = Path(__file__).resolve().parent.parent
    join = re.compile(_HAND_JOIN)
    found = []
    for path in sorted((root / 'nodl').rglob('*.py')):
        relative = path.relative_to(root).as_posix()
        if relative.startswith('nodl/naming/'):
            continue
        for number, line in enumerate(path.read_text(encoding='utf-8').splitlines(), 1):
            code = line.strip()
            if join.search(code) and re.search(r'namespace|node|\bns\b|name', code) \
                    and (relative, code) not in _NOT_ROS_NAMES:
                found.append(f'{relative}:{number}: {code}')
    assert not found, 'use nodl.naming (join_name, expand_name, resolve_name, node_fqn):\n' \
        + '\n'.join(found)


# -- declared_names: the inverse of resolution (describe --all --launch) -------------------


@pytest.mark.parametrize('final, node, namespace, rules, service, expected', [
    # a remap undone: the match side as the node declares it, then what else resolves there
    ('/shared/chat', 'talker', '/robot', ['chatter:=/shared/chat'], False,
     ['chatter', '/robot/chatter', '/shared/chat']),
    # the node renamed by __node: ~ stands for its final name
    ('/robot/talk1/x', 'talker', '/robot', ['__node:=talk1'], False,
     ['~/x', 'talk1/x', '/robot/talk1/x']),
    # a name a rule takes elsewhere cannot be declared to reach it
    ('/robot/chatter', 'talker', '/robot', ['chatter:=/shared/chat'], False, []),
    # outside the namespace: absolute only
    ('/other', 'talker', '/robot', [], False, ['/other']),
    # at the root every name is under the namespace: relative first
    ('/scan', 'a', '/', [], False, ['scan', '/scan']),
    # a rosservice:// rule applies to services only
    ('/srv2', 'n', '/', ['rosservice://srv:=srv2'], True, ['srv', '/srv', 'srv2', '/srv2']),
    ('/srv2', 'n', '/', ['rosservice://srv:=srv2'], False, ['srv2', '/srv2']),
    # a rule for another node does not apply
    ('/b', 'n', '/', ['other:a:=b'], False, ['b', '/b']),
])
def test_declared_names_resolve_back_to_the_final_name(final: str, node: str, namespace: str,
                                                       rules: list[str], service: bool,
                                                       expected: list[str]) -> None:
    from nodl.naming import NodeNames, declared_names

    names = NodeNames.create(node, namespace, rules)
    found = declared_names(final, names, service=service)
    assert found == expected
    for name in found:
        assert names.resolve(name, service=service) == final
