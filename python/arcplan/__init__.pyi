# Type stubs of arcplan's core (robots, scenes, planning, time scaling): what editors complete.
# The model loop and benchmarks have their own stubs (model.pyi, bench.pyi).
import os
import pathlib
from typing import Any, Dict, List, Mapping, Optional, Tuple, Union

import numpy as np
import numpy.typing as npt

from . import bench as bench, model as model

ArrayLike = npt.ArrayLike
FloatArray = npt.NDArray[np.float64]
PathLike = Union[str, os.PathLike]

class Error(RuntimeError):
    """Bad input or an impossible request; the message names the file:line or field."""

class Robot:
    name: str
    dof: int
    source_file: pathlib.Path
    joint_names: List[str]
    link_names: List[str]
    tip_link: str
    lower_limits: FloatArray
    upper_limits: FloatArray
    velocity_limits: FloatArray
    def fk(self, q: ArrayLike, link: Optional[str] = None) -> FloatArray: ...
    def jacobian(self, q: ArrayLike, link: Optional[str] = None) -> FloatArray: ...
    def ik(self, pose: ArrayLike) -> FloatArray: ...
    def ik_nearest(self, pose: ArrayLike, seed: ArrayLike) -> Optional[FloatArray]: ...

def load_robot(urdf: Optional[str] = None, *, ur_type: Optional[str] = None, description: Optional[str] = None,
               kinematics: Optional[str] = None, base_link: str = "base_link", tip_link: str = "tool0",
               tcp_offset: Optional[ArrayLike] = None) -> Robot: ...
def pose_from_xyz_rpy(xyz_rpy: ArrayLike) -> FloatArray: ...

class Distance:
    obstacle_distance: float
    obstacle_pair: Tuple[str, str]
    self_distance: float
    self_pair: Tuple[str, str]
    minimum: float
    clearance: float

class Scene:
    name: str
    source_file: pathlib.Path
    query_names: List[str]
    obstacle_names: List[str]
    link_names: List[str]
    robot: Robot
    def is_valid(self, q: ArrayLike) -> Union[bool, npt.NDArray[np.bool_]]: ...
    def collisions(self, q: ArrayLike) -> List[Tuple[str, str]]: ...
    def distance(self, q: ArrayLike) -> Distance: ...

def load_scene(scene_file: PathLike) -> Scene: ...

class Trajectory:
    time: FloatArray
    q: FloatArray
    qd: FloatArray
    qdd: FloatArray
    tcp_speed: FloatArray
    tcp_position: FloatArray
    knot_times: FloatArray
    knots: FloatArray
    dense_path: FloatArray
    duration: float
    tcp_path_length: float
    tcp_speed_limit: float
    joint_speed_limits: FloatArray
    metrics: Dict[str, Optional[float]]

def scale(robot: Robot, path: ArrayLike, *, vmax: float = 0.25, rise_time: float = 0.2,
          max_tcp_acceleration: Optional[float] = None) -> Trajectory: ...

class PlanResult:
    status: str
    reason: str
    scene: str
    query: str
    planner: str
    parameters: Dict[str, str]
    seed: Optional[int]
    time_limit_s: float
    vmax_mps: Optional[float]
    clearance_m: float
    clearance_kept: Optional[bool]
    solve_time_s: float
    simplification_time_s: float
    mode: Optional[str]
    fallback_reason: Optional[str]
    path: FloatArray
    waypoints: int
    trajectory: Optional[Trajectory]
    # The metrics of docs/metrics.md (None without a path; the timed ones None without vmax).
    execution_time_s: Optional[float]
    tcp_path_length_m: Optional[float]
    joint_path_length_rad: Optional[float]
    mean_tcp_speed_mps: Optional[float]
    peak_tcp_speed_mps: Optional[float]
    time_above_limit_s: Optional[float]
    min_clearance_m: Optional[float]
    max_joint_speed_ratio: Optional[float]
    def to_dict(self) -> Dict[str, Any]: ...

def plan(scene_file: Union[PathLike, Scene], query: Optional[str] = None, planner: str = "arc",
         params: Mapping[str, Any] = {}, seed: Optional[int] = None, time_limit: float = 1.0,
         vmax: Optional[float] = None, clearance: float = 0.0) -> PlanResult: ...
def planner_names() -> List[str]: ...
