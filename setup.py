"""Packaging glue that pyproject.toml cannot express: files outside the Python package.

The ament index marker and package.xml are installed so that colcon and the
ament index see this project (``nodl_toolkit``) like any ROS package.
"""

from setuptools import setup

setup(
    data_files=[
        ('share/ament_index/resource_index/packages', ['resource/nodl_toolkit']),
        ('share/nodl_toolkit', ['package.xml']),
    ],
)
