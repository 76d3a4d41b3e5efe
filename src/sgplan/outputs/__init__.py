"""Robot-ready outputs of a planned path: metric waypoints (dense and simplified), the events along the
path, and the files a robot stack reads (CSV, a ROS ``nav_msgs/Path``-shaped YAML per floor)."""
