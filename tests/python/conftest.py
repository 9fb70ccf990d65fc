"""Shared helpers of the Python tests: the built `arcplan` binary (ARCPLAN_EXECUTABLE, set by CTest)
run with --json, and the data folders."""
import json
import os
import pathlib
import subprocess
import tempfile
import threading
import time

import pytest

REPO = pathlib.Path(__file__).resolve().parents[2]
DATA = REPO / "data"
THESIS_SCENE = DATA / "scenes" / "thesis_obstacle.yaml"


def run_cli(*arguments):
    """Runs `arcplan ARGUMENTS --json FILE` and returns the parsed JSON document."""
    executable = os.environ.get("ARCPLAN_EXECUTABLE")
    if not executable:
        raise RuntimeError("ARCPLAN_EXECUTABLE is not set (CTest sets it to the built arcplan binary)")
    with tempfile.TemporaryDirectory() as folder:
        output = pathlib.Path(folder) / "result.json"
        subprocess.run([executable, *map(str, arguments), "--json", str(output)], check=True,
                       stdout=subprocess.DEVNULL)
        return json.loads(output.read_text())


@pytest.fixture(scope="session")
def cli():
    return run_cli


def main_thread_ran_during(call):
    """Runs call() in a thread and tells whether this thread ran Python before call() returned. While a
    call holds the GIL no other Python runs until it returns; a call that releases it lets this thread
    take its timestamp (after a short sleep that hands the GIL to the worker) long before the return."""
    started, when = threading.Event(), {}

    def work():
        started.set()
        call()
        when["returned"] = time.perf_counter()

    worker = threading.Thread(target=work)
    worker.start()
    started.wait()
    time.sleep(0.02)
    when["main"] = time.perf_counter()
    worker.join()
    return when["main"] < when["returned"]

