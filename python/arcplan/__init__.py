"""arcplan from Python: robots and kinematics, scenes and collision checks, planning with the arc
planner and OMPL's planners, PCHIP time scaling (docs/python.md). NumPy arrays in and out; every
error is arcplan.Error with arcplan's message."""
from ._arcplan import *  # noqa: F401,F403
