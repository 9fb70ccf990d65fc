"""Plan on the thesis scene, time-scale at 0.25 m/s, plot the TCP speed — notebook-style, one cell
per step. Run: PYTHONPATH=build/python python3 examples/python/plan_and_scale.py speed.png"""
import sys

import matplotlib

matplotlib.use("Agg")  # no display needed; the figure goes to a file
import matplotlib.pyplot as plt
import numpy as np

import arcplan

# %% The thesis workcell: UR10e, table, the particle O on the straight line A -> B.
scene = arcplan.load_scene("scenes/thesis_obstacle.yaml")
print(scene)

# %% The arc planner (thesis detour h = 0.5 r) and RRTConnect, both time-scaled at the collaborative 0.25 m/s.
results = {
    "arc, h = 0.5 r": arcplan.plan(scene, params={"sagitta": 0.1}, vmax=0.25),
    "RRTConnect + simplifier": arcplan.plan(scene, planner="RRTConnect", seed=1, vmax=0.25),
}
for name, result in results.items():
    print(f"{name:24s} {result.status}: {result.waypoints} waypoints, TCP path {result.tcp_path_length_m:.4f} m, "
          f"{result.execution_time_s:.3f} s, peak TCP speed {result.peak_tcp_speed_mps:.4f} m/s")

# %% The same arc path scaled again with a gentler ramp, straight from its joint path.
gentle = arcplan.scale(scene.robot, results["arc, h = 0.5 r"].path, vmax=0.25, rise_time=0.5)
print(f"arc with 0.5 s ramps      {gentle.duration:.3f} s")

# %% TCP speed over time.
figure, axes = plt.subplots(figsize=(8, 4))
for name, result in results.items():
    trajectory = result.trajectory
    axes.plot(trajectory.time, trajectory.tcp_speed, label=f"{name} ({trajectory.duration:.2f} s)")
axes.plot(gentle.time, gentle.tcp_speed, "--", label=f"arc, 0.5 s ramps ({gentle.duration:.2f} s)")
axes.axhline(0.25, color="grey", linewidth=0.8, label="v_max 0.25 m/s")
axes.set(xlabel="time (s)", ylabel="TCP speed (m/s)", title="thesis scene A -> B at 0.25 m/s")
axes.set_ylim(0, 0.3)
axes.legend(loc="lower center")
figure.tight_layout()
figure.savefig(sys.argv[1] if len(sys.argv) > 1 else "plan_and_scale.png", dpi=80)
assert np.all(np.concatenate([r.trajectory.tcp_speed for r in results.values()]) <= 0.25 + 1e-9)
