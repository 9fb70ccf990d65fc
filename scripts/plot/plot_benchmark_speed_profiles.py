#!/usr/bin/python3
"""TCP speed over time of each planner's median run on one benchmark problem.

Reads the median-run files a campaign writes to paths/<suite>/<problem>/<planner>.csv (header line
`t,tcp_speed,x,y,z` after `#` comment lines) and draws one curve per planner with the speed limit.

    plot_benchmark_speed_profiles.py --paths DIR/paths/<suite>/<problem> --out speed.png [--vmax 0.25] [--title T]
                                     [--order arc-auto,RRTConnect,...]
"""
import argparse
import csv
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read_profile(path):
    with open(path) as stream:
        lines = [line for line in stream if not line.startswith("#")]
    return [{key: float(value) for key, value in row.items()} for row in csv.DictReader(lines)]


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--paths", required=True)
    parser.add_argument("--vmax", type=float, help="TCP speed limit; default: vmax_mps of the folder's scene.json")
    parser.add_argument("--out", required=True)
    parser.add_argument("--title", default="")
    parser.add_argument("--order", default="")
    args = parser.parse_args()

    if args.vmax is None:
        with open(os.path.join(args.paths, "scene.json")) as stream:
            args.vmax = json.load(stream)["vmax_mps"]
    planners = sorted(name[:-4] for name in os.listdir(args.paths) if name.endswith(".csv"))
    if not planners:
        print("plot_benchmark_speed_profiles: no median-run files in %s" % args.paths, file=sys.stderr)
        return 1
    order = [p for p in args.order.split(",") if p in planners] if args.order else []
    order += [p for p in planners if p not in order]

    figure, axis = plt.subplots(figsize=(11, 5.5))
    colors = plt.get_cmap("tab20")
    for index, planner in enumerate(order):
        rows = read_profile(os.path.join(args.paths, planner + ".csv"))
        if not rows:
            continue
        duration = rows[-1]["t"]
        style = "-" if planner.startswith("arc") else "--"
        axis.plot([r["t"] for r in rows], [r["tcp_speed"] for r in rows], style, color=colors(index % 20),
                  linewidth=1.4, label="%s (%.2f s)" % (planner, duration))
    axis.axhline(args.vmax, color="black", linestyle=":", linewidth=1.0, label="v_max = %.3g m/s" % args.vmax)
    axis.set_xlabel("time (s)")
    axis.set_ylabel("TCP speed (m/s)")
    axis.set_ylim(bottom=0.0)
    axis.grid(color="lightgrey", linewidth=0.5)
    axis.legend(fontsize=8, loc="center left", bbox_to_anchor=(1.0, 0.5))
    axis.set_title(args.title or "TCP speed of each planner's median run (by execution time)")
    figure.tight_layout()
    figure.savefig(args.out, dpi=110)
    return 0


if __name__ == "__main__":
    sys.exit(main())
