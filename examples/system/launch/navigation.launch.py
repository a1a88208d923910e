"""The rover's navigation: localisation, planning and path following."""

import os

from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument, GroupAction
from launch.conditions import IfCondition
from launch.substitutions import LaunchConfiguration
from launch_ros.actions import Node, SetRemap


def generate_launch_description():
    params = os.path.join(os.path.dirname(__file__), '..', 'config', 'navigation.yaml')
    return LaunchDescription([
        DeclareLaunchArgument('use_localizer', default_value='true'),
        # when launched on its own, navigation brings its own diagnostic aggregator
        DeclareLaunchArgument('with_aggregator', default_value='true'),
        GroupAction([
            SetRemap(src='pose', dst='localization/pose'),
            # PLANTED type-mismatch (wheel_odom), qos-warning (imu/data) and
            # orphan-subscription (gps/fix, no GPS receiver is launched)
            Node(package='rover_navigation', executable='localizer',
                 condition=IfCondition(LaunchConfiguration('use_localizer'))),
            # PLANTED orphan-service-client: no costmap serves clear_costmap
            Node(package='rover_navigation', executable='planner', parameters=[params]),
            Node(package='rover_navigation', executable='path_follower', parameters=[params]),
        ]),
        # PLANTED duplicate-node: rover.launch.xml starts an aggregator already, and
        # includes this file without with_aggregator:=false
        Node(package='rover_base', executable='diagnostic_aggregator',
             condition=IfCondition(LaunchConfiguration('with_aggregator'))),
    ])
