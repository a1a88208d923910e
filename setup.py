"""Packaging glue that pyproject.toml cannot express: files outside the Python package.

* the ament index marker and package.xml, so that colcon and the ament index
  see this project (``nodl_toolkit``) like any ROS package;
* the ``ament_nodl`` CMake package (cmake/ament_nodl), so that
  ``find_package(ament_nodl)`` works in an ament_cmake package once this
  project is installed.
"""

from setuptools import setup

setup(
    data_files=[
        ('share/ament_index/resource_index/packages', ['resource/nodl_toolkit']),
        ('share/nodl_toolkit', ['package.xml']),
        ('share/ament_index/resource_index/packages', ['resource/ament_nodl/ament_nodl']),
        ('share/ament_nodl/cmake', ['cmake/ament_nodl/ament_nodlConfig.cmake',
                                    'cmake/ament_nodl/ament_nodl_register.cmake']),
    ],
)
