"""A node's parameter defaults as a ``ros__parameters`` YAML file."""

from __future__ import annotations

import json
import re
from typing import Any

from nodl.composition.entities import Provider
from nodl.composition.resolved import ResolvedNode
from nodl.plan.parameter_plan import ParameterPlan, ParametersPlan, plan_parameters
from nodl.text_safety import json_escapes, visible

__all__ = ['defaults_yaml', 'yaml_scalar']


def yaml_scalar(value: Any, base: str) -> str:
    """``value`` in YAML flow style, typed as rcl will type it (a double is always written with a point)."""
    if isinstance(value, list):
        return '[' + ', '.join(yaml_scalar(v, base) for v in value) + ']'
    if isinstance(value, bool):
        return 'true' if value else 'false'
    if base.startswith('double') and isinstance(value, (int, float)):
        text = repr(float(value))
        return {'inf': '.inf', '-inf': '-.inf', 'nan': '.nan'}.get(text, text)
    if isinstance(value, str):
        # a double-quoted YAML string; what a YAML reader would fold or show raw is escaped
        return json_escapes(json.dumps(value, ensure_ascii=False))
    return repr(value)


def _comment(text: str) -> str:
    return visible(' '.join(text.split()), one_line=True)


def defaults_yaml(node: ResolvedNode, fqn: str, *, include_base: bool = False) -> str:
    """The parameters of ``node`` with their defaults under the node key ``fqn``.

    The implementation's and the mixins' parameters are written (the base's,
    such as ``use_sim_time``, only with ``include_base``); a required parameter,
    a ``byte_array`` (which rcl's parameter files cannot express) and an empty
    list default (which rcl reads as no value) are written as comments saying
    what to give.
    """
    wanted = [Provider.IMPLEMENTATION, Provider.OTHER_CODE] + ([Provider.CLIENT_LIBRARY] if include_base else [])
    plan: ParametersPlan = plan_parameters([e for e in node.provided_by(*wanted) if e.is_parameter])
    lines = [f'# Defaults of the parameters of {node.file.rsplit("/", 1)[-1]}, written by nodl params.',
             f'{_key(fqn)}:', '  ros__parameters:']
    if not plan.parameters:
        lines[-1] += ' {}'
    opened: list[str] = []
    for p in plan.parameters:
        parts = p.name.split('.')
        common = 0
        while common < min(len(opened), len(parts) - 1) and opened[common] == parts[common]:
            common += 1
        opened = opened[:common]
        for group in parts[common:-1]:
            lines.append('    ' + '  ' * len(opened) + f'{_key(group)}:')
            opened.append(group)
        lines.extend(_entry(p, '    ' + '  ' * len(opened), parts[-1]))
    return '\n'.join(lines) + '\n'


def _key(text: str) -> str:
    return text if re.fullmatch(r'[A-Za-z_/*~][A-Za-z0-9_/*~.-]*', text) else yaml_scalar(text, 'string')


def _entry(p: ParameterPlan, indent: str, leaf: str) -> list[str]:
    out = []
    if p.description:
        out.append(f'{indent}# {_comment(p.description)}')
    if p.required:
        out.append(f'{indent}# {_key(leaf)}: required ({p.type_name}): no default, give a value')
    elif p.dynamic_typing and p.default is None:
        out.append(f'{indent}# {_key(leaf)}: any type, no default')
    elif isinstance(p.default, (list, tuple)) and not p.default and not p.dynamic_typing:
        out.append(f'{indent}# {_key(leaf)}: [] (an empty list is no value in a parameter file: '
                   "rcl would leave the parameter unset; the node's default applies)")
    elif p.type.base == 'byte_array':
        out.append(f'{indent}# {_key(leaf)}: {yaml_scalar(p.default, "int_array")} '
                   '(a byte array: parameter files cannot set one)')
    else:
        out.append(f'{indent}{_key(leaf)}: {yaml_scalar(p.default, p.type.base)}')
    return out
