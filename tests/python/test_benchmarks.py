"""arcplan.bench against `arcplan bench --json` on the same small campaign (the thesis suite's two problems, the arc
planner at h = 0.5r and RRTConnect, 2 runs of at most 0.3 s), the campaign read back against the CLI's own
ranking.json and its run records, and bad input raising arcplan.Error with arcplan's message."""
import json

import pytest

import arcplan
from arcplan import bench
from conftest import run_cli

PLANNERS = ["arc-h0.50r", "RRTConnect"]
# Metrics of the path itself: equal between two campaigns of the same seeds. The solve time is wall-clock time.
PATH_METRICS = ["tcp_path_length_m", "joint_path_length_rad", "execution_time_s", "min_clearance_m"]


@pytest.fixture(scope="module")
def campaigns(tmp_path_factory):
    folder = tmp_path_factory.mktemp("bench")
    cli_out, python_out = folder / "cli", folder / "python"
    expected = run_cli("bench", "--suite", "thesis", "--planners", ",".join(PLANNERS), "--runs", "2", "--time", "0.3",
                       "-j", "1", "--no-plots", "--quiet", "--out", cli_out)
    summary = bench.run("thesis", out=python_out, planners=PLANNERS, runs=2, time=0.3)
    return expected, summary, cli_out, python_out


def test_run_returns_the_cli_summary_and_ranking(campaigns):
    expected, summary, cli_out, python_out = campaigns
    assert summary.keys() == expected.keys()
    assert summary["out"] == str(python_out) and summary["suite"] == "thesis" and summary["shard"] == "1/1"
    assert (summary["jobs_in_campaign"], summary["jobs_run"], summary["interrupted"]) == (4, 4, False)
    ours, theirs = summary["ranking"], expected["ranking"]
    assert ours.keys() == theirs.keys()
    assert [p["name"] for p in ours["planners"]] == [p["name"] for p in theirs["planners"]]
    for mine, cli in zip(ours["planners"] + ours["problems"], theirs["planners"] + theirs["problems"]):
        assert mine.keys() == cli.keys()
    for mine, cli in zip(ours["planners"], theirs["planners"]):
        for key in ["rank", "runs", "solved", "success_rate", "mean_rank", "problems", "first_places"]:
            assert mine[key] == cli[key], key
        for metric in PATH_METRICS:
            for statistic in ["median", "mean", "min", "max", "count"]:
                assert mine[metric][statistic] == pytest.approx(cli[metric][statistic], abs=1e-9), metric


def test_read_campaign_ranking_equals_the_cli_ranking_file(campaigns):
    _, _, cli_out, _ = campaigns
    campaign = bench.read_campaign(cli_out)
    assert campaign.ranking == json.loads((cli_out / "ranking.json").read_text())
    assert bench.read_campaign(cli_out / "benchmark.db").ranking == campaign.ranking


def test_run_records_per_problem_and_planner(campaigns):
    expected, _, cli_out, _ = campaigns
    campaign = bench.read_campaign(cli_out)
    assert sorted(campaign.runs) == ["thesis/obstacle", "thesis/straight"]
    assert campaign.families == {"thesis/obstacle": "scene file", "thesis/straight": "scene file"}
    for problem, planners in campaign.runs.items():
        assert sorted(planners) == sorted(PLANNERS)
        for planner, records in planners.items():
            assert len(records) == 2
            assert campaign.settings[problem][planner]["runs"] == "2"
            for record in records:
                assert record.succeeded == (record.solved and record.value("execution_time_s") is not None)
    # Success rates counted from the records agree with the ranking's.
    for standing in expected["ranking"]["planners"]:
        records = [r for planners in campaign.runs.values() for r in planners[standing["name"]]]
        assert standing["success_rate"] == sum(r.succeeded for r in records) / len(records)


def test_run_again_resumes_the_finished_campaign(campaigns):
    _, summary, _, python_out = campaigns
    again = bench.run("thesis", out=python_out, planners=PLANNERS, runs=2, time=0.3)
    assert (again["jobs_run"], again["jobs_skipped"]) == (0, 4)
    assert again["ranking"] == summary["ranking"]


def test_bad_input_raises_arcplans_message(tmp_path):
    with pytest.raises(arcplan.Error, match=r"^--suite: 'no_such_suite' is neither a suite file nor a built-in suite"):
        bench.run("no_such_suite", out=tmp_path / "a")
    with pytest.raises(arcplan.Error, match=r"^--runs must be at least 1$"):
        bench.run("thesis", out=tmp_path / "b", runs=0)
    with pytest.raises(arcplan.Error, match=r"^--time must be a positive number of seconds$"):
        bench.run("thesis", out=tmp_path / "c", time=-1.0)
    with pytest.raises(arcplan.Error, match=r"unknown planner 'NoSuchPlanner'"):
        bench.run("thesis", out=tmp_path / "d", planners=["NoSuchPlanner"], runs=1)
    assert not (tmp_path / "d").exists()  # checked before anything is written
    with pytest.raises(arcplan.Error, match=r"not a finished campaign folder \(no benchmark.db"):
        bench.read_campaign(tmp_path)
