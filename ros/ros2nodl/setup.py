"""ros2nodl: registers `ros2 nodl` with ros2cli.

The command itself lives in the nodl_toolkit package (nodl.cli.ros2cli),
so that `nodl` and `ros2 nodl` share one set of verbs; this package only adds
the entry point (and, in package.xml, the dependency on ros2cli).
"""

from setuptools import setup

package_name = 'ros2nodl'

setup(
    name=package_name,
    version='0.1.0',
    packages=[],
    data_files=[
        ('share/ament_index/resource_index/packages', ['resource/' + package_name]),
        ('share/' + package_name, ['package.xml']),
    ],
    install_requires=['setuptools'],
    zip_safe=True,
    maintainer='NoDL toolkit maintainers',
    maintainer_email='maintainers@nodl-toolkit.example.org',
    description='The ros2 nodl command (a ros2cli extension)',
    license='Apache-2.0',
    entry_points={
        # the same entry point as in the toolkit's pyproject.toml (a test keeps them equal)
        'ros2cli.command': ['nodl = nodl.cli.ros2cli:NodlCommand'],
    },
)
