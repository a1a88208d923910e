"""Code generation from node definitions: the ``nodl.generators`` extension point.

A generator turns a :class:`~nodl.system.ResolvedNode` into source
files of one target language.  It implements what the node's own code
provides (the entities whose provider is the implementation, i.e. ``main``);
the base comes from the client library and mixins from other code.

Generators are entry points of the ``nodl.generators`` group named after the
language (``python``, ``cpp``); the built-ins are registered like third-party
ones.  A generator subclasses :class:`GeneratorExtension`, is instantiated
without arguments and returns :class:`GeneratedFile` objects: it never
writes, prints or exits.  :func:`write_files` writes them (or, with
``check=True``, only says which are stale).

Shared building blocks: :mod:`nodl.plan.identifiers` (names to
identifiers, collision-free) and :mod:`nodl.plan.parameter_plan` (the
language-neutral parameter plan).
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from typing import TYPE_CHECKING

from nodl.plugins import EXTENSION_POINTS, ExtensionPoint, PluginError, instantiate_extensions

if TYPE_CHECKING:
    from collections.abc import Callable, Sequence

    from nodl.diagnostics import Diagnostic
    from nodl.system import ResolvedNode

__all__ = ['GENERATOR_GROUP', 'GeneratedFile', 'GenerateOptions', 'GeneratorExtension',
           'GenerationError', 'load_generators', 'generate', 'write_files', 'default_class_name',
           'check_options']

#: The entry point group of generators (entry point name = ``--language`` value).
GENERATOR_GROUP = 'nodl.generators'


@dataclass(frozen=True)
class GeneratedFile:
    """One generated file: its path relative to the output folder, and its text."""

    path: str
    text: str


@dataclass(frozen=True)
class GenerateOptions:
    """What the user chose; a generator ignores what does not apply to its language."""

    #: The stem of the generated class: ``<class_name>Base`` (``LaserDriver``).
    class_name: str
    #: The node name the constructor defaults to (``laser_driver``).
    node_name: str
    #: The C++ namespace (or Python package hint) the code goes into; '' for the generator's default.
    namespace: str = ''
    #: C++: register the class as an rclcpp component.
    component: bool = False


class GenerationError(Exception):
    """The definition cannot be generated in this language (the message says why and what to do)."""


class GeneratorExtension(ExtensionPoint):
    """Base class of generators (the ``nodl.generators`` extension point).

    Version 1.0: ``generate(node, options) -> list[GeneratedFile]``; class
    attributes ``LANGUAGE`` (the ``--language`` value) and ``CLIENT_LIBRARY``
    (``rclpy``, ``rclcpp``: the base variant the node is resolved with).
    Output must be deterministic: the same input gives byte-identical files.
    """

    EXTENSION_POINT_VERSION = EXTENSION_POINTS[GENERATOR_GROUP].version
    #: The language name, as given to ``--language``.
    LANGUAGE: str = ''
    #: The client library the generated code uses (decides the base's variant).
    CLIENT_LIBRARY: str = ''

    def generate(self, node: ResolvedNode, options: GenerateOptions) -> list[GeneratedFile]:
        """The files implementing ``node``; raises :class:`GenerationError` for what cannot be generated."""
        raise NotImplementedError


def load_generators(on_error: Callable[[PluginError], None] | None = None
                    ) -> dict[str, GeneratorExtension]:
    """The installed generators by language (a broken plug-in is reported through ``on_error``)."""
    found: dict[str, GeneratorExtension] = {}
    for name, generator in instantiate_extensions(GENERATOR_GROUP, on_error=on_error).items():
        found[getattr(generator, 'LANGUAGE', '') or name] = generator
    return found


def default_class_name(name: str) -> str:
    """The class stem for a definition file or executable name (``laser_driver.nodl.yaml`` -> ``LaserDriver``)."""
    from nodl.plan.identifiers import pascal_case

    return pascal_case(default_node_name(name))


def default_node_name(name: str) -> str:
    """The node name for a definition file or executable (``dir/laser_driver.nodl.yaml`` -> ``laser_driver``)."""
    from nodl.plan.identifiers import snake_case

    base = os.path.basename(name)
    for ending in ('.nodl.yaml', '.nodl.yml', '.nodl.json', '.yaml', '.yml', '.json'):
        if base.endswith(ending):
            base = base[:-len(ending)]
            break
    return snake_case(base)


def generate(node: ResolvedNode, language: str, options: GenerateOptions,
             generators: dict[str, GeneratorExtension] | None = None) -> list[GeneratedFile]:
    """Generate ``node`` in ``language``; GenerationError for an unknown language."""
    available = load_generators() if generators is None else generators
    generator = available.get(language)
    if generator is None:
        known = ', '.join(sorted(available)) or 'none installed'
        raise GenerationError(f"no generator for language {language!r} (available: {known})")
    return generator.generate(node, options)


def check_options(options: GenerateOptions, language: str = '') -> list[Diagnostic]:
    """NODL707 for each option that is not a valid name: ``node_name`` (rmw's node name rules),
    ``class_name`` (an ASCII identifier, not a keyword of ``language``: it names classes and
    files), ``namespace`` (C++: identifiers separated by ``::``, no keywords)."""
    from nodl.diagnostics import Diagnostic, Severity
    from nodl.naming.validation import node_name_error
    from nodl.plan.identifiers import CPP_KEYWORDS, KEYWORDS, is_identifier

    problems: list[str] = []
    why = node_name_error(options.node_name)
    if why is not None:
        problems.append(f'--node-name {options.node_name!r}: {why}')
    keywords = KEYWORDS.get(language, frozenset())
    if not (options.class_name.isascii() and is_identifier(options.class_name)):
        problems.append(f'--class-name {options.class_name!r}: a class name is letters, digits and _, '
                        'not starting with a digit')
    elif options.class_name in keywords:
        problems.append(f'--class-name {options.class_name!r}: a {language} keyword')
    if options.namespace and language == 'cpp':
        parts = options.namespace.split('::')
        if not all(part.isascii() and is_identifier(part) and part not in CPP_KEYWORDS for part in parts):
            problems.append(f'--namespace {options.namespace!r}: a C++ namespace is identifiers '
                            'separated by ::, no keywords')
    return [Diagnostic(Severity.ERROR, f'{problem}; give a valid name', file='<command line>',
                       code='NODL707') for problem in problems]


def write_files(files: Sequence[GeneratedFile], out_dir: str, *, check: bool = False,
                force: bool = False) -> list[str]:
    """Write ``files`` under ``out_dir``; return the paths whose content changed.

    Each file is written as :func:`nodl.writing.write_marked` writes
    it: atomically, with a content marker, never over a file of the user's
    or one edited since it was generated (unless ``force``).  A file whose
    content is already the same is not touched (its time stamp stays, so
    build systems do not rebuild).  With ``check=True`` nothing is written:
    the result lists the files that are missing or stale (the marker
    included, so a hand-edited file is stale).  Every file is checked before
    any is written, so a refusal writes nothing.  Raises
    :class:`~nodl.writing.WriteError`: NODL708 for a path outside
    ``out_dir`` (a generated path that leaves it, or a folder under it that is a symbolic
    link to a place outside: :func:`nodl.writing.check_within`),
    NODL031/NODL032 for a file that is not nodl's to replace, NODL030 when a write fails.
    """
    from nodl.writing import WriteError, check_replaceable, check_within, holds_text, marked_text, write_marked

    planned: list[tuple[str, str]] = []
    for item in files:
        path = os.path.join(out_dir, item.path)
        problem = _outside(item.path, out_dir) or check_within(path, out_dir)
        if problem is not None:
            raise WriteError(problem)
        planned.append((path, marked_text(path, item.text)))
    changed: list[str] = []
    for path, text in planned:
        if holds_text(path, text):
            continue
        changed.append(path)
        if not check:
            refusal = check_replaceable(path, text, force=force)
            if refusal is not None:
                raise WriteError(refusal)
    if not check:
        for path, text in planned:
            if path in changed:
                write_marked(path, text, force=True, make_parents=True,  # checked above
                             within=out_dir)
    return changed


def _outside(relative: str, out_dir: str) -> Diagnostic | None:
    """NODL708 when the generated path ``relative`` would land outside ``out_dir``."""
    from nodl.diagnostics import Diagnostic, Severity

    normal = os.path.normpath(relative)
    if (not relative or os.path.isabs(relative) or normal == os.curdir or normal == os.pardir
            or normal.startswith(os.pardir + os.sep) or '\0' in relative):
        return Diagnostic(Severity.ERROR, f'a generated file would be written outside the output '
                          f'folder ({relative!r}); check --node-name and --class-name, or the '
                          'generator plug-in', file=out_dir, code='NODL708')
    return None
