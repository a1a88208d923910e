"""Enclaves: one per node, one per namespace, or a mapping file."""

from pathlib import Path

from nodl_schema.policy.enclaves import assign_enclaves, enclave_path_error, load_enclave_mapping

POLICY = Path(__file__).parent / 'fixtures' / 'policy'
NODES = ['/robot/camera', '/robot/talker', '/robot/listener', '/lidar']


def test_per_node_and_per_namespace():
    assert assign_enclaves(NODES)[0] == {n: n for n in NODES}
    assert assign_enclaves(NODES, 'namespace')[0] == {
        '/robot/camera': '/robot', '/robot/talker': '/robot', '/robot/listener': '/robot', '/lidar': '/'}


def test_mapping_file_first_match_wins_and_unmatched_is_an_error():
    mapping, problems = load_enclave_mapping(str(POLICY / 'enclaves.yaml'))
    assert problems == [] and mapping is not None
    assigned, problems = assign_enclaves(NODES, mapping)
    assert assigned == {'/robot/camera': '/robot/sensing', '/robot/talker': '/robot/talking',
                        '/robot/listener': '/robot/talking'}
    assert [d.code for d in problems] == ['NODL610'] and '/lidar' in problems[0].message


def test_bad_mapping_files(tmp_path):
    bad = tmp_path / 'bad.yaml'
    bad.write_text('robot: [/a]\n/ok: 5\n')
    mapping, problems = load_enclave_mapping(str(bad))
    assert mapping is None
    assert [(d.code, d.line) for d in problems] == [('NODL610', 1), ('NODL610', 2)]
    assert enclave_path_error('/a b') is not None and enclave_path_error('/a/b') is None
