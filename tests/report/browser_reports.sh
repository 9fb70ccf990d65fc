#!/usr/bin/env bash
# The HTML reports in a real browser: builds a small thesis campaign (3 planners, 3 runs), its
# comparison page against an edited baseline (bench compare --html), a plain OMPL database (no
# arcplan columns) and a model session (simulated log with a hidden load-friction effect), writes
# their reports with arcplan and checks each in headless Chromium (report/web/browser_test.js).
# Expected counts come from what this script asked for.
# Usage: browser_reports.sh ARCPLAN_EXECUTABLE SOURCE_DIR
set -euo pipefail
arcplan="$1"
source_dir="$2"
web="$source_dir/report/web"
if [ ! -d "$web/node_modules/puppeteer-core" ]; then
  echo "browser_reports: $web/node_modules/puppeteer-core missing: run scripts/setup (npm ci in report/web)" >&2
  exit 1
fi
work="$(mktemp -d "${TMPDIR:-/tmp}/arcplan-report-test.XXXXXX")"
[ -n "${ARCPLAN_KEEP_TEST_FILES:-}" ] || trap 'rm -rf "$work"' EXIT
browser_test() { node "$web/browser_test.js" "$@"; }

echo "== campaign: thesis suite, 3 planners x 2 problems x 3 runs, report through bench --html"
"$arcplan" bench --suite thesis --planners arc-h0.50r,RRTConnect,PRM --runs 3 --time 0.3 -j 1 --no-plots --quiet \
  --out "$work/campaign" --html "$work/campaign/report.html" > "$work/bench.out"
grep -q "^report: $work/campaign/report.html" "$work/bench.out"
size=$(stat -c %s "$work/campaign/report.html")
echo "campaign report: $size bytes"
[ "$size" -lt 5000000 ]
browser_test --report "$work/campaign/report.html" --kind campaign --planners 3 --speed-problems 2 --arm

echo "== campaign with a gripper and every obstacle kind: a MoveIt scene (box, cylinder, sphere, mesh, a held sphere) and an STL"
# The files of tests/report/drawn_campaign (shared with test_report_scene.cpp) and arcplan's UR10e with
# the box body and cylinder finger of gripper_links.xml beyond the flange.
cp -r "$source_dir/tests/report/drawn_campaign" "$work/drawn"
bash "$source_dir/tests/report/write_drawn_moveit.sh" "$work/drawn"
{
  sed -e "s|filename=\"meshes/|filename=\"$source_dir/data/ur10e/meshes/|" -e 's|</robot>||' "$source_dir/data/ur10e/ur10e.urdf"
  cat "$work/drawn/gripper_links.xml"
  echo "</robot>"
} > "$work/drawn/gripper.urdf"
"$arcplan" bench --suite "$work/drawn/suite.yaml" -j 1 --no-plots --quiet --out "$work/drawn/campaign" \
  --html "$work/drawn/report.html" > /dev/null
# 5 obstacles (4 MoveIt shapes + the STL part), 2 of them meshes; a held sphere; 7 UR10e links + gripper + finger.
browser_test --report "$work/drawn/report.html" --kind campaign --planners 1 --speed-problems 2 --arm \
  --obstacles 5 --mesh-obstacles 2 --attached 1 --links 9 --link-names gripper,finger --endpoints

echo "== comparison page: the campaign against a baseline of itself whose arc path was 1 mm shorter"
"$arcplan" bench baseline save "$work/campaign" "$work/baseline.json" 2> /dev/null
python3 - "$work/baseline.json" <<'PY'
import json, sys
baseline = json.load(open(sys.argv[1]))
for result in baseline["results"]:
    if result["planner"] == "arc-h0.50r" and result["problem"] == "thesis/obstacle":
        result["metrics"]["tcp_path_length_m"]["value"] -= 0.001
json.dump(baseline, open(sys.argv[1], "w"))
PY
status=0
"$arcplan" bench compare "$work/baseline.json" "$work/campaign" --html "$work/comparison.html" > /dev/null 2>&1 || status=$?
[ "$status" -eq 1 ]  # the 1 mm is worse
# 3 planners x 2 problems x (success rate + 5 metrics) rows; 5 metrics compared, one box plot each.
browser_test --report "$work/comparison.html" --kind comparison --rows 36 --worse 1 --metrics 5

echo "== plain OMPL database: no arcplan columns, no path data"
mkdir -p "$work/plain"
sqlite3 "$work/plain/benchmark.db" <<'SQL'
CREATE TABLE experiments (id INTEGER PRIMARY KEY, name VARCHAR(512), totaltime REAL, timelimit REAL, version VARCHAR(128));
CREATE TABLE plannerConfigs (id INTEGER PRIMARY KEY, name VARCHAR(512), settings TEXT);
CREATE TABLE runs (id INTEGER PRIMARY KEY, experimentid INTEGER, plannerid INTEGER, time REAL, memory REAL, solved BOOLEAN,
                   solution_length REAL);
INSERT INTO experiments VALUES (1, 'kitchen', 10, 1, 'OMPL 1.5.2');
INSERT INTO plannerConfigs VALUES (1, 'geometric_RRT', ''), (2, 'geometric_PRM', '');
INSERT INTO runs VALUES (1, 1, 1, 0.5, 10, 1, 3.0), (2, 1, 1, 1.0, 11, 0, NULL), (3, 1, 2, 0.2, 12, 1, 2.5);
SQL
"$arcplan" report "$work/plain" > "$work/plain.out"
grep -q "report note: .*no arcplan columns" "$work/plain.out"
grep -q "report note: No path data" "$work/plain.out"
browser_test --report "$work/plain/report.html" --kind campaign --planners 2 --speed-problems 0

echo "== model session: simulated logs with a hidden load-friction effect"
cat > "$work/base.yaml" <<'YAML'
kind: joint_current
load_torque: target_moment
effects: [drive_gain, offset, coulomb, viscous]
YAML
sed 's/viscous]/viscous, load_friction]/' "$work/base.yaml" > "$work/truth.yaml"
"$arcplan" model simulate --model "$work/truth.yaml" --data "$work/fit.csv" --validate "$work/val.csv" \
  --duration 12 --rate 200 --seed 4 > /dev/null
"$arcplan" model compare --model "$work/base.yaml" --data "$work/fit.csv" --validate "$work/val.csv" --out "$work/session" > /dev/null
"$arcplan" model diagnose --model "$work/base.yaml" --data "$work/fit.csv" --validate "$work/val.csv" --out "$work/session" \
  --json "$work/diagnose.json" --html "$work/session/report.html" > /dev/null
candidates=$(python3 -c 'import json,sys; print(len(json.load(open(sys.argv[1]))["ranking"]))' "$work/diagnose.json")
browser_test --report "$work/session/report.html" --kind model --channels 6 --history-traces 2 \
  --diagnosis-rows "$candidates" --model-line load_friction
