#!/usr/bin/env python3
"""What the Python module adds over the C++ calls it makes (docs/python.md): Scene.is_valid on 10^5
configurations against collision::areCollisionFree on the same states, and arcplan.plan on a trivial
query against benchmarks::planQuery. The C++ side is the Google Benchmark program
arcplan_perf_python (perf/perf_python_baseline.cpp); the batch is compared by the median over repetitions
of the mean time per call, the plan calls by their fastest and median call (every call timed: on a
loaded machine the mean measures the load); rounds alternate so that the load hits both sides alike.

Run: PYTHONPATH=build/python /usr/bin/python3 perf/python_overhead.py build/python/arcplan_perf_python
"""
import argparse
import json
import pathlib
import re
import statistics
import subprocess
import time

import numpy as np

import arcplan

PERF = pathlib.Path(__file__).resolve().parent


def states(count):
    """The states of perf_python_baseline.cpp's stateColumns, row k = state k."""
    index = np.arange(6 * count, dtype=np.float64).reshape(count, 6) + 1.0
    return -np.pi + 2.0 * np.pi * np.fmod(index * 0.6180339887498949, 1.0)


def per_call(function, calls, repetitions):
    """Median over repetitions of the mean time (s) of `calls` calls."""
    means = []
    for _ in range(repetitions):
        start = time.perf_counter()
        for _ in range(calls):
            function()
        means.append((time.perf_counter() - start) / calls)
    return statistics.median(means)


def each_call(function, calls, repetitions):
    """Median over repetitions of the fastest and of the median of `calls` calls timed one by one (s),
    the statistics of the C++ program's min_us and median_us counters."""
    fastest, medians = [], []
    for _ in range(repetitions):
        times = []
        for _ in range(calls):
            start = time.perf_counter()
            function()
            times.append(time.perf_counter() - start)
        fastest.append(min(times))
        medians.append(statistics.median(times))
    return statistics.median(fastest), statistics.median(medians)


def cpp_results(program, repetitions, pattern):
    """Benchmark name -> (median real time per iteration, min_us, median_us counters) in s."""
    run = subprocess.run([program, f"--benchmark_filter={pattern}", f"--benchmark_repetitions={repetitions}",
                          "--benchmark_format=json", "--benchmark_report_aggregates_only=true"],
                         check=True, capture_output=True, text=True)
    scale = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}
    results = {}
    for b in json.loads(run.stdout)["benchmarks"]:
        if b["aggregate_name"] == "median":
            name = b["run_name"].split("/iterations:")[0]  # fixed iteration counts are part of the name
            results[name] = (b["real_time"] * scale[b["time_unit"]], b.get("min_us", 0) * 1e-6,
                             b.get("median_us", 0) * 1e-6)
    return results


def print_batch(rounds, valid):
    cpp_time, python_time = (statistics.median(r[i] for r in rounds) for i in (0, 1))
    print(f"is_valid, 10^5 states ({valid} valid): C++ {cpp_time * 1e3:.1f} ms, Python {python_time * 1e3:.1f} ms, "
          f"Python / C++ {python_time / cpp_time:.3f} (median of {len(rounds)} rounds; per round: " +
          ", ".join(f"{p / c:.3f}" for c, p in rounds) + ")")


def print_plan(name, rounds):
    cpp_min, python_min, cpp_median, python_median = (statistics.median(r[i] for r in rounds) for i in range(4))
    print(f"{name}: fastest call C++ {cpp_min * 1e6:.1f} µs, Python {python_min * 1e6:.1f} µs "
          f"({(python_min - cpp_min) * 1e6:+.1f} µs); median call C++ {cpp_median * 1e6:.1f} µs, "
          f"Python {python_median * 1e6:.1f} µs ({(python_median - cpp_median) * 1e6:+.1f} µs); per round "
          "(fastest C++, Python µs): " + ", ".join(f"({r[0] * 1e6:.1f}, {r[1] * 1e6:.1f})" for r in rounds))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("program", help="the built arcplan_perf_python")
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--repetitions", type=int, default=5)
    parser.add_argument("--filter", default=".", help="only the calls whose name matches this regular expression")
    arguments = parser.parse_args()

    thesis = arcplan.load_scene("scenes/thesis_obstacle.yaml")
    trivial = arcplan.load_scene(PERF / "python_trivial_query.yaml")
    configurations = states(100000)

    def trivial_plan(planner):
        if arcplan.plan(trivial, planner=planner).status != "exact":
            raise RuntimeError("the trivial query must be solved")

    batch = "PythonBaselineIsValidBatch"
    cases = {batch: lambda: thesis.is_valid(configurations),
             "PythonBaselinePlanTrivial/arc": lambda: trivial_plan("arc"),
             "PythonBaselinePlanTrivial/RRTConnect": lambda: trivial_plan("RRTConnect")}
    cases = {name: case for name, case in cases.items() if re.search(arguments.filter, name)}
    measured = {name: [] for name in cases}  # per round: C++ and Python times (s)
    for _ in range(arguments.rounds):
        cpp = cpp_results(arguments.program, arguments.repetitions, arguments.filter)
        for name, case in cases.items():
            if name == batch:
                measured[name].append((cpp[name][0], per_call(case, 3, arguments.repetitions)))
            else:
                fastest, median = each_call(case, 200, arguments.repetitions)
                measured[name].append((cpp[name][1], fastest, cpp[name][2], median))

    for name, rounds in measured.items():
        if name == batch:
            print_batch(rounds, thesis.is_valid(configurations).sum())
        else:
            print_plan(name, rounds)


if __name__ == "__main__":
    main()
