"""Reading CommonRoad recordings and measuring their road users' room to maneuver (docs/commonroad.md)."""
from ._maneuvermap import commonroad as _commonroad

globals().update({name: getattr(_commonroad, name) for name in dir(_commonroad) if not name.startswith("__")})
__all__ = [name for name in dir(_commonroad) if not name.startswith("_")]
