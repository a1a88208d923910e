"""The C++ (rclcpp) generator: ``nodl generate --language cpp``.

For a node definition it writes ``<stem>_base.hpp`` and ``<stem>_base.cpp``
(``stem`` from the class name: ``LaserDriver`` -> ``laser_driver``) holding,
in a namespace, ``struct <Name>Params`` (the parameters nested by dotted
name) and ``class <Name>Base`` deriving from ``rclcpp::Node`` or
``rclcpp_lifecycle::LifecycleNode``:

* constructors ``(const std::string & node_name = "<default>", const
  rclcpp::NodeOptions & options = rclcpp::NodeOptions())`` and ``(const
  rclcpp::NodeOptions &)`` (components);
* members ``pub_<name>_``, ``sub_<name>_``, ``srv_<name>_``, ``cli_<name>_``,
  ``action_server_<name>_``, ``action_client_<name>_`` created with an
  ``rclcpp::QoS`` built from every declared policy (services included; a
  lifecycle node's publishers are lifecycle publishers, created on configure
  and switched on activate and deactivate);
* pure virtual callbacks ``on_<subscription>(msg)``,
  ``on_<service>(request, response)`` and, per action server,
  ``on_<action>_goal``, ``on_<action>_cancel`` and ``on_<action>_accepted``;
* parameters declared with descriptors (description, read_only, additional
  constraints in words, integer or floating point range), required ones
  reported together, every validator enforced at start-up and at set time
  (the whole batch rejected with the validator's requirement as ``reason``),
  validation in the on-set callback and commit in the post-set callback,
  ``params()``, ``is_old()``, ``try_update()`` and the hook
  ``on_parameters_changed()``; custom validators ``ns::fn`` are functions the
  user defines (declared in the header, returning an empty string to accept).

The generated code depends on rclcpp and the interface packages only.  The
header's ``// nodl-dependencies:`` line names the packages it needs (read by
the CMake function ``ament_nodl_generate_cpp``).
"""

from __future__ import annotations

import os
from typing import TYPE_CHECKING

from nodl.generate import GeneratedFile, GenerateOptions, GenerationError, GeneratorExtension
from nodl.plan.identifiers import CPP_KEYWORDS, is_identifier, snake_case

if TYPE_CHECKING:
    from nodl.generate.cpp.node_code import CppNode
    from nodl.system import ResolvedNode

__all__ = ['CppGenerator', 'plan_cpp', 'generate_cpp', 'cpp_dependencies', 'cpp_file_names']


def _namespace(options: GenerateOptions) -> str:
    if options.namespace:
        parts = options.namespace.split('::')
        if not all(is_identifier(p) and p not in CPP_KEYWORDS for p in parts):
            raise GenerationError(f'{options.namespace!r} is not a C++ namespace (identifiers '
                                  'separated by ::, no keywords)')
        return options.namespace
    name = snake_case(options.node_name)
    if name[0].isdigit():
        name = '_' + name
    return name + '_' if name in CPP_KEYWORDS else name


def plan_cpp(node: ResolvedNode, options: GenerateOptions) -> CppNode:
    """The C++ names of everything ``node``'s implementation provides."""
    from nodl.generate.cpp.node_code import plan_node
    from nodl.model import Base

    if not is_identifier(options.class_name) or options.class_name in CPP_KEYWORDS:
        raise GenerationError(f'{options.class_name!r} is not a C++ class name')
    return plan_node(list(node.implementation_entities()), class_name=options.class_name,
                     namespace=_namespace(options), node_name=options.node_name,
                     source=os.path.basename(node.file), lifecycle=node.base is Base.LIFECYCLE_NODE,
                     description=node.node.main.description or '', component=options.component)


def cpp_file_names(options: GenerateOptions) -> tuple[str, str]:
    """The header and source file names for ``options``."""
    stem = snake_case(options.class_name) + '_base'
    return stem + '.hpp', stem + '.cpp'


def generate_cpp(node: ResolvedNode, options: GenerateOptions) -> list[GeneratedFile]:
    """The header and source of ``node``'s rclcpp base class."""
    from nodl.generate.cpp.node_code import render_header, render_source

    plan = plan_cpp(node, options)
    return [GeneratedFile(plan.stem + '.hpp', render_header(plan)),
            GeneratedFile(plan.stem + '.cpp', render_source(plan))]


def cpp_dependencies(node: ResolvedNode, options: GenerateOptions) -> list[str]:
    """The ROS packages the generated code needs (for package.xml and CMake)."""
    from nodl.generate.cpp.node_code import dependencies

    return dependencies(plan_cpp(node, options))


class CppGenerator(GeneratorExtension):
    """rclcpp: ``<stem>_base.hpp`` and ``<stem>_base.cpp`` (see the module docstring)."""

    LANGUAGE = 'cpp'
    CLIENT_LIBRARY = 'rclcpp'

    def generate(self, node: ResolvedNode, options: GenerateOptions) -> list[GeneratedFile]:
        """The files implementing ``node``."""
        return generate_cpp(node, options)
