"""The C++ generator: golden files, determinism, naming, escaping, and its tables kept complete.

Golden files are under tests/fixtures/generate/cpp/; regenerate them with
``pytest tests/test_generate_cpp.py --update-golden`` and review the diff.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from conftest import FIXTURES, REPO
from nodl.generate import GenerateOptions, GenerationError, default_class_name, default_node_name, load_generators
from nodl.generate.cpp import CppGenerator, cpp_dependencies, generate_cpp, plan_cpp
from nodl.generate.cpp.parameter_code import CPP_PREDICATES
from nodl.generate.cpp.qos_code import CPP_POLICY_VALUES, qos_expression
from nodl.generate.cpp.text import comment_lines, cpp_value, rosidl_file_stem, string_literal
from nodl.generate.cpp.user import render_user_source
from nodl.model import QoSProfile
from nodl.system import resolve_node
from nodl.validation.validators import BUILTIN_NAMES
from nodl.vocabulary import QOS_ENUMS

GENERATE = FIXTURES / 'generate'
GOLDEN = GENERATE / 'cpp'
DEFINITIONS = ['talker', 'managed_camera', 'everything']


def options_for(path: Path, **extra: object) -> GenerateOptions:
    return GenerateOptions(default_class_name(str(path)), default_node_name(str(path)), **extra)  # type: ignore[arg-type]


def generated(name: str, text: str | None = None, **extra: object) -> dict[str, str]:
    path = GENERATE / f'{name}.nodl.yaml'
    source = path if text is None else text
    node = resolve_node(source, file=str(path), client_library='rclcpp')  # type: ignore[arg-type]
    return {f.path: f.text for f in generate_cpp(node, options_for(path, **extra))}


@pytest.mark.parametrize('name', DEFINITIONS)
def test_golden_base_files(name: str, golden) -> None:  # type: ignore[no-untyped-def]
    files = generated(name)
    assert sorted(files) == [f'{name}_base.cpp', f'{name}_base.hpp']
    for path, text in files.items():
        golden.check(text, GOLDEN / path)


@pytest.mark.parametrize('name', DEFINITIONS)
def test_golden_user_stub(name: str, golden) -> None:  # type: ignore[no-untyped-def]
    path = GENERATE / f'{name}.nodl.yaml'
    plan = plan_cpp(resolve_node(path, client_library='rclcpp'), options_for(path))
    golden.check(render_user_source(plan, default_class_name(name)), GOLDEN / f'{name}.cpp')


@pytest.mark.parametrize('name', DEFINITIONS)
def test_output_is_byte_identical_when_regenerated(name: str) -> None:
    assert generated(name) == generated(name)


def test_the_order_entries_are_written_in_does_not_change_the_names() -> None:
    text = (GENERATE / 'everything.nodl.yaml').read_text(encoding='utf-8')
    # swap two parameters' lines: identifiers and struct layout stay
    lines = text.splitlines()
    i = next(n for n, line in enumerate(lines) if line.strip().startswith('flag:'))
    j = next(n for n, line in enumerate(lines) if line.strip().startswith('count:'))
    lines[i], lines[j] = lines[j], lines[i]
    assert generated('everything', '\n'.join(lines) + '\n') == generated('everything')


def test_the_generator_is_registered_for_cpp() -> None:
    generators = load_generators()
    assert isinstance(generators.get('cpp'), CppGenerator)
    assert CppGenerator.CLIENT_LIBRARY == 'rclcpp'


def test_members_and_callbacks_are_collision_free_and_keyword_safe() -> None:
    header = generated('everything')['everything_base.hpp']
    # `class` is a keyword; `~/configure` would be rclcpp_lifecycle's on_configure
    assert 'int64_t class_{INT64_C(3)};' in header
    assert 'virtual void on_configure_2(' in header
    # `~/out` and `out` are both "out"; the one written as the identifier keeps it
    assert re.search(r'Publisher<std_msgs::msg::Int32>::SharedPtr pub_out_;', header)
    assert re.search(r'Publisher<std_msgs::msg::String>::SharedPtr pub_out_2_;', header)
    for suffix in ('goal', 'cancel', 'accepted'):
        assert f'on_fibonacci_{suffix}(' in header
    assert 'action_client_other_fibonacci_;' in header


def test_lifecycle_publishers_are_lifecycle_publishers_switched_on_activate() -> None:
    files = generated('managed_camera')
    header, source = files['managed_camera_base.hpp'], files['managed_camera_base.cpp']
    assert 'class ManagedCameraBase : public rclcpp_lifecycle::LifecycleNode' in header
    assert 'rclcpp_lifecycle::LifecyclePublisher<' in header
    assert 'rclcpp::Publisher<' not in header
    # entities on configure, not in the constructor
    constructor = source.split('::ManagedCameraBase(const rclcpp::NodeOptions')[0]
    assert 'create_entities();' not in constructor
    configure = source.split('::on_configure(')[1].split('}')[0]
    assert 'create_entities();' in configure
    activate = source.split('ManagedCameraBase::on_activate(')[1].split('\n}\n')[0]
    assert '->on_activate();' in activate and 'return handle_activate(state);' in activate


def test_every_declared_qos_policy_reaches_rclcpp_for_topics_and_services() -> None:
    source = generated('everything')['everything_base.cpp']
    assert ('rclcpp::QoS(rclcpp::KeepLast(7)).reliability(rclcpp::ReliabilityPolicy::Reliable)'
            '.durability(rclcpp::DurabilityPolicy::TransientLocal)'
            '.liveliness(rclcpp::LivelinessPolicy::Automatic)'
            '.deadline(rclcpp::Duration::from_nanoseconds(2000000000))'
            '.lifespan(rclcpp::Duration::from_nanoseconds(3000000000))'
            '.liveliness_lease_duration(rclcpp::Duration::from_nanoseconds(4000000000))') in source
    assert 'rclcpp::QoS(rclcpp::KeepAll()).reliability(rclcpp::ReliabilityPolicy::BestEffort)' \
        in source
    trigger = source.split('create_service<std_srvs::srv::Trigger>(')[1].split('});')[0]
    assert 'rclcpp::QoS(rclcpp::KeepLast(4)).reliability(rclcpp::ReliabilityPolicy::Reliable)' \
        in trigger
    configure = source.split('create_service<std_srvs::srv::SetBool>(')[1].split('});')[0]
    assert 'rclcpp::ServicesQoS()' in configure
    assert 'create_client<std_srvs::srv::Trigger>("~/remote", rclcpp::ServicesQoS())' in source


@pytest.mark.parametrize('policy', sorted(QOS_ENUMS))
def test_every_qos_value_of_the_vocabulary_has_an_rclcpp_enumerator(policy: str) -> None:
    enum, values = CPP_POLICY_VALUES[policy]
    assert enum.startswith('rclcpp::')
    assert set(values) == set(QOS_ENUMS[policy])


def test_system_default_history_keeps_the_depth() -> None:
    expr = qos_expression(QoSProfile('SYSTEM_DEFAULT', 'RELIABLE', depth=3))
    assert expr.startswith('rclcpp::QoS(rclcpp::QoSInitialization(RMW_QOS_POLICY_HISTORY_SYSTEM_DEFAULT, 3))')


def test_every_builtin_validator_has_a_cpp_translation() -> None:
    assert set(CPP_PREDICATES) == set(BUILTIN_NAMES)


def test_parameters_every_type_descriptor_range_and_required() -> None:
    source = generated('everything')['everything_base.cpp']
    assert 'rclcpp::ParameterValue(std::vector<uint8_t>{static_cast<uint8_t>(1), ' \
        'static_cast<uint8_t>(2), static_cast<uint8_t>(255)})' in source
    assert 'get_value<std::vector<uint8_t>>()' in source
    assert 'this->declare_parameter("group.inner.depth"' in source
    assert 'candidate.group.inner.depth = parameter.get_value<int64_t>();' in source
    assert 'rclcpp::ParameterType::PARAMETER_DOUBLE, descriptor);' in source  # required_scale
    assert 'catch (const rclcpp::exceptions::NoParameterOverrideProvided &)' in source
    assert 'descriptor.dynamic_typing = true;' in source
    count = source.split('// count\n')[1].split('this->declare_parameter')[0]
    assert 'descriptor.integer_range[0].from_value = INT64_C(0);' in count
    assert 'descriptor.integer_range[0].to_value = INT64_C(10);' in count
    limit_gt = source.split('// limit.gt\n')[1].split('this->declare_parameter')[0]
    assert 'descriptor.integer_range[0].from_value = INT64_C(11);' in limit_gt  # gt 10, integer
    read_only = source.split('// group.inner.depth\n')[1].split('this->declare_parameter')[0]
    assert 'descriptor.read_only = true;' in read_only


def test_validators_reject_with_the_tables_requirement_and_custom_ones_are_hooks() -> None:
    files = generated('everything')
    header, source = files['everything_base.hpp'], files['everything_base.cpp']
    assert '"invalid value for parameter \'count\': it must be between 0 and 10"' in source
    assert 'result.successful = result.reason.empty();' in source
    # validated before the set (on-set), committed after it (post-set)
    assert 'add_on_set_parameters_callback' in source and 'add_post_set_parameters_callback' in source
    post = source.split('::on_post_set_parameters(')[1].split('\n}\n')[0]
    assert '++params_.revision_;' in post and 'on_parameters_changed(snapshot);' in post
    assert 'namespace my_pkg\n{\nstd::string is_even(const rclcpp::Parameter & parameter);' in header
    assert 'my_pkg::is_even(rclcpp::Parameter("checked", params.checked))' in source


def test_string_literals_escape_everything_a_definition_can_hold() -> None:
    assert string_literal('a"b\\c') == '"a\\"b\\\\c"'
    assert string_literal('??=') == '"\\?\\?="'
    assert string_literal('\n\t') == '"\\n\\t"'
    # non-ASCII as octal (never \x, which would swallow the following hex digits)
    assert string_literal('é1') == '"\\303\\2511"'
    assert cpp_value('a\0b', 'string') == 'std::string("a\\000b", 3)'


def test_comments_cannot_be_escaped_from() -> None:
    lines = comment_lines('ends with a backslash \\\nnext */ line\r\nthird <b> & @param')
    assert lines == ['/// ends with a backslash &#92;', '/// next */ line',
                     '/// third &lt;b&gt; &amp; &#64;param']
    assert all(not line.rstrip().endswith('\\') for line in lines)


def test_hostile_names_and_descriptions_stay_inside_literals_and_comments() -> None:
    text = '''nodl_version: 2
base: node
main:
  nodl_version: 2
  description: "line one \\\\\\nint injected = 1; /* */ \\"quoted\\""
  parameters:
    "odd.name":
      type: string
      default_value: "\\" + evil() + \\""
      description: "ends with a backslash \\\\"
  publishers:
    - name: ~/out
      type: std_msgs/msg/String
      description: "*/ #include <evil>"
      qos: {history: KEEP_LAST, depth: 1, reliability: RELIABLE}
'''
    files = generated('talker', text)
    for body in files.values():
        for line in body.splitlines():
            stripped = line.strip()
            assert 'evil' not in stripped or stripped.startswith('//') or \
                re.search(r'"[^"]*\\"[^"]*evil', stripped), line
            assert not stripped.startswith('#include <evil>')
            if stripped.startswith('//'):
                assert not stripped.endswith('\\')


@pytest.mark.parametrize('name', ['LaserScan', 'WStrings', 'Int32', 'SetCameraInfo', 'UUID',
                                  'CameraInfo', 'BoundedPlainSequences', 'Fibonacci'])
def test_header_names_follow_rosidl(name: str) -> None:
    expected = {'LaserScan': 'laser_scan', 'WStrings': 'w_strings', 'Int32': 'int32',
                'SetCameraInfo': 'set_camera_info', 'UUID': 'uuid', 'CameraInfo': 'camera_info',
                'BoundedPlainSequences': 'bounded_plain_sequences', 'Fibonacci': 'fibonacci'}
    assert rosidl_file_stem(name) == expected[name]


def test_header_names_match_the_installed_interface_headers() -> None:
    import sys

    include = Path(sys.prefix) / 'include'
    checked = 0
    for package in ('std_msgs', 'sensor_msgs', 'test_msgs', 'std_srvs'):
        share = Path(sys.prefix) / 'share' / package
        for kind in ('msg', 'srv', 'action'):
            for idl in sorted((share / kind).glob('*.idl')):
                stem = rosidl_file_stem(idl.stem)
                assert (include / package / package / kind / f'{stem}.hpp').is_file(), idl
                checked += 1
    assert checked > 50


def test_dependencies_follow_what_the_node_uses() -> None:
    for name, expected in (
            ('talker', {'rclcpp', 'rcl_interfaces', 'std_msgs'}),
            ('managed_camera', {'rclcpp', 'rclcpp_lifecycle', 'rcl_interfaces', 'std_msgs',
                                'std_srvs'}),
            ('everything', {'rclcpp', 'rclcpp_action', 'rcl_interfaces', 'std_msgs', 'std_srvs',
                            'test_msgs'})):
        path = GENERATE / f'{name}.nodl.yaml'
        node = resolve_node(path, client_library='rclcpp')
        assert set(cpp_dependencies(node, options_for(path))) >= expected
        header = generated(name)[f'{name}_base.hpp']
        line = next(text for text in header.splitlines() if text.startswith('// nodl-dependencies:'))
        assert line.split(':', 1)[1].split() == cpp_dependencies(node, options_for(path))


def test_mixins_are_not_generated() -> None:
    node = resolve_node(REPO / 'examples' / 'camera_lifecycle.nodl.yaml', client_library='rclcpp')
    text = '\n'.join(f.text for f in generate_cpp(node, GenerateOptions('Camera', 'camera')))
    assert 'set_camera_info' not in text  # a mixin's service: other code provides it
    assert 'pub_image_raw_' in text


def test_component_option_includes_the_registration_macro() -> None:
    header = generated('talker', component=True)['talker_base.hpp']
    assert '#include "rclcpp_components/register_node_macro.hpp"' in header
    assert 'rclcpp_components' in header.splitlines()[2]
    assert 'explicit TalkerBase(const rclcpp::NodeOptions & options);' in header


@pytest.mark.parametrize('bad', [{'class_name': 'class'}, {'class_name': '3D'},
                                 {'namespace': 'a::int'}, {'namespace': 'a-b'}])
def test_unusable_names_are_generation_errors(bad: dict[str, str]) -> None:
    path = GENERATE / 'talker.nodl.yaml'
    node = resolve_node(path, client_library='rclcpp')
    options = {'class_name': 'Talker', 'node_name': 'talker', **bad}
    with pytest.raises(GenerationError):
        generate_cpp(node, GenerateOptions(**options))  # type: ignore[arg-type]


def test_control_bidi_and_trigraphs_in_comments_are_shown_not_kept() -> None:
    from nodl.text_safety import first_unsafe

    lines = comment_lines('swap \u202e here \x1b[2J and \x85 then ??/ and ??= end??')
    assert lines == ['/// swap &#92;u202e here &#92;x1b[2J and',  # NEL ends a line, as in Python
                     '///  then &#63;?/ and &#63;?= end&#63;?']
    assert all(first_unsafe(line) == -1 and '??' not in line for line in lines)
    # a literal keeps the bytes, as octal escapes, and no trigraph
    assert string_literal('\u202e??/') == '"\\342\\200\\256\\?\\?/"'
