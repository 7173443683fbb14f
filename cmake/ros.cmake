# ROS layer targets (nodelet, node, rostests).
