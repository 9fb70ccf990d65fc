"""Shared by the benchmark plot scripts: the median-run data a campaign writes to paths/<suite>/<problem>/."""
import csv
import json
import os


def median_run_files(folders):
    """planner -> CSV file, over all folders (merged shards each hold the planners they ran)."""
    files = {}
    for folder in folders:
        for name in sorted(os.listdir(folder)):
            if name.endswith(".csv"):
                files.setdefault(name[:-4], os.path.join(folder, name))
    return files


def read_median_run(path):
    """Rows of t, tcp_speed, x, y, z as floats (the '#' lines above the header are comments)."""
    with open(path) as stream:
        lines = [line for line in stream if not line.startswith("#")]
    return [{key: float(value) for key, value in row.items()} for row in csv.DictReader(lines)]


def read_scene(folders):
    """scene.json: obstacles, start and goal TCP positions, vmax_mps."""
    with open(os.path.join(folders[0], "scene.json")) as stream:
        return json.load(stream)


def planner_order(planners, order_text):
    """The planners in the given comma-separated order first, the rest sorted."""
    order = [p for p in order_text.split(",") if p in planners] if order_text else []
    return order + sorted(p for p in planners if p not in order)
