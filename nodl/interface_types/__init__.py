"""Interface types: the messages, services and actions a definition names, as installed.

A shared layer below every consumer (it imports none):

* :mod:`.resolve`: ``pkg/msg/T`` -> the files that define it, from the ament
  index's ``rosidl_interfaces`` resource or from a package's source folder;
* :mod:`.tree`: those files read with ROS's own parsers (rosidl_parser,
  rosidl_adapter) into a typed tree (fields, bounds, defaults, constants,
  comments; nested types expanded; request/response, goal/result/feedback);
* :mod:`.mapping`: IDL types -> C++ and Python types as the installed rosidl
  generators write them, and parameter types as rclcpp and rclpy map them;
* :mod:`.hashes`: RIHS01 type hashes from rosidl's type-description generator;
* :mod:`.check`: the type names of a NoDL document checked against an index.

The ROS parsers are imported only when a file is read: resolving names needs
no ROS package at all.
"""

from __future__ import annotations

from nodl.interface_types.resolve import (
                                                  InterfaceIndex,
                                                  InterfacePackage,
                                                  Resolution,
                                                  TypeName,
                                                  interface_index,
)

__all__ = ['InterfaceIndex', 'InterfacePackage', 'Resolution', 'TypeName', 'interface_index']
