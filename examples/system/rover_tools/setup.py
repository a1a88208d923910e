from setuptools import setup

from nodl.packaging import nodl_data_files

package_name = 'rover_tools'

setup(
    name=package_name,
    version='0.1.0',
    packages=[package_name],
    data_files=[
        ('share/ament_index/resource_index/packages', ['resource/' + package_name]),
        ('share/' + package_name, ['package.xml']),
        # web_bridge (also launched) has no definition yet
        *nodl_data_files(package_name,
                         nodes={'teleop': 'nodl/teleop.nodl.yaml',
                                'mission_executive': 'nodl/mission_executive.nodl.yaml',
                                'dashboard': 'nodl/dashboard.nodl.yaml'},
                         node_names={'teleop': 'teleop', 'mission_executive': 'mission',
                                     'dashboard': 'dashboard'}),
    ],
)
