"""The model loop on the real UR10e logs — compare the base model with a measured log, diagnose what it misses, add
the proposed effects one at a time, plot the falling held-out error; notebook-style, one cell per step.
Run: PYTHONPATH=build/python python3 examples/python/model_loop.py error.png
The logs are read from $ARCPLAN_SHARED_DATA/ur10e_real (default: ../shared/data next to the repository)."""
import os
import pathlib
import sys

import matplotlib

matplotlib.use("Agg")  # no display needed; the figure goes to a file
import matplotlib.pyplot as plt

from arcplan import model

REPO = pathlib.Path(__file__).resolve().parents[2]
LOGS = pathlib.Path(os.environ.get("ARCPLAN_SHARED_DATA", REPO.parent / "shared" / "data")) / "ur10e_real"

# %% The base model (current = torque / gain + offset + Coulomb + viscous friction) and the logs: fitted on a
# Fourier excitation, validated on a point-to-point run, on the rows where the robot moves (the logs' README).
spec = model.load_model(REPO / "data" / "models" / "ur10e_current_base.yaml")
data = model.load_data(spec, LOGS / "ur-20_02_12-50sec_12harm.csv", LOGS / "ur-20_01_17-ptp_10_points.csv",
                       columns="ur10e_real", rows="355-5090", validate_rows="700-4200")
print(data.quality)

# %% Compare: errors per joint on both logs, and where the model fails.
comparison = model.compare(spec, data)
print(comparison.validation)
history = model.History()
history.add(comparison)

# %% Diagnose and fit: add the effect the diagnosis ranks first, until none is suggested (at most three rounds).
steps, proposed = [], []
for _ in range(3):
    diagnosis = model.diagnose(spec, data)
    if not diagnosis.ranking or not diagnosis.ranking[0].suggested:
        break
    first = diagnosis.ranking[0]
    print(f"{first.entry}: removes {100 * first.heldout_reduction:.1f} % of the held-out residual. {first.explanation}")
    step = model.fit(spec, data, first)
    print(f"validation NRMSE {step.before_validation.overall_nrmse:.4f} -> {step.after_validation.overall_nrmse:.4f}")
    steps.append(step)
    proposed.append(first)
    history.add(step)
    spec = step.model
print(history)

# %% The falling error (validation NRMSE after every step) and one joint's held-out residual before and after.
figure, (errors, residual) = plt.subplots(1, 2, figsize=(11, 4))
labels = [s.command.replace("fit +", "+") for s in history.steps]
errors.plot(labels, history.validation_overall_nrmse, "o-", label="validation")
errors.plot(labels, history.overall_nrmse, "s--", label="fit data")
errors.set(ylabel="overall NRMSE", title="error after every step")
errors.tick_params(axis="x", labelrotation=20)
errors.legend()
joint = proposed[0].joints[0]
before, after = comparison.validation_series, steps[-1].after_fitted.series(validation=True)
residual.plot(before.time, before.residual[:, joint], linewidth=0.6, label="base model")
residual.plot(after.time, after.residual[:, joint], linewidth=0.6, label="+ " + ", ".join(s.added[0] for s in steps))
residual.set(xlabel="time (s)", ylabel="residual (A)", title=f"held-out residual, joint {joint}")
residual.legend(loc="upper right", fontsize=8)
figure.tight_layout()
figure.savefig(sys.argv[1] if len(sys.argv) > 1 else "model_loop.png", dpi=80)

# Every added effect lowered the held-out error, as the diagnosis predicted.
assert steps and all(s.after_validation.overall_nrmse < s.before_validation.overall_nrmse for s in steps)
