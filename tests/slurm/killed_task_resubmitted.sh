#!/usr/bin/env bash
# One array task of a Slurm campaign is killed with SIGKILL midway (after its first job, during its
# second); the merge step that depended on the array is never run; resubmitting that one task and
# the merge completes the campaign with every job run exactly once and nothing lost.
# Usage: killed_task_resubmitted.sh ARCPLAN_EXECUTABLE SOURCE_DIR
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
source "$here/common.sh" "$@"
slurm_test_begin

# Shard 4/4 holds jobs 4 and 8 of 8: RRTstar on both problems, each 5 runs that plan until the
# 0.5 s limit, so the task runs for several seconds with one log written halfway.
runs=5
options=(--suite "$suite" --runs $runs --time 0.5)
bench=("$source_dir/scripts/slurm/bench.sbatch" 4 "$work/campaign" "${options[@]}")
rank_step=("$source_dir/scripts/slurm/rank.sbatch" "$work/campaign" --no-plots)

array="$(submit --array=1-4 --output="$work/bench-%A_%a.out" "${bench[@]}")"
rank="$(submit --dependency=afterok:"$array" --kill-on-invalid-dep=yes --output="$work/rank-%j.out" "${rank_step[@]}")"
echo "submitted array $array and merge/rank job $rank"

# Kill task 4 once its first log exists (its first job done, the second running).
shard4="$work/campaign/shard4/logs"
deadline=$((SECONDS + 240))
while true; do
  state="$(squeue -h -j "${array}_4" -o %T 2>/dev/null || true)"
  logs=0
  [ -d "$shard4" ] && logs=$(find "$shard4" -name '*.log' | wc -l)
  if [ "$state" = RUNNING ] && [ "$logs" -ge 1 ]; then break; fi
  [ -n "$state" ] || fail "array task 4 ended before it could be killed midway ($logs logs)"
  [ $SECONDS -lt $deadline ] || fail "array task 4 did not get halfway in 240 s (state $state)"
  sleep 0.1
done
scancel --signal=KILL "${array}_4"
echo "killed array task ${array}_4 with SIGKILL after its first job"
wait_gone 300 "$array" "$rank"

tasks="$(completions "$array")"
[ "$(grep -c ' COMPLETED 0:0$' <<<"$tasks")" -eq 3 ] && ! grep -q '^4 COMPLETED' <<<"$tasks" ||
  fail "expected tasks 1-3 completed and task 4 killed: $tasks"
[ "$(find "$shard4" -name '*.log' | wc -l)" -eq 1 ] || fail "task 4 was not killed midway: $(find "$shard4" -name '*.log')"
# afterok can no longer be satisfied: Slurm cancels the merge step without running it.
grep -q '^- CANCELLED' <<<"$(completions "$rank")" || fail "the merge step was not cancelled: $(completions "$rank")"
[ ! -e "$work/rank-$rank.out" ] && [ ! -e "$work/campaign/merged" ] || fail "the merge step ran after a failed task"

# Resubmit the killed task alone, then the merge step.
again="$(submit --array=4 --output="$work/bench-%A_%a.out" "${bench[@]}")"
rank="$(submit --dependency=afterok:"$again" --output="$work/rank-%j.out" "${rank_step[@]}")"
echo "resubmitted task 4 as $again, merge/rank job $rank"
wait_gone 300 "$again" "$rank"
[ "$(completions "$again")" = "4 COMPLETED 0:0" ] || fail "the resubmitted task: $(completions "$again")"
[ "$(completions "$rank")" = "- COMPLETED 0:0" ] || fail "rank job: $(completions "$rank"); $(cat "$work/rank-$rank.out")"
grep -q "^bench: 1 job(s) run, 1 already done, of 2 in this shard" "$work/bench-${again}_4.out" ||
  fail "the resubmitted task did not resume: $(grep '^bench:' "$work/bench-${again}_4.out")"

# Nothing lost or duplicated: all 8 jobs reported finished once over the killed and the resubmitted
# tasks, 8 logs, and the merged database holds each job's runs once.
finished_lines "$work"/bench-*.out | sort >"$work/finished.txt"
[ "$(wc -l <"$work/finished.txt")" -eq 8 ] || fail "$(wc -l <"$work/finished.txt") finished jobs reported, not 8"
[ -z "$(uniq -d "$work/finished.txt")" ] || fail "jobs ran twice: $(uniq -d "$work/finished.txt")"
[ "$(find "$work/campaign" -path '*/logs/*' -name '*.log' | wc -l)" -eq 8 ] || fail "not 8 logs"
leftovers="$(find "$work/campaign" -path '*/logs/*' -type f ! -name '*.log')"
[ -z "$leftovers" ] || echo "note: the SIGKILL left temporary files (not merged): $leftovers"
merged="$work/campaign/merged/benchmark.db"
[ -f "$merged" ] || fail "the merge step did not build $merged"
per_job="$(db_rows "$merged" "SELECT e.name, p.name, count(*), count(DISTINCT run_seed) FROM runs
            JOIN experiments e ON runs.experimentid = e.id JOIN plannerConfigs p ON runs.plannerid = p.id
            GROUP BY e.name, p.name")"
[ "$(wc -l <<<"$per_job")" -eq 8 ] || fail "the merged database has $(wc -l <<<"$per_job") (problem, planner) pairs, not 8"
bad="$(awk -F'|' -v n=$runs '$3 != n || $4 != n' <<<"$per_job")"
[ -z "$bad" ] || fail "jobs without exactly $runs distinct runs: $bad"
[ -s "$work/campaign/merged/ranking.md" ] || fail "no ranking.md"
echo "PASS: task 4 killed after 1 of its 2 jobs; resubmitted, it ran the other one; 8 jobs x $runs runs, once each"
