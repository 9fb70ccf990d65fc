#!/usr/bin/python3
"""Measured vs predicted per channel, and the residual against each signal, from a model series CSV.

The CSV (written by `arcplan model compare|fit --out DIR`) has one row per sample and channel:
channel,index,time,measured,predicted,base,q,qd,qdd,tau,temperature (empty cells where a signal is absent).

    plot_model_compare.py SERIES.csv OUT_PREFIX
        -> OUT_PREFIX_measured_vs_predicted.png, OUT_PREFIX_residual_vs_signals.png
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

SIGNALS = [("q", "joint angle q [rad]"), ("qd", "speed qd [rad/s]"), ("qdd", "acceleration qdd [rad/s²]"),
           ("tau", "load torque [N·m]"), ("temperature", "temperature [°C]")]
MAX_POINTS = 4000  # per channel in scatter plots


def read_series(path):
    channels = {}
    with open(path, newline="") as handle:
        for row in csv.DictReader(handle):
            data = channels.setdefault(row["channel"], {key: [] for key in row if key != "channel"})
            for key, value in row.items():
                if key != "channel":
                    data[key].append(float(value) if value != "" else None)
    return channels


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    channels = read_series(sys.argv[1])
    prefix = sys.argv[2]
    names = list(channels)
    timed = any(t is not None and t != i for t, i in zip(channels[names[0]]["time"], channels[names[0]]["index"]))

    fig, axes = plt.subplots(len(names), 1, figsize=(11, 2.2 * len(names)), sharex=timed, squeeze=False)
    for ax, name in zip(axes[:, 0], names):
        data = channels[name]
        x = data["time"] if timed else data["tau"]
        order = sorted(range(len(x)), key=lambda i: x[i])
        style = "-" if timed else "o"
        ax.plot([x[i] for i in order], [data["measured"][i] for i in order], style, lw=0.8, ms=3, label="measured")
        ax.plot([x[i] for i in order], [data["predicted"][i] for i in order], style, lw=0.8, ms=3, label="predicted",
                alpha=0.8)
        residual = [m - p for m, p in zip(data["measured"], data["predicted"])]
        rmse = (sum(r * r for r in residual) / len(residual)) ** 0.5
        ax.set_ylabel(name, fontsize=8)
        ax.set_title(f"{name}: RMSE {rmse:.4g}", fontsize=9, loc="left")
        ax.grid(alpha=0.3)
    axes[0, 0].legend(loc="upper right", fontsize=8)
    axes[-1, 0].set_xlabel("time [s]" if timed else "output torque [N·m]")
    fig.tight_layout()
    fig.savefig(prefix + "_measured_vs_predicted.png", dpi=110)
    plt.close(fig)

    present = [(key, label) for key, label in SIGNALS
               if any(v is not None for v in channels[names[0]].get(key, []))]
    fig, axes = plt.subplots(len(names), len(present), figsize=(3.0 * len(present), 2.1 * len(names)), squeeze=False)
    for row, name in enumerate(names):
        data = channels[name]
        residual = [m - p for m, p in zip(data["measured"], data["predicted"])]
        step = max(1, len(residual) // MAX_POINTS)
        for col, (key, label) in enumerate(present):
            ax = axes[row, col]
            ax.plot(data[key][::step], residual[::step], ".", ms=1.5, alpha=0.5)
            ax.axhline(0.0, color="k", lw=0.6)
            ax.grid(alpha=0.3)
            if row == len(names) - 1:
                ax.set_xlabel(label, fontsize=8)
            if col == 0:
                ax.set_ylabel(f"residual\n{name}", fontsize=7)
            ax.tick_params(labelsize=7)
    fig.suptitle("residual (measured - predicted) against each signal", fontsize=10)
    fig.tight_layout()
    fig.savefig(prefix + "_residual_vs_signals.png", dpi=100)
    plt.close(fig)


if __name__ == "__main__":
    main()
