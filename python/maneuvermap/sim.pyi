"""The traffic microsimulator and its scenario files (docs/simulator.md, docs/scenario-format.md)."""
from ._maneuvermap.sim import *
