"""ROS 2: the blended loop drives a ROS 2 robot (`btplan run DOMAIN --ros bindings.toml`).

- `bindings`: the binding file (TOML), read and checked against the domain and the ROS
  message types: each action template to a ROS 2 action, each condition to a topic or a
  service, the timeouts;
- `expressions`: the small expressions a binding file fills goals and reads conditions
  with, checked when the file is read;
- `robot`: `RosRobot`, a `btplan.robot.Robot` whose skills are action goals and whose
  conditions read topics and services: the bridge is one robot, not a second loop;
- `tree_topics`: the tree (BT.CPP XML) and each tick's statuses on topics, for ros2 bag
  and other nodes.

rclpy is imported from whichever ROS 2 the Python path has: a sourced install, or the
Kilted wheels of `pip install 'btplan[ros]'`.
"""
