#!/usr/bin/python3
"""The falling-error chart of a model session: overall NRMSE (train and validation) and the RMSE of every
channel after each step, from the session file `arcplan model compare|fit --out DIR` keeps (DIR/session.json).

    plot_model_history.py SESSION.json OUT.png
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
        steps = json.load(handle)["steps"]
    if not steps:
        sys.exit("no steps in " + sys.argv[1])
    x = list(range(1, len(steps) + 1))
    labels = [s["command"] for s in steps]
    fig, (left, right) = plt.subplots(1, 2, figsize=(12, 4.2))
    left.plot(x, [s["train"]["overall_nrmse"] for s in steps], "o-", label="train")
    if all("validation" in s for s in steps):
        left.plot(x, [s["validation"]["overall_nrmse"] for s in steps], "s-", label="validation (held out)")
    left.set_ylabel("overall NRMSE (mean over channels of RMSE / spread)")
    # The pooled RMSE in the channels' unit (A, rad or N·m) weights the channels by their size.
    pooled = left.twinx()
    key_all = "validation" if all("validation" in s for s in steps) else "train"
    pooled.plot(x, [(sum(c["rmse"] ** 2 for c in s[key_all]["channels"].values()) / len(s[key_all]["channels"])) ** 0.5
                    for s in steps], "^--", color="tab:green", label=f"pooled RMSE ({key_all})")
    pooled.set_ylabel("pooled RMSE [channel unit]")
    lines = left.get_legend_handles_labels()
    extra = pooled.get_legend_handles_labels()
    left.legend(lines[0] + extra[0], lines[1] + extra[1], fontsize=8)
    key = "validation" if all("validation" in s for s in steps) else "train"
    for channel in steps[-1][key]["channels"]:
        right.plot(x, [s[key]["channels"][channel]["rmse"] for s in steps], "o-", ms=3, label=channel)
    right.set_ylabel(f"RMSE per channel ({key})")
    right.legend(fontsize=7)
    for ax in (left, right):
        ax.set_xticks(x)
        ax.set_xticklabels(labels, rotation=25, ha="right", fontsize=7)
        ax.grid(alpha=0.3)
    fig.suptitle("model error after each step", fontsize=10)
    fig.tight_layout()
    fig.savefig(sys.argv[2], dpi=110)


if __name__ == "__main__":
    main()
