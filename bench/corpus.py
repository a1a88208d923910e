"""Corpora of realistic node definitions (about 8 KB each), generated deterministically.

Each document has 25 parameters with validators, 10 publishers, 10
subscriptions, service servers and clients, and action servers and clients,
written the way people write them (comments, descriptions, QoS blocks).
"""

from __future__ import annotations

import random

_TOPIC_TYPES = ['sensor_msgs/msg/LaserScan', 'sensor_msgs/msg/Imu', 'std_msgs/msg/String',
                'geometry_msgs/msg/Twist', 'nav_msgs/msg/Odometry', 'std_msgs/msg/Float64']
_PARAMS = [
    ('int', '{v}', 'bounds<>: [0, 1000]'),
    ('double', '{v}.5', 'gt_eq<>: [0.0]'),
    ('string', 'frame_{v}', 'not_empty<>: null'),
    ('bool', 'true', None),
    ('double_array', '[0.1, 0.2, {v}.0]', 'element_bounds<>: [-100.0, 100.0]'),
    ('string_array', '[a, b]', 'unique<>: null'),
    ('int', '{v}', 'one_of<>: [[{v}, 1, 2, 3]]'),
]


def document(seed: int) -> str:
    """One node definition as YAML text."""
    rng = random.Random(seed)
    lines = [
        f'# Driver {seed}: generated for the benchmark.',
        'nodl_version: 2',
        'base: node',
        'main:',
        '  nodl_version: 2',
        f'  description: Device driver {seed}, publishing measurements and serving commands.',
        '  parameters:',
    ]
    for index in range(25):
        ptype, default, validator = _PARAMS[rng.randrange(len(_PARAMS))]
        value = rng.randrange(1, 9)
        lines += [
            f'    group_{index % 4}.param_{index}:',
            f'      type: {ptype}',
            f'      default_value: {default.format(v=value)}',
            f'      description: Tunes stage {index}.',
        ]
        if validator:
            lines += ['      validation:', f'        {validator.format(v=value)}']
        if index % 5 == 0:
            lines.append('      read_only: true')
    for section, prefix in (('publishers', 'out'), ('subscriptions', 'in')):
        lines.append(f'  {section}:')
        for index in range(10):
            lines += [
                f'    - name: ~/{prefix}_{index}',
                f'      type: {_TOPIC_TYPES[rng.randrange(len(_TOPIC_TYPES))]}',
                f'      description: Stream {index}.',
                f'      qos: {{history: KEEP_LAST, depth: {rng.choice([1, 5, 10])}, '
                f'reliability: {rng.choice(["RELIABLE", "BEST_EFFORT"])}}}',
            ]
    for section, stype in (('service_servers', 'std_srvs/srv/Trigger'),
                           ('service_clients', 'std_srvs/srv/SetBool'),
                           ('action_servers', 'test_msgs/action/Fibonacci'),
                           ('action_clients', 'test_msgs/action/Fibonacci')):
        lines.append(f'  {section}:')
        for index in range(2):
            lines += [f'    - name: ~/{section[:-1]}_{index}', f'      type: {stype}',
                      f'      description: Endpoint {index}.']
    return '\n'.join(lines) + '\n'


def corpus(count: int = 40) -> list[str]:
    """``count`` distinct documents."""
    return [document(seed) for seed in range(count)]


def block_document(seed: int) -> str:
    """The same definition written the way ``yaml.safe_dump`` writes it: every list and
    mapping in block style, one item a line, no comments."""
    import yaml

    data = yaml.safe_load(document(seed))
    return yaml.safe_dump(data, default_flow_style=False, sort_keys=False)


def block_corpus(count: int = 40) -> list[str]:
    """``count`` distinct block-style documents."""
    return [block_document(seed) for seed in range(count)]
