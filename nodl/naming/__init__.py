"""ROS names exactly as rcl computes them: validation, expansion, remapping.

This module is the one place where the toolkit turns a name written in a
definition (``scan``, ``~/scan``, ``{node}/scan``, ``/scan``) into the name a
real node uses.  It follows rcl (``rcl/expand_topic_name.c``, ``remap.c``,
``arguments.c``, ``node.c``) and the rmw validators, and its tests compare it
with real rclpy nodes.

* :func:`declared_name_error` -- the one check of a topic, service or action name a
  definition writes (rcl's rules; ``nodl validate``'s NODL201 words its reason).
* :func:`expand_name` -- ``~``, ``~/x``, ``{node}``, ``{ns}``/``{namespace}``,
  relative and absolute names, as ``rclpy.expand_topic_name`` does.
* :func:`parse_remap_rules` -- ``from:=to``, ``node:from:=to``,
  ``rostopic://``/``rosservice://`` rules, ``__ns:=``, ``__node:=`` and
  ``__name:=``, from a list of rules or a whole ``--ros-args`` command line.
* :func:`node_name_after_remaps`, :func:`node_fqn` -- the node's own final
  name.  The ``__node`` rule is looked up with the node's name as created;
  the ``__ns`` rule with the name after ``__node``.
* :func:`declared_names` -- the inverse: the names a node could declare that become a
  given final name (``nodl describe --all --launch`` undoes remaps with it).
* :func:`resolve_name` -- expansion, then the first matching rule (a
  node-scoped rule applies only to the node of that final name; the match
  side is expanded against the final name and namespace), then the check
  rmw makes of a fully qualified name.

Invalid names raise :class:`InvalidNameError` (a ``ValueError``) with rcl's
reason; malformed rules raise :class:`InvalidRemapRuleError`.

The older, tolerant helpers :func:`expand`, :func:`fully_qualified` and
:func:`relativize` stay for code that works on names read from a running
graph (already valid): they accept namespaces written without the leading
``/`` or with a trailing one, and do not validate.
"""

from __future__ import annotations

from nodl.naming.remap_rules import (
    RULE_KINDS,
    InvalidRemapRuleError,
    RemapArgs,
    RemapRule,
    parse_remap_rule,
    parse_remap_rules,
)
from nodl.naming.resolution import (
    NodeNames,
    declared_name_error,
    declared_names,
    expand,
    expand_name,
    fully_qualified,
    join_name,
    node_fqn,
    node_name_after_remaps,
    node_namespace_after_remaps,
    relative_to_namespace,
    relativize,
    resolve_name,
    split_name,
)
from nodl.naming.validation import (
    InvalidNameError,
    full_name_error,
    namespace_error,
    node_name_error,
    normalize_namespace,
    topic_name_error,
)

__all__ = [
    'RULE_KINDS', 'InvalidNameError', 'InvalidRemapRuleError', 'NodeNames', 'RemapArgs', 'RemapRule',
    'declared_name_error', 'declared_names', 'expand', 'expand_name', 'full_name_error',
    'fully_qualified', 'join_name', 'namespace_error', 'node_fqn', 'node_name_after_remaps',
    'node_name_error', 'node_namespace_after_remaps', 'normalize_namespace', 'parse_remap_rule',
    'parse_remap_rules', 'relative_to_namespace', 'relativize', 'resolve_name', 'split_name', 'topic_name_error',
]
