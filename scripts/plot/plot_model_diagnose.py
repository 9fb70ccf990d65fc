#!/usr/bin/python3
"""Held-out error reduction of every candidate effect, from `arcplan model diagnose` JSON.

    plot_model_diagnose.py DIAGNOSIS.json OUT.png
Suggested effects (significant on at least one channel) are drawn in colour, the others in grey.
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
        diagnosis = json.load(handle)
    ranking = diagnosis["ranking"]
    if not ranking:
        ranking = [{"effect": "(no candidate)", "heldout_reduction": 0.0, "suggested": False, "joints": []}]
    labels = [f'{r["effect"]}' + (f' (joints {",".join(str(j) for j in r["joints"])})' if r["suggested"] else "")
              for r in ranking]
    values = [100.0 * r["heldout_reduction"] for r in ranking]
    colors = ["tab:green" if r["suggested"] else "lightgray" for r in ranking]
    fig, ax = plt.subplots(figsize=(8, 0.4 * len(ranking) + 1.6))
    ax.barh(range(len(ranking)), values, color=colors)
    ax.set_yticks(range(len(ranking)))
    ax.set_yticklabels(labels, fontsize=8)
    ax.invert_yaxis()
    ax.axvline(0.0, color="k", lw=0.6)
    ax.set_xlabel("held-out residual RMS removed [%]")
    ax.set_title(f'diagnosis on {diagnosis["heldout"]}', fontsize=9)
    ax.grid(axis="x", alpha=0.3)
    fig.tight_layout()
    fig.savefig(sys.argv[2], dpi=110)


if __name__ == "__main__":
    main()
