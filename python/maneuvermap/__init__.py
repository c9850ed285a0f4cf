"""Collision-avoidance motion planning with Maneuverability Maps.

The planner of the C++ library ``maneuvermap`` (``mm::plan``) and its value types, with the
simulator in ``maneuvermap.sim`` and the CommonRoad reader and measurement in
``maneuvermap.commonroad``. Names are those of the C++ library and of docs/method.md; units are
SI (metres, seconds, radians). See docs/python.md.
"""
from . import _maneuvermap
from ._maneuvermap import *  # noqa: F401,F403  the planner and its value types
from ._maneuvermap import __version__  # noqa: F401

from . import sim, commonroad  # noqa: E402,F401
