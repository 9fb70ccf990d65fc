#!/usr/bin/python3
"""TCP speed over time of each planner's median run on one benchmark problem.

Reads the median-run files a campaign writes to paths/<suite>/<problem>/<planner>.csv (header line
`t,tcp_speed,x,y,z` after `#` comment lines) and draws one curve per planner with the speed limit.

    plot_benchmark_speed_profiles.py --paths DIR/paths/<suite>/<problem> [DIR2/...] --out speed.png [--vmax 0.25]
                                     [--title T] [--order arc-auto,RRTConnect,...]
"""
import argparse
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from plot_benchmark_data import median_run_files, planner_order, read_median_run, read_scene  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--paths", required=True, nargs="+", help="median-run folders (several for merged shards)")
    parser.add_argument("--vmax", type=float, help="TCP speed limit; default: vmax_mps of the folder's scene.json")
    parser.add_argument("--out", required=True)
    parser.add_argument("--title", default="")
    parser.add_argument("--order", default="")
    args = parser.parse_args()

    if args.vmax is None:
        args.vmax = read_scene(args.paths)["vmax_mps"]
    files = median_run_files(args.paths)
    if not files:
        print("plot_benchmark_speed_profiles: no median-run files in %s" % ", ".join(args.paths), file=sys.stderr)
        return 1
    order = planner_order(files, args.order)

    figure, axis = plt.subplots(figsize=(11, 5.5))
    colors = plt.get_cmap("tab20")
    for index, planner in enumerate(order):
        rows = read_median_run(files[planner])
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
