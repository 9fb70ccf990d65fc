"""arcplan.model against `arcplan model ... --json` on the same simulated UR10e logs (written by the CLI's own
seeded simulator with load friction the base model lacks), against NumPy recomputations of its errors, logs built
from arrays, and bad input: every error is arcplan.Error with arcplan's message, never a crash."""

import numpy as np
import pytest

import arcplan
from arcplan import model
from conftest import DATA, main_thread_ran_during, run_cli
from json_documents import assert_same_document

BASE = DATA / "models" / "ur10e_current_base.yaml"
TRUTH = "kind: joint_current\nload_torque: target_moment\neffects: [drive_gain, offset, coulomb, viscous, load_friction]\n"


@pytest.fixture(scope="module")
def logs(tmp_path_factory):
    folder = tmp_path_factory.mktemp("model")
    truth = folder / "truth.yaml"
    truth.write_text(TRUTH)
    fit, validation = folder / "fit.csv", folder / "validation.csv"
    run_cli("model", "simulate", "--model", truth, "--data", fit, "--validate", validation, "--duration", "20",
            "--rate", "100", "--seed", "3")
    return folder, str(fit), str(validation)


@pytest.fixture(scope="module")
def base():
    return model.load_model(BASE)


@pytest.fixture(scope="module")
def data(base, logs):
    return model.load_data(base, logs[1], logs[2])


def test_compare_equals_cli(base, data, logs):
    expected = run_cli("model", "compare", "--model", BASE, "--data", logs[1], "--validate", logs[2])
    comparison = model.compare(base, data)
    assert abs(comparison.overall_nrmse - expected["overall_nrmse"]) <= 1e-12
    assert abs(comparison.validation.overall_nrmse - expected["validation"]["overall_nrmse"]) <= 1e-12
    assert_same_document(comparison.to_dict(), expected)


def test_series_arrays_and_errors_recomputed_with_numpy(base, data):
    comparison = model.compare(base, data)
    series = comparison.series
    rows = data.samples
    assert rows == 2001 and series.channels == [f"actual_current_{j}" for j in range(6)]
    assert series.time.shape == (rows,) and series.time.dtype == np.float64
    for array in (series.measured, series.predicted, series.residual):
        assert array.shape == (rows, 6) and array.dtype == np.float64
    np.testing.assert_array_equal(series.residual, series.measured - series.predicted)
    # RMSE, NRMSE = RMSE / std of the measured channel, R^2, and the overall NRMSE (docs/model.md).
    rmse = np.sqrt(np.mean(series.residual**2, axis=0))
    nrmse = rmse / np.std(series.measured, axis=0)
    r2 = 1 - np.sum(series.residual**2, axis=0) / np.sum((series.measured - series.measured.mean(axis=0)) ** 2, axis=0)
    np.testing.assert_allclose(comparison.data.rmse, rmse, rtol=1e-10)
    np.testing.assert_allclose(comparison.data.nrmse, nrmse, rtol=1e-10)
    np.testing.assert_allclose(comparison.data.r2, r2, rtol=1e-10)
    assert comparison.overall_nrmse == pytest.approx(np.sqrt(np.mean(nrmse**2)), rel=1e-10)
    assert comparison.validation_series.measured.shape == (data.validation_samples, 6)


def test_log_from_arrays_gives_the_files_result(base, data, logs):
    def from_arrays(file):
        log = model.read_log(file)
        assert log.time.shape == (2001,) and log["actual_q"].shape == (2001, 6) and log.time.dtype == np.float64
        return model.log_from_arrays(log.time, {name: log[name] for name in log.signals}, source=file)

    arrays = model.load_data(base, from_arrays(logs[1]), from_arrays(logs[2]))
    assert_same_document(model.compare(base, arrays).to_dict(), model.compare(base, data).to_dict())


def test_diagnose_and_fit_equal_cli(base, data, logs):
    expected = run_cli("model", "diagnose", "--model", BASE, "--data", logs[1], "--validate", logs[2])
    diagnosis = model.diagnose(base, data)
    assert_same_document(diagnosis.to_dict(), expected)
    first = diagnosis.ranking[0]
    assert first.effect == "load_friction" and first.suggested  # the effect the simulation put in
    assert first.channel_reduction.shape == (6,) and first.channel_reduction.dtype == np.float64
    step = model.fit(base, data, first)
    fitted = run_cli("model", "fit", "--model", BASE, "--data", logs[1], "--validate", logs[2], "--add", str(first.entry))
    assert_same_document(step.to_dict(), fitted)
    assert step.after_validation.overall_nrmse < step.before_validation.overall_nrmse
    for joint in first.joints:
        assert step.after_validation.rmse[joint] < step.before_validation.rmse[joint]
    assert step.model.has_effect("load_friction")


def test_history_in_memory_and_in_the_session_folder(base, data, tmp_path):
    comparison = model.compare(base, data, session=tmp_path)
    step = model.fit(base, data, ["load_friction"], session=tmp_path)
    history = model.History()
    history.add(comparison)
    history.add(step)
    recorded = model.read_history(tmp_path)
    assert recorded.to_dict() == history.to_dict() and len(recorded) == 2
    assert [s.command for s in recorded.steps] == ["compare", "fit +load_friction"]
    np.testing.assert_array_equal(recorded.overall_nrmse, [comparison.overall_nrmse, step.after.overall_nrmse])
    np.testing.assert_array_equal(recorded.validation_overall_nrmse,
                                  [comparison.validation.overall_nrmse, step.after_validation.overall_nrmse])


def arrays(rows=20):
    time = np.arange(rows) * 0.01
    q = np.tile(np.linspace(0, 1, rows)[:, None], (1, 6))
    return time, {"actual_q": q, "actual_current": np.cos(q), "target_moment": np.sin(q)}


def with_signal(name, values):
    time, signals = arrays()
    signals[name] = values
    return time, signals


@pytest.mark.parametrize(
    "time, signals, message",
    [
        (np.zeros((20, 2)), arrays()[1], r"^arrays: time: expected one column \(rows,\), got 2$"),
        (*with_signal("actual_q", np.zeros((19, 6))), r"^arrays: actual_q: 19 rows, but the time has 20$"),
        (*with_signal("actual_q", np.zeros((20, 6, 1))), r"^arrays: actual_q: expected an array of shape"),
        (*with_signal("actual_current", np.zeros((20, 5))), r"mismatched joint count: actual_current has 5 columns"),
        (*with_signal("actual_current", np.where(np.eye(20, 6, -3) > 0, np.nan, 1.0)),
         r"^arrays: actual_current: row 3, column 0 is NaN$"),
        (*with_signal("actual_q", np.full((20, 6), np.inf)), r"^arrays: actual_q: row 0, column 0 is infinite$"),
        (*with_signal("speed", np.zeros(20)), r"^arrays: unknown signal 'speed' \(known: target_q, "),
        (np.r_[0.0, 0.02, 0.01, np.arange(3, 20) * 0.01], arrays()[1], r"^arrays: time: row 2 \(0.010000 s\) does not"),
        (*with_signal("actual_q", [["a"] * 6] * 20), r"^arrays: actual_q: expected an array of numbers$"),
    ],
)
def test_bad_arrays_raise_arcplans_message(time, signals, message):
    with pytest.raises(arcplan.Error, match=message):
        model.log_from_arrays(time, signals)


def test_bad_input_raises_arcplans_message(base, data, logs, tmp_path):
    with pytest.raises(arcplan.Error, match=r"no_such\.csv"):
        model.read_log(tmp_path / "no_such.csv")
    with pytest.raises(arcplan.Error, match=r"^rows: expected a 1-based line range FIRST-LAST or FIRST-, got 'abc'$"):
        model.load_data(base, logs[1], rows="abc")
    with pytest.raises(arcplan.Error, match=r"unknown effect 'no_such_effect'"):
        model.fit(base, data, "no_such_effect")
    with pytest.raises(arcplan.Error, match=r"effect 'coulomb' is already in the model"):
        model.fit(base, data, ["coulomb"])
    with pytest.raises(arcplan.Error, match=r"^series\(validation=True\): the data has no validation log$"):
        model.compare(base, model.load_data(base, logs[1])).fitted.series(validation=True)
    with pytest.raises(arcplan.Error, match=r"^m\.yaml:1:1: model: unknown key 'kindd'"):
        model.parse_model("kindd: joint_current\n", "m.yaml")
    tracking = model.parse_model("kind: joint_tracking\neffects: [offset]\n", "tracking.yaml")
    with pytest.raises(arcplan.Error, match=r"^tracking\.yaml: the data was prepared for a model with other settings"):
        model.compare(tracking, data)
    # A log built from arrays without the signals a current model needs names what is missing.
    time, signals = arrays()
    del signals["actual_current"]
    with pytest.raises(arcplan.Error, match=r"actual_current"):
        model.load_data(base, model.log_from_arrays(time, signals))


def test_diagnose_releases_the_gil(base, data):
    # The diagnosis takes seconds: this thread runs meanwhile only if the GIL is free.
    assert main_thread_ran_during(lambda: model.diagnose(base, data))


def test_no_data_is_a_type_error_not_a_crash(base):
    for call in (lambda: model.compare(base, None), lambda: model.diagnose(base, None),
                 lambda: model.fit(base, None, "coulomb")):
        with pytest.raises(TypeError):
            call()
