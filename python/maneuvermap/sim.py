"""The traffic microsimulator and its scenario files (docs/simulator.md, docs/scenario-format.md)."""
from ._maneuvermap import sim as _sim

globals().update({name: getattr(_sim, name) for name in dir(_sim) if not name.startswith("__")})
__all__ = [name for name in dir(_sim) if not name.startswith("_")]
