"""Code generation from node definitions: the ``nodl.generators`` extension point.

A generator turns a :class:`~nodl_schema.system.ResolvedNode` into source
files of one target language.  It implements what the node's own code
provides (the entities whose provider is the implementation, i.e. ``main``);
the base comes from the client library and mixins from other code.

Generators are entry points of the ``nodl.generators`` group named after the
language (``python``, ``cpp``); the built-ins are registered like third-party
ones.  A generator subclasses :class:`GeneratorExtension`, is instantiated
without arguments and returns :class:`GeneratedFile` objects: it never
writes, prints or exits.  :func:`write_files` writes them (or, with
``check=True``, only says which are stale).

Shared building blocks: :mod:`nodl_schema.generate.identifiers` (names to
identifiers, collision-free) and :mod:`nodl_schema.generate.parameters` (the
language-neutral parameter plan).
"""

from __future__ import annotations

import os
from dataclasses import dataclass

from nodl_schema.plugins import EXTENSION_POINTS, ExtensionPoint, PluginError, instantiate_extensions

TYPE_CHECKING = False  # typing costs the command line start-up time; only type checkers need it
if TYPE_CHECKING:
    from typing import Callable, Sequence

    from nodl_schema.system import ResolvedNode

__all__ = ['GENERATOR_GROUP', 'GeneratedFile', 'GenerateOptions', 'GeneratorExtension',
           'GenerationError', 'load_generators', 'generate', 'write_files', 'default_class_name']

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
    from nodl_schema.generate.identifiers import pascal_case

    return pascal_case(default_node_name(name))


def default_node_name(name: str) -> str:
    """The node name for a definition file or executable (``dir/laser_driver.nodl.yaml`` -> ``laser_driver``)."""
    from nodl_schema.generate.identifiers import snake_case

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


def write_files(files: Sequence[GeneratedFile], out_dir: str, *, check: bool = False) -> list[str]:
    """Write ``files`` under ``out_dir``; return the paths whose content changed.

    A file whose content is already the same is not touched (its time stamp
    stays, so build systems do not rebuild).  With ``check=True`` nothing is
    written: the result lists the files that are missing or stale.
    """
    changed: list[str] = []
    for item in files:
        path = os.path.join(out_dir, item.path)
        try:
            with open(path, encoding='utf-8', newline='') as f:
                same = f.read() == item.text
        except OSError:
            same = False
        if same:
            continue
        changed.append(path)
        if check:
            continue
        os.makedirs(os.path.dirname(path) or '.', exist_ok=True)
        with open(path, 'w', encoding='utf-8', newline='') as f:
            f.write(item.text)
    return changed
