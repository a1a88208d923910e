"""Test configuration shared by every test module.

Network rule: anything that starts ROS stays on loopback, in a domain of its
own.  Both variables are set here, once, before any test imports rclpy.
"""

from __future__ import annotations

import os

os.environ['ROS_AUTOMATIC_DISCOVERY_RANGE'] = 'LOCALHOST'
# A domain per test run (0-101 are valid with localhost discovery).
os.environ.setdefault('ROS_DOMAIN_ID', str(10 + os.getpid() % 90))

from pathlib import Path  # noqa: E402

import pytest  # noqa: E402

FIXTURES = Path(__file__).parent / 'fixtures'
REPO = Path(__file__).resolve().parent.parent


def pytest_addoption(parser: pytest.Parser) -> None:
    parser.addoption('--update-golden', action='store_true', default=False,
                     help='rewrite the expected-output files instead of comparing with them')


class Golden:
    """Compares generated text with a checked-in expected file."""

    def __init__(self, update: bool) -> None:
        self.update = update

    def check(self, actual: str, expected_file: Path) -> None:
        if self.update:
            expected_file.parent.mkdir(parents=True, exist_ok=True)
            expected_file.write_text(actual, encoding='utf-8')
            return
        assert expected_file.exists(), (
            f'{expected_file} is missing; run pytest --update-golden to create it')
        assert actual == expected_file.read_text(encoding='utf-8'), (
            f'output differs from {expected_file}; if the change is intended, '
            'run pytest --update-golden and review the diff')


@pytest.fixture
def golden(request: pytest.FixtureRequest) -> Golden:
    """Golden-file comparison; ``pytest --update-golden`` regenerates the files."""
    return Golden(request.config.getoption('--update-golden'))


@pytest.fixture
def fixtures() -> Path:
    """The fixture file folder."""
    return FIXTURES
