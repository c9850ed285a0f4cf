"""Shared fixtures of the Python module's tests (run by CTest: tests/python/CMakeLists.txt)."""
import math
import os
import pathlib

import pytest

import maneuvermap as mm


@pytest.fixture
def source_dir():
    return pathlib.Path(os.environ["MM_SOURCE_DIR"])


@pytest.fixture
def cli():
    """The `maneuvermap` command of the same build."""
    return os.environ["MM_CLI"]


def crossing_scene(ego_speed=40.0 / 3.6, crossing_speed=36.0 / 3.6):
    """The scene of examples/01: the ego drives east, a car crosses from the north, timed to meet it."""
    track = mm.obstacle_track(id=1)
    for k in range(-50, 1):
        t = 0.01 * k
        track.history.append(mm.observation(t, mm.pose(22.0, 20.0 - crossing_speed * t, -math.pi / 2), crossing_speed))
    return mm.plan_input(time=0.0, ego=mm.ego_state(pose=mm.pose(0.0, 0.0, 0.0), speed=ego_speed),
                         nominal=mm.maneuver(0.0, 0.0), obstacles=[track])
