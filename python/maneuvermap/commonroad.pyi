"""Reading CommonRoad recordings and measuring their road users' room to maneuver (docs/commonroad.md)."""
from ._maneuvermap.commonroad import *
