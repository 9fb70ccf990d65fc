#!/usr/bin/env bash
# A campaign as a Slurm array (scripts/slurm/bench.sbatch, 4 shards) and its merge/rank step as a
# job with --dependency=afterok (scripts/slurm/rank.sbatch), on the local single-node cluster. The
# merged result must equal an unsharded run of the same campaign made without Slurm.
# Usage: array_campaign.sh ARCPLAN_EXECUTABLE SOURCE_DIR
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
source "$here/common.sh" "$@"
slurm_test_begin

options=(--suite "$suite" --runs 3 --time 0.3)
jobs=8  # 2 problems x 4 planners

# The independent reference: the same campaign, unsharded, without Slurm.
"$arcplan" bench "${options[@]}" -j 2 --no-plots --out "$work/reference" >"$work/reference.out" 2>"$work/reference.err" ||
  fail "the unsharded reference run failed: $(tail -n 3 "$work/reference.err")"

array="$(submit --array=1-4 --output="$work/bench-%A_%a.out" "$source_dir/scripts/slurm/bench.sbatch" 4 "$work/campaign" "${options[@]}")"
rank="$(submit --dependency=afterok:"$array" --output="$work/rank-%j.out" "$source_dir/scripts/slurm/rank.sbatch" "$work/campaign" --no-plots)"
echo "submitted array $array (4 tasks) and merge/rank job $rank"
wait_gone 300 "$array" "$rank"

# Slurm: each array task ran once and succeeded, then the rank job, which started after them.
tasks="$(completions "$array")"
[ "$tasks" = "$(printf '%s COMPLETED 0:0\n' 1 2 3 4)" ] || fail "array tasks did not each complete once: $tasks"
[ "$(completions "$rank")" = "- COMPLETED 0:0" ] || fail "rank job: $(completions "$rank"); $(cat "$work"/rank-*.out)"
last_task_end="$(jobcomp "$array" EndTime | sort | tail -n 1)"
rank_start="$(jobcomp "$rank" StartTime)"
[ -n "$last_task_end" ] && [ -n "$rank_start" ] && [[ ! "$rank_start" < "$last_task_end" ]] ||
  fail "the afterok rank job started at $rank_start, before the last array task ended at $last_task_end"
for task in 1 2 3 4; do
  out="$work/bench-${array}_$task.out"
  [ -f "$out" ] || fail "array task $task left no output"
  grep -q "shard $task/4" "$out" || fail "task $task did not run shard $task/4: $(head -n 3 "$out")"
  grep -q "^bench: 2 job(s) run, 0 already done, of 2 in this shard" "$out" ||
    fail "task $task did not run its 2 jobs: $(grep '^bench:' "$out")"
done

# Every campaign job ran exactly once: the finished-job lines of all tasks are the reference's, once each.
finished_lines "$work"/bench-*.out | sort >"$work/array-jobs.txt"
finished_lines "$work/reference.err" | sort >"$work/reference-jobs.txt"
[ "$(wc -l <"$work/reference-jobs.txt")" -eq $jobs ] || fail "the reference did not report $jobs jobs"
[ -z "$(uniq -d "$work/array-jobs.txt")" ] || fail "jobs ran twice: $(uniq -d "$work/array-jobs.txt")"
diff "$work/reference-jobs.txt" "$work/array-jobs.txt" >&2 || fail "the array ran other jobs than the reference"
(cd "$work/reference" && find logs -name '*.log' | sort) >"$work/reference-logs.txt"
(cd "$work/campaign" && find shard*/logs -name '*.log' | sed 's|^shard[0-9]*/||' | sort) >"$work/array-logs.txt"
[ "$(wc -l <"$work/reference-logs.txt")" -eq $jobs ] || fail "the reference wrote $(wc -l <"$work/reference-logs.txt") logs"
diff "$work/reference-logs.txt" "$work/array-logs.txt" >&2 || fail "the shards' logs differ from the reference's"

# The merged database equals the reference's: experiments, runs per (problem, planner), the seed of
# every run, and every value that does not depend on timing for the seed-deterministic planners.
merged="$work/campaign/merged/benchmark.db"
reference="$work/reference/benchmark.db"
[ -f "$merged" ] || fail "the rank job did not build $merged"
[ -f "$reference" ] || fail "the reference run did not build $reference"
same() {  # same WHAT SQL
  local a b
  a="$(db_rows "$reference" "$2")"
  b="$(db_rows "$merged" "$2")"
  [ -n "$a" ] || fail "$1: the reference has no rows"
  [ "$a" = "$b" ] || fail "$1 differ: reference [$a] merged [$b]"
}
runs_of="FROM runs JOIN experiments e ON runs.experimentid = e.id JOIN plannerConfigs p ON runs.plannerid = p.id"
same "experiment count" "SELECT count(DISTINCT name) FROM experiments"
same "run count" "SELECT count(*) FROM runs"
[ "$(db_rows "$merged" "SELECT count(*) FROM runs")" -eq $((jobs * 3)) ] || fail "the merged database does not hold $((jobs * 3)) runs"
same "runs per problem and planner" "SELECT e.name, p.name, count(*) $runs_of GROUP BY e.name, p.name ORDER BY e.name, p.name"
same "run seeds" "SELECT e.name, p.name, run_seed $runs_of ORDER BY e.name, p.name, run_seed"
deterministic="p.name LIKE '%arc-h0.50r%' OR p.name LIKE '%RRTConnect%'"
same "arc planner and RRTConnect runs" \
  "SELECT e.name, p.name, run_seed, solved, round(tcp_path_length, 9), round(solution_length, 9),
          round(execution_time, 9), round(min_clearance, 9) $runs_of WHERE $deterministic ORDER BY e.name, p.name, run_seed"
[ "$(db_rows "$merged" "SELECT count(*) $runs_of WHERE ($deterministic) AND solved = 1")" -gt 0 ] ||
  fail "no deterministic planner solved a run: nothing was compared"

# The ranking files of the merge step.
for file in ranking.md ranking.json ranking.csv; do
  [ -s "$work/campaign/merged/$file" ] || fail "the rank job did not write $file"
done
grep -q "arc-h0.50r" "$work/campaign/merged/ranking.md" || fail "ranking.md does not rank the arc planner"
echo "PASS: 4 array tasks + afterok merge/rank: $jobs jobs once each, merged database equals the unsharded run"
