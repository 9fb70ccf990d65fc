#!/usr/bin/env bash
# Samples the memory of the worker processes of a running `arcplan bench` campaign from outside, to
# show whether a worker grows from job to job (a leak per job would make the late jobs' workers
# bigger than the early ones'). Every INTERVAL seconds it writes one line per worker: seconds since
# the start, jobs finished so far (job logs under OUT/logs), the worker's pid, VmRSS and VmHWM (its
# peak) in kB. At the end it prints each worker's RSS at the first sample after 10 % of the jobs and
# at the last sample, and the campaign's exit status.
set -euo pipefail

usage() {
  cat <<'EOF'
Usage: tools/measure_worker_memory.sh [-i INTERVAL] SAMPLES.tsv OUT -- COMMAND...

Runs COMMAND (an `arcplan bench ... --out OUT` campaign, directly or through `nice`, which execs it)
and samples its child processes' VmRSS and
VmHWM every INTERVAL seconds (default 1) into SAMPLES.tsv, with the number of finished jobs.
Example:
  tools/measure_worker_memory.sh /tmp/rss.tsv /tmp/run -- nice build/apps/arcplan bench \
      --suite suite.yaml -j 2 --out /tmp/run --no-plots --quiet
EOF
}

interval=1
case "${1:-}" in
  -h|--help) usage; exit 0 ;;
  -i) interval="${2:?-i needs a number of seconds}"; shift 2 ;;
esac
if [ $# -lt 4 ] || [ "$3" != "--" ]; then
  usage >&2
  exit 2
fi
samples="$1"
out="$2"
shift 3

# Both tolerate what is not there yet or any more: no logs before the first job, a worker that just ended.
finished_jobs() { { find "$out/logs" -name '*.log' 2>/dev/null || true; } | wc -l; }
status_kb() { sed -n "s/^$2:[[:space:]]*\([0-9]*\) kB/\1/p" "/proc/$1/status" 2>/dev/null || true; }

"$@" &
campaign=$!
start=$(date +%s.%N)
printf 'seconds\tjobs_finished\tworker_pid\tvm_rss_kb\tvm_hwm_kb\n' >"$samples"
while kill -0 "$campaign" 2>/dev/null; do
  jobs=$(finished_jobs)
  now=$(date +%s.%N)
  # Workers are the campaign's forked children named arcplan (not the statistics script at the end).
  for worker in $(pgrep -P "$campaign" -x arcplan || true); do
    rss=$(status_kb "$worker" VmRSS)
    hwm=$(status_kb "$worker" VmHWM)
    [ -n "$rss" ] && printf '%.1f\t%s\t%s\t%s\t%s\n' "$(echo "$now - $start" | bc)" "$jobs" "$worker" "$rss" "$hwm" >>"$samples"
  done
  sleep "$interval"
done
status=0
wait "$campaign" || status=$?

total=$(finished_jobs)
echo "campaign exit status $status, $total jobs finished, samples in $samples"
awk -F'\t' -v total="$total" 'NR > 1 {
    if (!($3 in early) && $2 >= total / 10) { early[$3] = $4; earlyJobs[$3] = $2 }
    last[$3] = $4; lastJobs[$3] = $2; hwm[$3] = $5
  }
  END {
    for (w in last) printf "worker %s: RSS %d kB after %d jobs, %d kB after %d jobs, peak %d kB\n",
                           w, early[w], earlyJobs[w], last[w], lastJobs[w], hwm[w]
  }' "$samples"
exit "$status"
