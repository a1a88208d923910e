"""The ``nodl`` resolver: ``nodl://<package>/<name>`` through the registry.

Interface definitions are registered under the resource type
``nodl_interfaces`` with the resource name ``<package>__<name>``.  The
resource's content is the path of the installed file relative to
``share/<package>`` (what ``ament_nodl_register_interface`` and the Python
helper write), an absolute path (the build-time staging index), or the
document itself.

What the reference implementation's current ``ament_nodl_register`` installs
(resource type ``nodl``, same ``<package>__<name>`` key, the document itself
as content) is found too, after ``nodl_interfaces``: the reference resolves
``nodl://<package>/<name>`` there.

Definitions folders in force (:mod:`nodl.registry.overlay`) come first:
``DIR/<package>/interfaces/<name>.nodl.yaml``.  The look-up is the registry's
(:func:`nodl.registry.registrations.find_interface`); this module only plugs it into
composition as the ``nodl`` resolver.  It lives in the registry, not in composition:
composition knows resolvers only through their extension point and never imports the
registry (which composes legacy packages with composition).
"""

from __future__ import annotations

from nodl.composition.resolvers import (
    ResolutionError,
    ResolveContext,
    Resolved,
    ResolverExtension,
)
from nodl.registry import registrations
from nodl.validation.references import parse_nodl_uri

__all__ = ['AmentIndexResolver']


class AmentIndexResolver(ResolverExtension):
    """Resolves ``nodl://<package>/<name>`` to a registered interface definition."""

    def resolve(self, reference: str, context: ResolveContext) -> Resolved:
        """Find the registered interface definition (:func:`nodl.registry.registrations.find_interface`)."""
        parsed = parse_nodl_uri(reference)
        if parsed is None:
            raise ResolutionError(f'{reference!r} is not of the form nodl://<package>/<name>')
        # The caller's prefixes (an analysis with prefixes=...), else AMENT_PREFIX_PATH's.
        given = context.prefixes
        return registrations.find_interface(*parsed, list(given) if given is not None else None)
