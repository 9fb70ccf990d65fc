#!/usr/bin/python3
"""Box plots of the trajectory metrics (docs/metrics.md) per planner from an OMPL benchmark database.

Reads the SQLite file ompl_benchmark_statistics builds (runs, experiments, plannerConfigs) and draws one
figure with a panel per metric and a box per planner, over the successful runs (exact solution with
metrics). Tick labels show successes/runs, so a planner that rarely succeeds is visible as such.

    plot_benchmark_boxplots.py --db benchmark.db --out boxplots_all.png [--problem thesis/obstacle]
                               [--order arc-auto,RRTConnect,...] [--title TEXT]
                               --metric "execution time (s)" execution_time [--metric LABEL COLUMNS]...

The metrics come from the caller (arcplan passes its metric table, trajectory/metric_descriptors.h): one
panel per --metric, with its label and its database columns (comma-separated; the first non-NULL wins).
"""
import argparse
import sqlite3
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from plot_benchmark_data import planner_order  # noqa: E402

def strip_prefix(name):
    for prefix in ("geometric_", "control_"):
        if name.startswith(prefix):
            return name[len(prefix):]
    return name


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--db", required=True)
    parser.add_argument("--out", required=True)
    parser.add_argument("--problem", help="experiment name; all problems pooled when absent")
    parser.add_argument("--order", default="", help="comma-separated planner order (e.g. the ranking)")
    parser.add_argument("--title", default="")
    parser.add_argument("--metric", nargs=2, action="append", required=True, metavar=("LABEL", "COLUMNS"),
                        help="a panel: its label and database columns (comma-separated, first non-NULL wins)")
    args = parser.parse_args()
    metrics = [(label, columns.split(",")) for label, columns in args.metric]

    connection = sqlite3.connect(args.db)
    columns = {row[1] for row in connection.execute("PRAGMA table_info(runs)")}
    if "execution_time" not in columns:
        print("plot_benchmark_boxplots: no run in %s has metrics (nothing solved)" % args.db, file=sys.stderr)
        return 1
    expressions = []
    for _, candidates in metrics:
        present = [c for c in candidates if c in columns]
        expressions.append("NULL" if not present else present[0] if len(present) == 1
                           else "COALESCE(%s)" % ", ".join(present))
    query = ("SELECT plannerConfigs.name, runs.solved, runs.execution_time, %s FROM runs "
             "JOIN plannerConfigs ON runs.plannerid = plannerConfigs.id "
             "JOIN experiments ON runs.experimentid = experiments.id" % ", ".join(expressions))
    parameters = ()
    if args.problem:
        query += " WHERE experiments.name = ?"
        parameters = (args.problem,)

    runs, successes, values = {}, {}, {}
    for row in connection.execute(query, parameters):
        planner = strip_prefix(row[0])
        runs[planner] = runs.get(planner, 0) + 1
        values.setdefault(planner, [[] for _ in metrics])
        if row[1] == 1 and row[2] is not None:
            successes[planner] = successes.get(planner, 0) + 1
            for i, value in enumerate(row[3:]):
                if value is not None:
                    values[planner][i].append(value)
    if not runs:
        print("plot_benchmark_boxplots: no runs for %s" % (args.problem or "any problem"), file=sys.stderr)
        return 1

    order = planner_order(runs, args.order)
    labels = ["%s\n%d/%d" % (p, successes.get(p, 0), runs[p]) for p in order]

    columns_per_row = 3
    rows = (len(metrics) + columns_per_row - 1) // columns_per_row
    figure, axes = plt.subplots(rows, columns_per_row, figsize=(6.0 * columns_per_row, 4.2 * rows), squeeze=False)
    for index, (label, _) in enumerate(metrics):
        axis = axes[index // columns_per_row][index % columns_per_row]
        data = [values[p][index] for p in order]
        positions = [i + 1 for i, d in enumerate(data) if d]
        if positions:
            axis.boxplot([d for d in data if d], positions=positions, widths=0.6, showfliers=True)
        axis.set_xticks(range(1, len(order) + 1))
        axis.set_xticklabels(labels, rotation=60, ha="right", fontsize=7)
        axis.set_xlim(0.5, len(order) + 0.5)
        axis.set_title(label, fontsize=10)
        axis.grid(axis="y", color="lightgrey", linewidth=0.5)
    for index in range(len(metrics), rows * columns_per_row):
        axes[index // columns_per_row][index % columns_per_row].axis("off")
    title = args.title or ("problem " + args.problem if args.problem else "all problems")
    figure.suptitle(title + " — successful runs (labels: successes/runs)", fontsize=12)
    figure.tight_layout(rect=(0, 0, 1, 0.97))
    figure.savefig(args.out, dpi=110)
    return 0


if __name__ == "__main__":
    sys.exit(main())
