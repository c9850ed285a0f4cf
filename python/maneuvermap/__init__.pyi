"""Collision-avoidance motion planning with Maneuverability Maps (see docs/python.md)."""
from ._maneuvermap import *
from ._maneuvermap import __version__ as __version__
