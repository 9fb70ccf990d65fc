"""arcplan.model on the real UR10e logs of $ARCPLAN_SHARED_DATA/ur10e_real, which are not part of the project: CTest
registers this file as python.model_real_logs only when the folder exists (else python.model_real_logs.NotRun says
so), the rule of the C++ real-log tests (docs/model.md). The files, column map and identification rows are those of
tests/model/test_real_logs.cpp; every result is compared with `arcplan model ... --json` on the same inputs."""
import os
import pathlib

import pytest

from arcplan import model
from conftest import DATA, run_cli
from json_documents import assert_same_document

REAL = pathlib.Path(os.environ["ARCPLAN_SHARED_DATA"]) / "ur10e_real"
FIT, VALIDATION = REAL / "ur-20_02_12-50sec_12harm.csv", REAL / "ur-20_01_17-ptp_10_points.csv"
BASE = DATA / "models" / "ur10e_current_base.yaml"
CLI_DATA = ["--model", BASE, "--data", FIT, "--validate", VALIDATION, "--columns", "ur10e_real", "--rows", "355-5090",
            "--validate-rows", "700-4200"]


@pytest.fixture(scope="module")
def base():
    return model.load_model(BASE)


@pytest.fixture(scope="module")
def data(base):
    return model.load_data(base, FIT, VALIDATION, columns="ur10e_real", rows="355-5090", validate_rows="700-4200")


def test_compare_overall_nrmse_equals_the_cli(base, data):
    expected = run_cli("model", "compare", *CLI_DATA)
    comparison = model.compare(base, data)
    assert abs(comparison.overall_nrmse - expected["overall_nrmse"]) <= 1e-12
    assert abs(comparison.validation.overall_nrmse - expected["validation"]["overall_nrmse"]) <= 1e-12
    # The README's rows 355-5090 are 4736 lines; the reader drops none of them there.
    assert comparison.series.measured.shape == (4736, 6)


def test_first_effect_of_the_diagnosis_equals_the_cli(base, data):
    expected = run_cli("model", "diagnose", *CLI_DATA)
    diagnosis = model.diagnose(base, data)
    first, theirs = diagnosis.ranking[0], expected["ranking"][0]
    assert (first.effect, first.joints) == (theirs["effect"], theirs["joints"])
    assert abs(first.heldout_reduction - theirs["heldout_reduction"]) <= 1e-12
    assert_same_document(diagnosis.to_dict(), expected)
    # Load-dependent friction on the shoulder and elbow, which carry the arm's weight (docs/model-results.md).
    assert first.effect == "load_friction" and first.joints == [1, 2] and first.suggested


def test_fit_with_the_first_effect_equals_the_cli_and_lowers_the_heldout_error(base, data):
    first = model.diagnose(base, data).ranking[0]
    step = model.fit(base, data, first)
    assert_same_document(step.to_dict(), run_cli("model", "fit", *CLI_DATA, "--add", str(first.entry)))
    assert step.after_validation.overall_nrmse < step.before_validation.overall_nrmse
    for joint in first.joints:
        assert step.after_validation.rmse[joint] < step.before_validation.rmse[joint]


def test_run_folders_of_the_real_ur5_equal_the_cli(tmp_path):
    # Run folders (one log_<signal>.csv per signal) of the UR5 runs, two joined as --data does, and its own URDF.
    runs = pathlib.Path(os.environ["ARCPLAN_SHARED_DATA"]) / "ur5_kufieta"
    fit = [runs / "Movement_No1", runs / "Movement_No2"]
    validation = runs / "Movement_No7_Acc_slow_Verify_Model_short"
    spec = tmp_path / "ur5.yaml"
    urdf = pathlib.Path(os.environ["ARCPLAN_SHARED_DATA"]) / "mbm_ur5" / "ur5.urdf"
    spec.write_text("kind: joint_current\nload_torque: target_moment\nrobot: {urdf: %s}\n"
                    "effects: [drive_gain, offset, coulomb, viscous]\n" % urdf)
    expected = run_cli("model", "compare", "--model", spec, "--data", *fit, "--validate", validation)
    ur5 = model.load_model(spec)
    comparison = model.compare(ur5, model.load_data(ur5, fit, validation))
    assert abs(comparison.overall_nrmse - expected["overall_nrmse"]) <= 1e-12
    assert_same_document(comparison.to_dict(), expected)
    log = model.read_log(fit[0])
    assert log.joint_count == 6 and "actual_current" in log.signals and log["actual_q"].shape == (log.rows, 6)
