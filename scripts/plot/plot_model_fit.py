#!/usr/bin/python3
"""RMSE per channel before and after `arcplan model fit --add ...`, on training and validation data.

    plot_model_fit.py FIT.json OUT.png
"""
import json
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    with open(sys.argv[1]) as handle:
        step = json.load(handle)
    sets = [s for s in ("train", "validation") if s in step["before"]]
    fig, axes = plt.subplots(1, len(sets), figsize=(6 * len(sets), 3.8), squeeze=False)
    for ax, name in zip(axes[0], sets):
        channels = list(step["before"][name]["channels"])
        before = [step["before"][name]["channels"][c]["rmse"] for c in channels]
        after = [step["after"][name]["channels"][c]["rmse"] for c in channels]
        x = range(len(channels))
        ax.bar([i - 0.2 for i in x], before, width=0.4, label="before", color="tab:gray")
        ax.bar([i + 0.2 for i in x], after, width=0.4, label="after", color="tab:green")
        ax.set_xticks(list(x))
        ax.set_xticklabels(channels, rotation=30, ha="right", fontsize=7)
        ax.set_ylabel("RMSE")
        ax.set_title(f'{name}: overall NRMSE {step["before"][name]["overall_nrmse"]:.4f} -> '
                     f'{step["after"][name]["overall_nrmse"]:.4f}', fontsize=9)
        ax.grid(axis="y", alpha=0.3)
        ax.legend(fontsize=8)
    fig.suptitle("added: " + ", ".join(step["added"]), fontsize=10)
    fig.tight_layout()
    fig.savefig(sys.argv[2], dpi=110)


if __name__ == "__main__":
    main()
