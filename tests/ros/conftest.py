"""ROS 2 in the tests: its Python packages are compiled to bytecode on their first import,
which on a fresh install makes the first process of the first test seconds slower than
the rest; one import before the tests start takes that out of their timing."""

from __future__ import annotations

import subprocess
import sys

import pytest


@pytest.fixture(scope="session", autouse=True)
def ros_compiled() -> None:
    subprocess.run([sys.executable, "-c", "import rclpy, rclpy.action, action_msgs.msg, "
                    "std_msgs.msg, std_srvs.srv, test_msgs.action, btplan.ros.robot"],
                   check=True, timeout=300)
