"""Enclaves: one per node, one per namespace, or a mapping file."""

from pathlib import Path

from nodl.policy.enclaves import assign_enclaves, enclave_path_error, load_enclave_mapping

POLICY = Path(__file__).parent / 'fixtures' / 'policy'
NODES = ['/robot/camera', '/robot/talker', '/robot/listener', '/lidar']


def test_per_node_and_per_namespace():
    assert assign_enclaves(NODES)[0] == {n: n for n in NODES}
    assert assign_enclaves(NODES, 'namespace')[0] == {
        '/robot/camera': '/robot', '/robot/talker': '/robot', '/robot/listener': '/robot', '/lidar': '/'}


def test_mapping_file_places_nodes_and_unmatched_is_an_error():
    mapping, problems = load_enclave_mapping(str(POLICY / 'enclaves.yaml'))
    assert problems == [] and mapping is not None
    assigned, problems = assign_enclaves(NODES, mapping)
    assert assigned == {'/robot/camera': '/robot/sensing', '/robot/talker': '/robot/talking',
                        '/robot/listener': '/robot/talking'}
    # /lidar is in no enclave; /robot/lidar (a name of the mapping) is no node of this system
    assert [(d.code, d.severity.value, d.line) for d in problems] == [
        ('NODL610', 'error', 2), ('NODL613', 'warning', 2)]
    assert '/lidar' in problems[0].message and '/robot/lidar' in problems[1].message


def _mapping(tmp_path, text):
    file = tmp_path / 'enclaves.yaml'
    file.write_text(text)
    mapping, problems = load_enclave_mapping(str(file))
    assert problems == [], problems
    return mapping


def test_a_node_in_two_enclaves_is_an_error(tmp_path):
    """A node runs with one identity: no silent first-match between two enclaves."""
    nodes = ['/robot/talker']
    by_name = _mapping(tmp_path, '/a: [/robot/talker]\n/b: [/robot/other, /robot/talker]\n')
    assigned, problems = assign_enclaves(nodes, by_name)
    assert assigned == {}
    assert [(d.code, d.line, d.column) for d in problems if d.code == 'NODL610'] == [('NODL610', 2, 20)]
    assert "'/a' and '/b'" in problems[0].message
    by_pattern = _mapping(tmp_path, '/a: [/robot/t*]\n/b: ["/robot/*"]\n')
    assigned, problems = assign_enclaves(nodes, by_pattern)
    assert assigned == {} and [(d.code, d.line) for d in problems] == [('NODL610', 2)]
    # a name is more specific than a pattern: listed by name under one enclave, it belongs there
    named = _mapping(tmp_path, '/a: ["/robot/*"]\n/b: [/robot/talker]\n')
    assert assign_enclaves(nodes, named) == ({'/robot/talker': '/b'}, [])


def test_bad_mapping_files(tmp_path):
    bad = tmp_path / 'bad.yaml'
    bad.write_text('robot: [/a]\n/ok: 5\n')
    mapping, problems = load_enclave_mapping(str(bad))
    assert mapping is None
    assert [(d.code, d.line) for d in problems] == [('NODL610', 1), ('NODL610', 2)]
    bad.write_text('/a: [robot/talker, "/robot/*", /robot/bad-name]\n')
    mapping, problems = load_enclave_mapping(str(bad))
    assert mapping is None
    assert [(d.code, d.line, d.column) for d in problems] == [('NODL610', 1, 6), ('NODL610', 1, 32)]
    assert 'starting with /' in problems[0].message
    assert enclave_path_error('/a b') is not None and enclave_path_error('/a/b') is None


def test_composable_nodes_are_in_their_containers_enclave(tmp_path):
    """A container's nodes share its process, whose context has one enclave."""
    nodes = ['/robot/container', '/robot/camera', '/robot/rectifier', '/robot/lidar']
    containers = {'/robot/camera': '/robot/container', '/robot/rectifier': '/robot/container'}
    assigned, problems = assign_enclaves(nodes, 'node', containers)
    assert problems == [] and assigned == {
        '/robot/container': '/robot/container', '/robot/camera': '/robot/container',
        '/robot/rectifier': '/robot/container', '/robot/lidar': '/robot/lidar'}
    # a mapping may list them with their container, or not at all
    mapping = _mapping(tmp_path, '/robot/vision: [/robot/container, /robot/camera]\n'
                                 '/robot/ranging: [/robot/lidar]\n')
    assigned, problems = assign_enclaves(nodes, mapping, containers)
    assert problems == [] and {assigned[n] for n in nodes[:3]} == {'/robot/vision'}
    # ... but not elsewhere: the process cannot be in two enclaves
    mapping = _mapping(tmp_path, '/robot/vision: [/robot/container]\n'
                                 '/robot/ranging: [/robot/lidar, /robot/rectifier]\n')
    assigned, problems = assign_enclaves(nodes, mapping, containers)
    assert '/robot/rectifier' not in assigned
    assert [(d.code, d.line, d.column) for d in problems] == [('NODL610', 2, 32)]
    assert 'loaded into the container /robot/container' in problems[0].message
    # a container that is not part of the system (loaded into from elsewhere) changes nothing
    assert assign_enclaves(['/robot/camera'], 'node', containers)[0] == {'/robot/camera': '/robot/camera'}
