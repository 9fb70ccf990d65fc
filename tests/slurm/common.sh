# Shared by the Slurm tests (sourced): a running single-node cluster (scripts/slurm-cluster), a
# scratch folder, waiting for jobs and reading how they ended.
# Usage in a test: source common.sh "$arcplan" "$source_dir"; slurm_test_begin.

arcplan="$(realpath "$1")"
source_dir="$(realpath "$2")"
cluster="$source_dir/scripts/slurm-cluster"
suite="$source_dir/tests/slurm/tiny.yaml"
export ARCPLAN="$arcplan"  # the array scripts run this executable (sbatch passes the environment on)
started_cluster=0
work=""

fail() {
  echo "FAIL: $*" >&2
  exit 1
}

cleanup() {
  local status=$?
  cd /
  if [ -n "$work" ] && [ -d "$work" ]; then
    if [ $status -eq 0 ]; then
      rm -rf "$work"
    else
      echo "slurm test: kept $work for inspection" >&2
    fi
  fi
  if [ $started_cluster -eq 1 ]; then "$cluster" stop >&2 || true; fi
  exit $status
}

# Takes the cluster lock (Slurm tests of several build folders share one cluster on this host),
# starts the cluster unless it runs (stopping it again at exit), makes the scratch folder $work.
slurm_test_begin() {
  if [ "$(id -u)" -ne 0 ]; then
    fail "the Slurm tests need root: they start munged, slurmctld and slurmd (scripts/slurm-cluster); run ctest as root"
  fi
  exec 9>/tmp/arcplan-slurm-tests.lock
  flock -w 900 9 || fail "another Slurm test held /tmp/arcplan-slurm-tests.lock for 15 minutes"
  trap cleanup EXIT
  eval "$("$cluster" env)"
  if ! "$cluster" status >/dev/null 2>&1; then
    "$cluster" start >&2 || fail "could not start the Slurm cluster (see above)"
    started_cluster=1
  fi
  work="$(mktemp -d /tmp/arcplan-slurm-test.XXXXXX)"
  cd "$work"
}

# submit ARGS...: sbatch --parsable, prints the job id.
submit() {
  local id
  id="$(sbatch --parsable "$@")" || fail "sbatch $* was refused"
  echo "${id%%;*}"
}

# wait_gone SECONDS JOBID...: until squeue lists none of the jobs (array tasks included).
wait_gone() {
  local limit="$1" deadline
  shift
  deadline=$((SECONDS + limit))
  local ids
  ids="$(IFS=,; echo "$*")"
  while [ -n "$(squeue -h -j "$ids" -o %i 2>/dev/null)" ]; do
    if [ $SECONDS -ge $deadline ]; then
      squeue -j "$ids" >&2 || true
      fail "jobs $ids still queued or running after $limit s"
    fi
    sleep 0.5
  done
}

# jobcomp JOBID FIELD...: fields of the finished-job records (jobcomp/filetxt) of a job or of an
# array's tasks, one line per record, sorted. slurmctld writes the record as the job ends.
jobcomp() {
  local file="${ARCPLAN_SLURM_DIR:-/tmp/arcplan-slurm}/log/jobcomp.txt"
  [ -f "$file" ] || return 0
  local id="$1"
  shift
  awk -v id="$id" -v wanted="$*" '
    {
      delete field
      for (i = 1; i <= NF; ++i) {
        eq = index($i, "=")
        if (eq > 0) field[substr($i, 1, eq - 1)] = substr($i, eq + 1)
      }
      array = ("ArrayJobId" in field) ? field["ArrayJobId"] : ""
      if (array == id || ((array == "" || array == "0") && field["JobId"] == id)) {
        n = split(wanted, names, " ")
        line = ""
        for (k = 1; k <= n; ++k) {
          value = (names[k] in field) ? field[names[k]] : "-"
          line = line (k > 1 ? " " : "") value
        }
        print line
      }
    }' "$file" | sort -n
}

# completions JOBID: "<array task or -> <JobState> <ExitCode>" per finished job or array task.
completions() { jobcomp "$1" ArrayTaskId JobState ExitCode; }

# finished_lines FILE...: the campaign jobs the bench outputs report as finished ("problem · planner").
finished_lines() {
  sed -n 's/^\[[0-9]*\/[0-9]*\] \(.*\): [0-9]*\/[0-9]* runs solved .*/\1/p' "$@"
}

# db_rows DB SQL: the rows of a query, '|' separated.
db_rows() { sqlite3 -batch "$1" "$2"; }
