#!/usr/bin/python3
"""3D view of the TCP paths of each planner's median run on one benchmark problem, with the obstacles.

Reads paths/<suite>/<problem>/scene.json (obstacles: sphere, box, cylinder with position and rotation; start
and goal TCP positions) and paths/<suite>/<problem>/<planner>.csv (columns t,tcp_speed,x,y,z).

    plot_benchmark_paths3d.py --paths DIR/paths/<suite>/<problem> [DIR2/...] --out paths3d.png [--title T] [--order ...]
"""
import argparse
import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402,F401  (registers the 3d projection)
from mpl_toolkits.mplot3d import Axes3D  # noqa: E402,F401

from plot_benchmark_data import median_run_files, planner_order, read_median_run, read_scene  # noqa: E402


def transform(rotation, position, point):
    return [sum(rotation[r][c] * point[c] for c in range(3)) + position[r] for r in range(3)]


def draw_obstacle(axis, obstacle):
    shape, rotation, position = obstacle["shape"], obstacle["rotation"], obstacle["position"]
    style = dict(color="firebrick", linewidth=0.6, alpha=0.7)
    if shape == "sphere":
        r = obstacle["radius"]
        for k in range(7):
            latitude = -math.pi / 2 + math.pi * k / 6
            ring = [transform(rotation, position, [r * math.cos(latitude) * math.cos(a), r * math.cos(latitude) * math.sin(a),
                                                   r * math.sin(latitude)]) for a in [2 * math.pi * i / 24 for i in range(25)]]
            axis.plot(*zip(*ring), **style)
        for k in range(6):
            longitude = math.pi * k / 6
            ring = [transform(rotation, position, [r * math.cos(t) * math.cos(longitude), r * math.cos(t) * math.sin(longitude),
                                                   r * math.sin(t)]) for t in [2 * math.pi * i / 24 for i in range(25)]]
            axis.plot(*zip(*ring), **style)
    elif shape == "box":
        sx, sy, sz = [s / 2 for s in obstacle["size"]]
        corners = [[x, y, z] for x in (-sx, sx) for y in (-sy, sy) for z in (-sz, sz)]
        for i in range(8):
            for j in range(i + 1, 8):
                if sum(corners[i][k] != corners[j][k] for k in range(3)) == 1:
                    axis.plot(*zip(transform(rotation, position, corners[i]), transform(rotation, position, corners[j])),
                              **style)
    elif shape == "cylinder":
        r, h = obstacle["radius"], obstacle["length"] / 2
        for z in (-h, 0.0, h):
            ring = [transform(rotation, position, [r * math.cos(a), r * math.sin(a), z])
                    for a in [2 * math.pi * i / 24 for i in range(25)]]
            axis.plot(*zip(*ring), **style)
        for k in range(8):
            a = 2 * math.pi * k / 8
            axis.plot(*zip(transform(rotation, position, [r * math.cos(a), r * math.sin(a), -h]),
                           transform(rotation, position, [r * math.cos(a), r * math.sin(a), h])), **style)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--paths", required=True, nargs="+", help="median-run folders (several for merged shards)")
    parser.add_argument("--out", required=True)
    parser.add_argument("--title", default="")
    parser.add_argument("--order", default="")
    args = parser.parse_args()

    scene = read_scene(args.paths)
    files = median_run_files(args.paths)
    order = planner_order(files, args.order)

    figure = plt.figure(figsize=(10, 8))
    axis = figure.add_subplot(111, projection="3d")
    colors = plt.get_cmap("tab20")
    points = [scene["start"], scene["goal"]]
    for index, planner in enumerate(order):
        xyz = [(r["x"], r["y"], r["z"]) for r in read_median_run(files[planner])]
        if not xyz:
            continue
        points += xyz
        style = "-" if planner.startswith("arc") else "--"
        axis.plot(*zip(*xyz), style, color=colors(index % 20), linewidth=1.3, label=planner)
    for obstacle in scene["obstacles"]:
        if obstacle["name"] != "table":
            draw_obstacle(axis, obstacle)
    axis.scatter(*zip(scene["start"], scene["goal"]), color="black", s=25)
    axis.text(*scene["start"], " A", fontsize=9)
    axis.text(*scene["goal"], " B", fontsize=9)
    # Equal scale on all axes, so arcs look like arcs.
    low = [min(p[k] for p in points) for k in range(3)]
    high = [max(p[k] for p in points) for k in range(3)]
    half = max(h - l for l, h in zip(low, high)) / 2 + 0.05
    for setter, l, h in zip((axis.set_xlim, axis.set_ylim, axis.set_zlim), low, high):
        setter((l + h) / 2 - half, (l + h) / 2 + half)
    axis.set_box_aspect((1, 1, 1))
    axis.set_xlabel("x (m)")
    axis.set_ylabel("y (m)")
    axis.set_zlabel("z (m)")
    axis.legend(fontsize=7, loc="upper left")
    axis.set_title(args.title or "TCP paths of each planner's median run")
    figure.tight_layout()
    figure.savefig(args.out, dpi=110)
    return 0


if __name__ == "__main__":
    sys.exit(main())
