"""Shared fixtures of the Python module's tests (run by CTest: tests/python/CMakeLists.txt)."""
import math
import os
import pathlib

import numpy as np
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


def assert_same_attributes(original, copy, where="value"):
    """Every public attribute of `copy` equals the original's, recursively through the bound types,
    lists and arrays (a pickled round trip); `where` names the attribute that differs."""
    assert type(copy) is type(original), f"{where}: {type(copy).__name__} instead of {type(original).__name__}"
    if isinstance(original, np.ndarray):
        assert original.dtype == copy.dtype and original.shape == copy.shape, where
        np.testing.assert_array_equal(copy, original, err_msg=where)
    elif isinstance(original, (list, tuple)):
        assert len(copy) == len(original), f"{where}: {len(copy)} elements instead of {len(original)}"
        for k, (a, b) in enumerate(zip(original, copy)):
            assert_same_attributes(a, b, f"{where}[{k}]")
    elif type(original).__module__.startswith("maneuvermap") and not hasattr(original, "__members__"):
        names = [n for n in dir(original) if not n.startswith("_") and not callable(getattr(original, n))]
        assert names, f"{where}: no attributes to compare"
        for name in names:
            assert_same_attributes(getattr(original, name), getattr(copy, name), f"{where}.{name}")
    elif isinstance(original, float) and math.isnan(original):
        assert math.isnan(copy), f"{where}: {copy!r} instead of nan"
    else:
        assert copy == original, f"{where}: {copy!r} instead of {original!r}"
