"""arcplan from Python: robots and kinematics, scenes and collision checks, planning with the arc
planner and OMPL's planners, PCHIP time scaling (docs/python.md). NumPy arrays in and out; every
error is arcplan.Error with arcplan's message."""
from ._arcplan import *  # noqa: F401,F403
from ._arcplan import bench, model  # noqa: F401  the model loop and benchmark campaigns

# `import arcplan.model` and `from arcplan.bench import run` find the extension's submodules.
import sys as _sys

_sys.modules[__name__ + ".model"] = model
_sys.modules[__name__ + ".bench"] = bench
