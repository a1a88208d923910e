"""nodl.extract.cpp: rclcpp nodes read from C++ source with tree-sitter-cpp.

The accuracy tests read real nodes of public packages (tests/fixtures/extract/cpp/*, each with
its origin and licence) and compare with expected.yaml, written by hand against the source.
"""

from __future__ import annotations

import sys
from pathlib import Path

import pytest
import yaml

from nodl.extract.cpp import MAX_FILE_BYTES, extract_cpp, extract_cpp_package, qos_of_name
from nodl.extract.writer import GAP_MARKER, draft_text

FIXTURES = Path(__file__).parent / 'fixtures' / 'extract' / 'cpp'
CMAKE = Path(__file__).parent / 'fixtures' / 'extract' / 'cmake'
CASES = sorted(p.name for p in FIXTURES.iterdir() if (p / 'expected.yaml').exists())


def _entity(e):
    item = {'section': e.section, 'name': e.name, 'type': e.type, 'line': e.location.line}
    if e.qos:
        item['qos'] = e.qos.to_dict()
    if e.has_default:
        item['default'] = e.default_value
    if e.read_only:
        item['read_only'] = True
    if e.validation:
        item['validation'] = e.validation
    if e.gaps:
        item['gap'] = sorted({g.what for g in e.gaps})
    return item


def test_at_least_ten_real_nodes_with_origin_and_licence() -> None:
    assert len(CASES) >= 10
    for case in CASES:
        readme = (FIXTURES / case / 'README.md').read_text()
        assert 'repository: https://github.com/' in readme and 'commit: ' in readme and 'licence: ' in readme
        assert (FIXTURES / case / 'LICENSE').stat().st_size > 500


@pytest.mark.parametrize('case', CASES)
def test_real_node_matches_the_hand_checked_expectation(case: str) -> None:
    expected = yaml.safe_load((FIXTURES / case / 'expected.yaml').read_text())['nodes']
    extraction = extract_cpp([str(FIXTURES / case)])
    assert [n.name for n in extraction.nodes] == [n['class'] for n in expected]
    assert not [d for d in extraction.diagnostics if d.code in ('NODL934', 'NODL931')], \
        [str(d) for d in extraction.diagnostics]
    for node, want in zip(extraction.nodes, expected, strict=True):
        assert node.base == want['base']
        assert node.node_name == want['node_name']
        got = [_entity(e) for e in node.entities]
        assert got == [{k: v for k, v in e.items() if k != 'truth'} for e in want['entities']]
        for entity in node.entities:  # every entity carries its place, and every gap is located
            assert entity.location.line > 0 and entity.location.column > 0
            for gap in entity.gaps:
                assert gap.location.line > 0 and gap.code.startswith('NODL9')


def test_drafts_of_every_fixture_load_and_comment_out_gaps() -> None:
    for case in CASES:
        for node in extract_cpp([str(FIXTURES / case)]).nodes:
            text = draft_text(node, relative_to=str(FIXTURES))
            for entity in node.entities:
                assert f'{case}/' in text
                if not entity.complete:
                    assert f'# {GAP_MARKER} ' in text


def test_package_with_cmake_names_executables(tmp_path: Path) -> None:
    package = tmp_path / 'demo_nodes_cpp'
    (package / 'src' / 'topics').mkdir(parents=True)
    (package / 'CMakeLists.txt').write_text((CMAKE / 'demo_nodes_cpp' / 'CMakeLists.txt').read_text())
    (package / 'src' / 'topics' / 'talker.cpp').write_text((FIXTURES / 'demo_talker' / 'talker.cpp').read_text())
    extraction = extract_cpp_package(str(package))
    (node,) = extraction.nodes
    assert (node.package, node.executable, node.output_name) == ('demo_nodes_cpp', 'talker', 'talker')
    assert not node.notes


def test_component_without_executable_is_a_note(tmp_path: Path) -> None:
    package = tmp_path / 'composition'
    (package / 'src').mkdir(parents=True)
    (package / 'CMakeLists.txt').write_text((CMAKE / 'composition' / 'CMakeLists.txt').read_text())
    for name in ('talker_component.cpp', 'talker_component.hpp'):
        (package / 'src' / name).write_text((FIXTURES / 'composition_talker' / name).read_text())
    (node,) = extract_cpp_package(str(package)).nodes
    assert node.executable is None
    (note,) = node.notes
    assert note.code == 'NODL944' and 'plugin composition::Talker of library talker_component' in note.message


def _one(tmp_path: Path, code: str, name: str = 'node.cpp'):
    path = tmp_path / name
    path.write_text(code)
    extraction = extract_cpp([str(path)])
    return extraction


NODE = '''
#include "rclcpp/rclcpp.hpp"
namespace demo {{
{prelude}
class N : public rclcpp::Node {{
public:
  N() : Node("n"){init} {{
{body}
  }}
{members}
}};
}}  // namespace demo
'''


def _node(tmp_path: Path, body: str, prelude: str = '', members: str = '', init: str = ''):
    extraction = _one(tmp_path, NODE.format(prelude=prelude, body=body, members=members, init=init))
    (node,) = extraction.nodes
    return node, extraction


def test_constants_are_resolved(tmp_path: Path) -> None:
    node, _ = _node(tmp_path, '''
    pub_a = create_publisher<std_msgs::msg::String>(kTopic, 10);
    pub_b = this->create_publisher<std_msgs::msg::String>(std::string(PREFIX) + "b", kDepth);
    pub_c = create_publisher<std_msgs::msg::String>("c" "d", rclcpp::QoS(rclcpp::KeepLast(3)));
    pub_d = create_publisher<Msg>(topic_, rclcpp::QoS(4).best_effort().transient_local());
    const std::string local = "e";
    pub_e = create_publisher<std_msgs::msg::String>(local, rmw_qos_profile_sensor_data);
    pub_f = create_publisher<std_msgs::msg::String>(kStatic, rclcpp::SystemDefaultsQoS());
''', prelude='constexpr char kTopic[] = "a";\n#define PREFIX "pre_"\nconst int kDepth = 5;\n'
             'static const std::string kStatic = "f";\nusing Msg = std_msgs::msg::Bool;',
        members='  std::string topic_{"member"};', init=', topic_("ctor")')
    got = [(e.name, e.type, e.qos.to_dict() if e.qos else None) for e in node.entities]
    assert got == [
        ('a', 'std_msgs/msg/String', {'history': 'KEEP_LAST', 'depth': 10, 'reliability': 'RELIABLE',
                                      'durability': 'VOLATILE'}),
        ('pre_b', 'std_msgs/msg/String', {'history': 'KEEP_LAST', 'depth': 5, 'reliability': 'RELIABLE',
                                          'durability': 'VOLATILE'}),
        ('cd', 'std_msgs/msg/String', {'history': 'KEEP_LAST', 'depth': 3, 'reliability': 'RELIABLE',
                                       'durability': 'VOLATILE'}),
        ('ctor', 'std_msgs/msg/Bool', {'history': 'KEEP_LAST', 'depth': 4, 'reliability': 'BEST_EFFORT',
                                       'durability': 'TRANSIENT_LOCAL'}),
        ('e', 'std_msgs/msg/String', {'history': 'KEEP_LAST', 'depth': 5, 'reliability': 'BEST_EFFORT',
                                      'durability': 'VOLATILE'}),
        ('f', 'std_msgs/msg/String', {'history': 'SYSTEM_DEFAULT', 'reliability': 'SYSTEM_DEFAULT',
                                      'durability': 'SYSTEM_DEFAULT'}),
    ]
    assert all(e.complete for e in node.entities)


def test_run_time_values_are_located_gaps_never_guesses(tmp_path: Path) -> None:
    node, _ = _node(tmp_path, '''
    auto topic = this->declare_parameter<std::string>("topic", "scan");
    sub_ = create_subscription<sensor_msgs::msg::LaserScan>(topic, 10, cb);
    pub_ = create_publisher<std_msgs::msg::String>(get_name() + std::string("/x"), depth_);
    gen_ = create_generic_publisher("g", type_name_, 10);
    gen2_ = create_generic_publisher("h", "std_msgs/msg/String", rclcpp::QoS(2).keep_last(depth_));
    member_ = create_publisher<std_msgs::msg::String>(reassigned_, 1);
    reassigned_ = "other";
''', members='  std::string reassigned_ = "first"; int depth_;')
    by_name = {e.name: e for e in node.entities}
    (hint,) = node.section('subscriptions')[0].gaps
    assert hint.code == 'NODL941' and "parameter 'topic'" in hint.reason and "default 'scan'" in hint.reason
    assert node.section('subscriptions')[0].name is None
    assert by_name['topic'].type == 'string' and by_name['topic'].default_value == 'scan'
    pub = node.section('publishers')[0]
    assert sorted(g.code for g in pub.gaps) == ['NODL937', 'NODL939'] and pub.name is None
    assert 'node.cpp:11:52' in str(pub.gaps[0].location) and 'computed at run time' in pub.gaps[0].reason
    assert by_name['g'].type is None and [g.code for g in by_name['g'].gaps] == ['NODL938']
    assert by_name['h'].type == 'std_msgs/msg/String' and [g.what for g in by_name['h'].gaps] == ['qos']
    assert [g.what for g in node.section('publishers')[-1].gaps] == ['name']  # reassigned member
    text = draft_text(node)
    assert text.count(f'# {GAP_MARKER} ') == 6 and 'name: scan' not in text


def test_parameters_types_defaults_and_descriptors(tmp_path: Path) -> None:
    node, _ = _node(tmp_path, '''
    rcl_interfaces::msg::ParameterDescriptor d;
    d.read_only = true;
    d.description = "gain";
    rcl_interfaces::msg::FloatingPointRange r;
    r.from_value = 0.0;
    r.to_value = 2.5;
    d.floating_point_range.push_back(r);
    d.floating_point_range = {r};
    declare_parameter("gain", 1, d);
    declare_parameter<double>("rate", 10);
    declare_parameter<std::vector<std::string>>("names", std::vector<std::string>{"a", "b"});
    declare_parameter("required", rclcpp::PARAMETER_INTEGER);
    declare_parameter("flags", std::vector<bool>{true, false});
    declare_parameter("computed", compute());
    declare_parameter("neg", -3);
''')
    got = {e.name: (e.type, e.default_value if e.has_default else '-', e.read_only, e.validation, e.description,
                    [g.code for g in e.gaps]) for e in node.entities}
    assert got == {
        'gain': ('int', 1, True, {'bounds<>': [0.0, 2.5]}, 'gain', []),
        'rate': ('double', 10.0, False, None, None, []),
        'names': ('string_array', ['a', 'b'], False, None, None, []),
        'required': ('int', '-', False, None, None, []),
        'flags': ('bool_array', [True, False], False, None, None, []),
        'computed': (None, '-', False, None, None, ['NODL940']),
        'neg': ('int', -3, False, None, None, []),
    }


def test_lifecycle_actions_helpers_and_free_nodes(tmp_path: Path) -> None:
    code = '''
#include "rclcpp/rclcpp.hpp"
class L : public nav2_util::LifecycleNode {
public:
  L() : nav2_util::LifecycleNode("life") {}
  CallbackReturn on_configure(const rclcpp_lifecycle::State &) {
    server_ = rclcpp_action::create_server<nav2_msgs::action::NavigateToPose>(this, "navigate", a, b, c);
    client_ = rclcpp_action::create_client<nav2_msgs::action::Spin>(
      get_node_base_interface(), get_node_graph_interface(), get_node_logging_interface(),
      get_node_waitables_interface(), "spin");
    tf_listener_ = std::make_shared<tf2_ros::TransformListener>(*tf_buffer_);
    diag_ = std::make_unique<diagnostic_updater::Updater>(this);
    filt_.subscribe(this, "points", rmw_qos_profile_sensor_data);
    it_ = image_transport::create_publisher(this, "image");
    return CallbackReturn::SUCCESS;
  }
  message_filters::Subscriber<sensor_msgs::msg::PointCloud2> filt_;
};
int main() {
  auto node = rclcpp::Node::make_shared("free");
  auto c = node->create_client<std_srvs::srv::Trigger>("trigger");
  auto other = get_node_from_somewhere();
  auto p = other->create_publisher<std_msgs::msg::String>("lost", 1);
}
'''
    extraction = _one(tmp_path, code)
    life, free = extraction.nodes
    assert (life.base, life.node_name, free.node_name, free.name) == ('lifecycle_node', 'life', 'free', 'free')
    got = [(e.section, e.name, e.type, e.helper, [g.code for g in e.gaps]) for e in life.entities]
    assert got == [
        ('action_servers', 'navigate', 'nav2_msgs/action/NavigateToPose', None, []),
        ('action_clients', 'spin', 'nav2_msgs/action/Spin', None, []),
        ('subscriptions', '/tf', 'tf2_msgs/msg/TFMessage', 'tf2_ros::TransformListener', []),
        ('subscriptions', '/tf_static', 'tf2_msgs/msg/TFMessage', 'tf2_ros::TransformListener', []),
        ('publishers', '/diagnostics', 'diagnostic_msgs/msg/DiagnosticArray', 'diagnostic_updater::Updater', []),
        ('parameters', 'diagnostic_updater.period', 'double', 'diagnostic_updater::Updater', []),
        ('subscriptions', 'points', 'sensor_msgs/msg/PointCloud2', 'message_filters::Subscriber', []),
        ('publishers', 'image', 'sensor_msgs/msg/Image', 'image_transport', ['NODL942']),
    ]
    assert [(e.section, e.name) for e in free.entities] == [('service_clients', 'trigger')]
    (untied,) = [d for d in extraction.diagnostics if d.code == 'NODL944']
    assert "'other'" in untied.message and untied.line == 23


def test_qos_of_named_profiles() -> None:
    assert qos_of_name('rclcpp::SensorDataQoS').to_dict() == qos_of_name('rmw_qos_profile_sensor_data').to_dict()
    assert qos_of_name('rclcpp::RosoutQoS').lifespan_ns == 10_000_000_000
    assert qos_of_name('rclcpp::Whatever') is None


def test_class_template_types_are_gaps(tmp_path: Path) -> None:
    extraction = _one(tmp_path, '''
template<typename MsgT>
class Relay : public rclcpp::Node {
 public:
  Relay() : Node("relay") { pub_ = create_publisher<MsgT>("out", 10); }
};
''')
    (node,) = extraction.nodes
    (gap,) = node.entities[0].gaps
    assert gap.code == 'NODL936' and 'MsgT' in gap.reason
    assert [d.code for d in extraction.diagnostics] == ['NODL936']


def test_bad_input_is_one_located_diagnostic_each(tmp_path: Path) -> None:
    (tmp_path / 'broken.cpp').write_text('class A : public rclcpp::Node {\n  void f( {{{ \n')
    (tmp_path / 'huge.cpp').write_bytes(b'// x\n' * (MAX_FILE_BYTES // 5 + 1))
    (tmp_path / 'gen.hpp').write_text('// generated by rosidl, do not edit\nclass X {};\n')
    (tmp_path / 'bin.cpp').write_bytes(b'\x7fELF\0\0\0')
    (tmp_path / 'macro.hpp').write_text('#define MAKE_PUB(t) create_publisher<std_msgs::msg::String>(t, 1)\n')
    extraction = extract_cpp([str(tmp_path), str(tmp_path / 'missing.cpp')])
    codes = sorted((d.code, Path(d.file).name, d.line) for d in extraction.diagnostics)
    assert codes == [('NODL931', 'bin.cpp', 1), ('NODL931', 'missing.cpp', 0), ('NODL932', 'huge.cpp', 1),
                     ('NODL933', 'gen.hpp', 1), ('NODL934', 'broken.cpp', 1), ('NODL935', 'macro.hpp', 1)]


def test_without_the_parser_one_error(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setitem(sys.modules, 'tree_sitter_cpp', None)  # the import fails as when not installed
    (tmp_path / 'a.cpp').write_text('int main() {}\n')
    extraction = extract_cpp([str(tmp_path)])
    (diagnostic,) = extraction.diagnostics
    assert diagnostic.code == 'NODL930' and "nodl-toolkit[extract]" in diagnostic.message
