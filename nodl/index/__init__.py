"""Looking things up in the ament index (without needing ROS installed)."""
