#!/usr/bin/python3
"""Plot a time-scaled trajectory written by `arcplan scale --traj-csv` (columns t, q0..q5, qd0..qd5,
qdd0..qdd5, tcp_speed, tcp_x, tcp_y, tcp_z) like the seed thesis' figures 4.13-4.24: 3D TCP path, joint
positions, joint velocities (with their limits) and the TCP linear speed (with the limit).

Usage: plot_trajectory.py TRAJECTORY.csv OUT.png [--vmax V] [--title T] [--joint-limit L]x6
The PNG is written to a temporary file and renamed, so a failed run never leaves half a picture.
"""
import argparse
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

JOINTS = ["shoulder pan", "shoulder lift", "elbow", "wrist 1", "wrist 2", "wrist 3"]


def read_trajectory(path):
    with open(path, encoding="utf-8") as handle:
        header = handle.readline().strip().split(",")
    expected = ["t"] + [f"{name}{j}" for name in ("q", "qd", "qdd") for j in range(6)]
    expected += ["tcp_speed", "tcp_x", "tcp_y", "tcp_z"]
    if header != expected:
        sys.exit(f"plot_trajectory.py: {path}: unexpected header, expected {','.join(expected)}")
    data = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)
    return {name: data[:, i] for i, name in enumerate(header)}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("trajectory")
    parser.add_argument("output")
    parser.add_argument("--vmax", type=float, default=None, help="TCP speed limit [m/s]")
    parser.add_argument("--title", default="")
    parser.add_argument("--joint-limit", type=float, action="append", default=[], help="joint speed limits [rad/s]")
    args = parser.parse_args()

    d = read_trajectory(args.trajectory)
    t = d["t"]
    fig = plt.figure(figsize=(13, 9))
    title = f"{args.title}  " if args.title else ""
    title += f"final time {t[-1]:.2f} s, peak TCP speed {d['tcp_speed'].max():.4f} m/s"
    if args.vmax:
        title += f" (limit {args.vmax:g} m/s)"
    fig.suptitle(title)

    path3d = fig.add_subplot(2, 2, 1, projection="3d")
    path3d.plot(d["tcp_x"], d["tcp_y"], d["tcp_z"], color="tab:blue")
    path3d.scatter(d["tcp_x"][[0, -1]], d["tcp_y"][[0, -1]], d["tcp_z"][[0, -1]], color=["tab:green", "tab:red"])
    path3d.set_xlabel("x [m]")
    path3d.set_ylabel("y [m]")
    path3d.set_zlabel("z [m]")
    path3d.set_title("TCP position (base_link)")

    positions = fig.add_subplot(2, 2, 2)
    velocities = fig.add_subplot(2, 2, 3)
    for j, name in enumerate(JOINTS):
        positions.plot(t, d[f"q{j}"], label=name)
        line, = velocities.plot(t, d[f"qd{j}"], label=name)
        if j < len(args.joint_limit):
            for sign in (1, -1):
                velocities.axhline(sign * args.joint_limit[j], color=line.get_color(), linestyle=":", linewidth=0.8)
    positions.set_title("joint positions")
    positions.set_ylabel("q [rad]")
    velocities.set_title("joint velocities (dotted: limits)")
    velocities.set_ylabel("qd [rad/s]")
    if args.joint_limit:
        peak = max(abs(d[f"qd{j}"]).max() for j in range(6))
        velocities.set_ylim(-1.3 * peak - 1e-3, 1.3 * peak + 1e-3)
    for axis in (positions, velocities):
        axis.set_xlabel("t [s]")
        axis.grid(True, alpha=0.3)
        axis.legend(fontsize=7, loc="best")

    speed = fig.add_subplot(2, 2, 4)
    speed.plot(t, d["tcp_speed"], color="tab:blue", label="TCP speed (FK, every sample)")
    if args.vmax:
        speed.axhline(args.vmax, color="tab:red", linestyle="--", label=f"limit {args.vmax:g} m/s")
    speed.set_title("TCP linear speed")
    speed.set_xlabel("t [s]")
    speed.set_ylabel("v [m/s]")
    speed.grid(True, alpha=0.3)
    speed.legend(fontsize=8, loc="lower center")

    fig.tight_layout()
    temporary = f"{args.output}.tmp.{os.getpid()}.png"
    try:
        fig.savefig(temporary, dpi=110)
        os.replace(temporary, args.output)
    finally:
        if os.path.exists(temporary):
            os.remove(temporary)


if __name__ == "__main__":
    main()
