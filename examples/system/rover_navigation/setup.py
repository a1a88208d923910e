from setuptools import setup

from nodl.packaging import nodl_data_files

package_name = 'rover_navigation'

setup(
    name=package_name,
    version='0.1.0',
    packages=[package_name],
    data_files=[
        ('share/ament_index/resource_index/packages', ['resource/' + package_name]),
        ('share/' + package_name, ['package.xml']),
        *nodl_data_files(package_name,
                         nodes={'imu_filter': 'nodl/imu_filter.nodl.yaml',
                                'localizer': 'nodl/localizer.nodl.yaml',
                                'planner': 'nodl/planner.nodl.yaml',
                                'path_follower': 'nodl/path_follower.nodl.yaml'},
                         # the names the executables give their nodes when launched without one
                         node_names={'imu_filter': 'imu_filter', 'localizer': 'localizer',
                                     'planner': 'planner', 'path_follower': 'path_follower'}),
    ],
)
