"""Checks across the entities of one interface definition.

* an endpoint name appears at most once per section;
* every parameter is checked by :mod:`nodl.validation.parameters`;
* warnings for what a reader of the interface will miss: an endpoint or
  parameter without a description.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from typing import Any

from nodl.diagnostics import Diagnostic, DocPath, Severity, format_path
from nodl.validation.characters import check_text_fields
from nodl.validation.parameters import check_parameter
from nodl.vocabulary import SECTION_WORDS
from nodl.wording import show

__all__ = ['SECTIONS', 'NO_DESCRIPTION', 'check_interface']

#: How every missing-description warning ends (tools may recognise it).
NO_DESCRIPTION = 'has no description'

#: Endpoint sections and how one of their entries is called in messages (from the vocabulary).
SECTIONS = SECTION_WORDS


def check_interface(data: Any, path: DocPath, out: list[Diagnostic]) -> None:
    """Semantic checks of an interface definition found at ``path``."""
    if not isinstance(data, dict):
        return
    check_text_fields(data, path, out)
    parameters = data.get('parameters')
    if isinstance(parameters, dict):
        for name, param in parameters.items():
            check_parameter(param, path + ('parameters', name), out)
            if isinstance(param, dict) and not param.get('description'):
                out.append(Diagnostic(Severity.WARNING, f'parameter {show(name)} {NO_DESCRIPTION}',
                                      path + ('parameters', name), anchor='key', code='NODL216'))
    for section, word in SECTIONS.items():
        entries = data.get(section)
        if not isinstance(entries, list):
            continue
        first_index: dict[str, int] = {}
        for index, entry in enumerate(entries):
            if not isinstance(entry, dict):
                continue
            name = entry.get('name')
            entry_path = path + (section, index)
            _check_qos(entry.get('qos'), entry_path + ('qos',), out)
            check_text_fields(entry, entry_path, out)
            if isinstance(name, str):
                if name in first_index:
                    earlier = format_path(path + (section, first_index[name]))
                    out.append(Diagnostic(
                        Severity.ERROR, f'duplicate {word} {show(name)} (already declared at {earlier}); '
                        'a name appears once per section', entry_path + ('name',), code='NODL215'))
                else:
                    first_index[name] = index
            if not entry.get('description'):
                label = f' {show(name)}' if isinstance(name, str) else ''
                out.append(Diagnostic(Severity.WARNING, f'{word}{label} {NO_DESCRIPTION}',
                                      entry_path, anchor='key', code='NODL216'))


def _check_qos(qos: Any, path: DocPath, out: list[Diagnostic]) -> None:
    """QoS settings that are valid but do not do what they say."""
    if isinstance(qos, dict) and qos.get('history') == 'KEEP_ALL' and 'depth' in qos:
        out.append(Diagnostic(Severity.WARNING, 'depth has no effect with history KEEP_ALL (the '
                              'middleware keeps every sample); remove it, or use KEEP_LAST',
                              path + ('depth',), anchor='key', code='NODL230'))
