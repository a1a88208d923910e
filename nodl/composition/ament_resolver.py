"""The ``nodl`` resolver: ``nodl://<package>/<name>`` through the ament index.

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

Definitions folders in force (:mod:`nodl.targets.overlay`) come first:
``DIR/<package>/interfaces/<name>.nodl.yaml``.
"""

from __future__ import annotations

import os

from nodl.composition.resolvers import (
    ResolutionError, ResolveContext, Resolved, ResolverExtension)
from nodl.files import tidy_path
from nodl.frontends.source import read_regular
from nodl.index import ament
from nodl.vocabulary import INTERFACE_RESOURCE, NODE_RESOURCE, REFERENCE_RESOURCE, resource_name

__all__ = ['AmentIndexResolver', 'read_registered', 'INTERFACE_RESOURCE', 'NODE_RESOURCE',
           'resource_name']



def read_registered(resource: ament.Resource, package: str) -> Resolved:
    """The document a registration resource points at (or holds); read once per entry
    within an :func:`nodl.index.ament.snapshot`."""
    return ament.remembered(('registered', resource, package), lambda: _read(resource, package))


def _read(resource: ament.Resource, package: str) -> Resolved:
    content = resource.content.strip()
    # A path is one line; a document held in the entry may be one line too (flow YAML
    # or minified JSON: '{...}', or 'key: value').
    if content and '\n' not in content and not content.startswith('{') and ': ' not in content:
        candidate = tidy_path(content if os.path.isabs(content) else
                              os.path.join(resource.prefix, 'share', package, content))
        data = read_regular(candidate)
        if data is not None:
            return Resolved(data, candidate)
        raise ResolutionError(f'the index entry {resource.path} points at {candidate}, '
                              'which does not exist (is the package fully installed?)', [candidate])
    return Resolved(resource.content, resource.path)


class AmentIndexResolver(ResolverExtension):
    """Resolves ``nodl://<package>/<name>`` to a registered interface definition."""

    def resolve(self, reference: str, context: ResolveContext) -> Resolved:
        """Find the registered interface definition."""
        from nodl.validation.references import parse_nodl_uri

        parsed = parse_nodl_uri(reference)
        if parsed is None:
            raise ResolutionError(f'{reference!r} is not of the form nodl://<package>/<name>')
        package, name = parsed
        from nodl.targets import overlay

        definitions = overlay.active()
        served = definitions.find_interface(package, name) if definitions else None
        if served is not None:
            data = read_regular(served[0])
            if data is None:
                raise ResolutionError(f'{served[0]} cannot be read', [served[0]])
            return Resolved(data, served[0])
        # The caller's prefixes (an analysis with prefixes=...), else AMENT_PREFIX_PATH's.
        given = context.prefixes
        prefixes = list(given) if given is not None else ament.prefix_paths()
        where = 'prefixes searched' if given is not None else 'AMENT_PREFIX_PATH'
        key = resource_name(package, name)
        resource = (ament.get_resource(INTERFACE_RESOURCE, key, prefixes)
                    or ament.get_resource(REFERENCE_RESOURCE, key, prefixes))
        if resource is not None:
            return read_registered(resource, package)
        searched = [ament.resource_file(p, t, key) for t in (INTERFACE_RESOURCE, REFERENCE_RESOURCE)
                    for p in prefixes]
        if not prefixes:
            if given is not None:
                raise ResolutionError('no ament prefix was given to search, so no package can be found')
            raise ResolutionError('AMENT_PREFIX_PATH is empty, so no package can be found; '
                                  'source the workspace (install/setup.bash) first')
        prefix = resource_name(package, '')
        available = sorted({n[len(prefix):] for t in (INTERFACE_RESOURCE, REFERENCE_RESOURCE)
                            for n in ament.get_resources(t, prefixes) if n.startswith(prefix)})
        if available:
            raise ResolutionError(f"package '{package}' registers no interface definition "
                                  f"'{name}' (it registers: {', '.join(available)})", searched)
        if ament.package_share_directory(package, prefixes) is None:
            raise ResolutionError(f"package '{package}' is not in the ament index "
                                  f"({where}: {os.pathsep.join(prefixes)})", searched)
        raise ResolutionError(f"package '{package}' registers no interface definitions", searched)
