"""The gaps of an extracted draft: the entities ``nodl extract`` left commented out.

``nodl extract`` writes an entity whose name, type or QoS is known only at
run time commented out, under one ``# GAP FILE:LINE:COL: reason [NODL9xx]``
line per missing part and a ``# fill in what is missing, then uncomment:``
line (:mod:`nodl.extract.writer`).  A definition served from such a draft is
incomplete: :func:`draft_gaps` reads which entities are still unresolved, so
that ``nodl analyse`` and ``nodl policy`` can say so instead of taking the
draft for the whole node.

An entity counts as resolved once its lines are uncommented (the ``# GAP``
comments may stay): only a ``# GAP`` run followed by commented-out YAML is a
gap.  Only files whose header says ``nodl extract`` wrote them are read
(:func:`nodl.targets.resolve.made_by`).
"""

from __future__ import annotations

import re
import textwrap
from typing import NamedTuple

import yaml

from nodl.targets.resolve import made_by
from nodl.vocabulary import SECTION_BY_KEY

__all__ = ['GapLine', 'DraftGap', 'draft_gaps', 'gaps_of_text', 'describe', 'COMMUNICATION_SECTIONS']

#: The sections whose entities are granted in a policy (parameters are not).
COMMUNICATION_SECTIONS = ('publishers', 'subscriptions', 'service_servers', 'service_clients',
                          'action_servers', 'action_clients')
#: A ``# GAP`` line: its indentation, the source place, the reason and the code.
_GAP = re.compile(r'^(\s*)#\s*GAP\s+(.*?)(?:\s+\[(NODL\d+)\])?\s*$')
#: A section header, live (``  publishers:``) or commented out (``  # publishers:``).
_SECTION = re.compile(r'^  (?:#\s*)?([a-z_]+):\s*$')
_FILL = re.compile(r'^\s*#\s*fill in what is missing')
#: Gap codes that leave an entity's name unknown (a name computed at run time, a plug-in's
#: name, arguments not written out, a name the validator refuses).
_NAME_GAPS = frozenset({'NODL901', 'NODL904', 'NODL909', 'NODL910', 'NODL914'})
#: The largest draft read (a draft is a few kilobytes; anything larger is no draft of ours).
_MAX_BYTES = 4 * 1024 * 1024


class GapLine(NamedTuple):
    """One ``# GAP`` comment of a draft."""

    #: The draft file.
    file: str
    #: Its line (1-based).
    line: int
    #: The column of its ``#`` (1-based).
    column: int
    #: What it says is missing (``topic name is computed at run time ...``), with the source place.
    reason: str
    #: The extraction code (``NODL901``), or None.
    code: str | None


class DraftGap(NamedTuple):
    """An entity of an extracted draft that is still commented out because of gaps."""

    #: Its section (``subscriptions``, ``parameters``, ...).
    section: str
    #: Its name as written in the draft (relative, before remapping), or None when unknown.
    name: str | None
    #: Its ``# GAP`` comments, in order.
    lines: tuple[GapLine, ...]

    @property
    def communication(self) -> bool:
        """True for a publisher, subscription, service or action (a policy would grant it)."""
        return self.section in COMMUNICATION_SECTIONS


def draft_gaps(file: str | None) -> list[DraftGap]:
    """The unresolved entities of ``file`` if ``nodl extract`` wrote it (else, or when it
    cannot be read, an empty list), in the order they are written."""
    if file is None:
        return []
    if made_by(file) != 'extracted':
        return []
    try:
        with open(file, encoding='utf-8', errors='replace') as stream:
            text = stream.read(_MAX_BYTES)
    except OSError:
        return []
    return gaps_of_text(text, file)


def gaps_of_text(text: str, file: str) -> list[DraftGap]:
    """The unresolved entities of a draft's ``text`` (see :func:`draft_gaps`)."""
    lines = text.split('\n')
    found: list[DraftGap] = []
    section = ''
    index = 0
    while index < len(lines):
        line = lines[index]
        header = _SECTION.match(line)
        if header:
            section = header.group(1)
        match = _GAP.match(line)
        if match is None:
            index += 1
            continue
        run: list[GapLine] = []
        while index < len(lines) and (match := _GAP.match(lines[index])) is not None:
            run.append(GapLine(file, index + 1, len(match.group(1)) + 1, match.group(2),
                               match.group(3)))
            index += 1
        if index < len(lines) and _FILL.match(lines[index]):
            index += 1
        body: list[str] = []
        while index < len(lines) and lines[index].lstrip().startswith('#') \
                and not _GAP.match(lines[index]) and not _SECTION.match(lines[index]):
            body.append(lines[index].lstrip()[1:])
            index += 1
        if not body:
            continue  # uncommented since: filled in (the GAP comments stayed)
        found.append(DraftGap(section, _name(body, section, run), tuple(run)))
    return found


def _name(body: list[str], section: str, run: list[GapLine]) -> str | None:
    """The name the commented-out entity gives, if it is known."""
    if any(gap.code in _NAME_GAPS for gap in run):
        return None
    try:
        data = yaml.safe_load(textwrap.dedent('\n'.join(line.removeprefix(' ') for line in body)))
    except yaml.YAMLError:
        return None
    if section == 'parameters' and isinstance(data, dict) and len(data) == 1:
        (name,) = data
        return name if isinstance(name, str) and name != '?' else None
    if isinstance(data, list) and len(data) == 1 and isinstance(data[0], dict):
        name = data[0].get('name')
        return name if isinstance(name, str) and name else None
    return None


def describe(gaps: list[DraftGap]) -> str:
    """``1 publisher, 2 subscriptions and 1 parameter``: what ``gaps`` leave unknown, by kind,
    in the draft's order."""
    counts: dict[str, int] = {}
    for gap in gaps:
        counts[gap.section] = counts.get(gap.section, 0) + 1
    words = []
    for section, count in counts.items():
        entry = SECTION_BY_KEY.get(section)
        word = entry.word if entry is not None else section.rstrip('s').replace('_', ' ')
        words.append(f'{count} {word}{"s" if count > 1 else ""}')
    return words[0] if len(words) == 1 else f'{", ".join(words[:-1])} and {words[-1]}'
