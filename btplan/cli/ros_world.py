"""`--ros FILE.toml`: the robot of `btplan run` on ROS 2, and the check of its bindings."""

from __future__ import annotations

from typing import Any

from btplan.errors import InputError, Span, WorldError
from btplan.io import read_text
from btplan.model import Domain, Task

__all__ = ["check_ros_bindings", "open_ros_robot"]


def read_bindings(path: str, domain: Domain) -> Any:
    """The binding file at `path`, read and checked against `domain`."""
    from btplan.ros.bindings import load_bindings

    return load_bindings(path, read_text(path), domain)


def check_ros_bindings(path: str, domain: Domain) -> str:
    """Check the binding file against `domain`; a line saying what it binds."""
    bindings = read_bindings(path, domain)
    from btplan.ros.robot import rclpy_origin

    return (f"{path}: {len(bindings.actions)} actions and {len(bindings.conditions)} "
            f"conditions bound ({rclpy_origin()})")


def open_ros_robot(path: str, task: Task) -> Any:
    """The robot of the binding file, bound to the task, its action servers there.

    A server that does not come within `server_wait` is bad input naming it (exit 2):
    nothing has moved yet."""
    bindings = read_bindings(path, task.domain)
    from btplan.ros.robot import RosRobot

    robot = RosRobot(bindings, task)
    try:
        robot.bind(task)
        robot.wait_for_servers()
    except WorldError as error:
        robot.close()
        raise InputError(str(error), Span(path, 1, 1),
                         "start the robot's action servers first, or raise "
                         "[ros] server_wait") from None
    except BaseException:
        robot.close()
        raise
    return robot
