#!/usr/bin/python3
"""Force-transfer diagrams like the seed thesis' figures 2.12-2.14: input torque against output torque
per gearbox, DIRECT (red) and INDIRECT (blue) measurements, the model's lines and the ideal ratio.

    plot_model_ftd.py SERIES.csv MODEL_CURVES.csv OUT.png
(both CSVs as written by `arcplan model compare --out DIR` for kind gearbox_ftd; channels "<gearbox>/<direction>")
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read(path):
    rows = {}
    with open(path, newline="") as handle:
        for row in csv.DictReader(handle):
            rows.setdefault(row["channel"], []).append(row)
    return rows


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    measured, curves = read(sys.argv[1]), read(sys.argv[2])
    gearboxes = []
    for name in measured:
        gearbox = name.rsplit("/", 1)[0]
        if gearbox not in gearboxes:
            gearboxes.append(gearbox)
    fig, axes = plt.subplots(1, len(gearboxes), figsize=(5.2 * len(gearboxes), 4.6), squeeze=False)
    for ax, gearbox in zip(axes[0], gearboxes):
        for direction, color in (("direct", "tab:red"), ("indirect", "tab:blue")):
            name = f"{gearbox}/{direction}"
            if name not in measured:
                continue
            points = measured[name]
            ax.plot([float(p["tau"]) for p in points], [float(p["measured"]) for p in points], "o", ms=4,
                    color=color, alpha=0.7, label=f"{direction.upper()} measured")
            curve = sorted(curves.get(name, []), key=lambda p: float(p["tau"]))
            ax.plot([float(p["tau"]) for p in curve], [float(p["predicted"]) for p in curve], "-", color=color,
                    label=f"{direction.upper()} model")
        ideal = sorted(curves.get(f"{gearbox}/direct", curves.get(f"{gearbox}/indirect", [])), key=lambda p: float(p["tau"]))
        ax.plot([float(p["tau"]) for p in ideal], [float(p["base"]) for p in ideal], "k--", lw=1, label="ideal ratio")
        ax.set_title(gearbox, fontsize=10)
        ax.set_xlabel("output torque [N·m]")
        ax.set_ylabel("input torque [N·m]")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(sys.argv[3], dpi=110)


if __name__ == "__main__":
    main()
