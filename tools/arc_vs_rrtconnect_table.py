#!/usr/bin/python3
"""The arc planner against RRTConnect (+ OMPL's simplifier) on a benchmark campaign: issue 23's measures.

Reads the campaign's benchmark.db (the database `arcplan bench` builds with ompl_benchmark_statistics) and
prints, as markdown:
  1. per problem family: arc success, runs in mode "arc", runs in mode "fallback", median execution times
     and solve times of both planners;
  2. every run in which the arc planner's fallback ran: its execution time at the campaign's v_max against
     RRTConnect + simplifier's run of the same problem and run seed;
  3. every problem where the arc planner's median solve time is above `--factor` (5) times RRTConnect's.
A run succeeds when it is solved and has an execution time (as RunRecord::succeeded; a run that came closer
than the suite's clearance is not solved). Solve time: the arc planner's own `solve time`, OMPL's `time` for
RRTConnect (without the simplifier).

Reproduce (docs/benchmarks.md, "Issue 23"):
  arcplan bench --suite generated --planners arc-auto,RRTConnect --runs 3 --time 10 --budget 10000000 \\
      --no-plots -j 2 --out /tmp/issue23
  tools/arc_vs_rrtconnect_table.py /tmp/issue23/benchmark.db
or let this script run that campaign first: tools/arc_vs_rrtconnect_table.py --arcplan build/apps/arcplan
--out /tmp/issue23 (an existing campaign folder with the same settings is resumed, not re-run).
"""
import argparse
import os
import sqlite3
import statistics
import subprocess
import sys

NEW_FAMILIES = ("forearm-beam", "lintel-gate", "tilted-tool")
ARC_MODE = {1: "arc", 2: "fallback"}


def run_campaign(arcplan, out, arc, baseline):
    command = [arcplan, "bench", "--suite", "generated", "--planners", f"{arc},{baseline}", "--runs", "3",
               "--time", "10", "--budget", "10000000", "--no-plots", "-j", "2", "--quiet", "--out", out]
    print("$ " + " ".join(command), file=sys.stderr)
    subprocess.run(command, check=True, stdout=sys.stderr)  # bench's ranking table: not part of this one
    return os.path.join(out, "benchmark.db")


def read_runs(db, planner):
    """{problem: (family, [run dicts])} of one planner label (OMPL's 'geometric_' prefix removed)."""
    if not os.path.isfile(db):
        sys.exit(f"{db}: no such file (a finished campaign's benchmark.db is expected)")
    connection = sqlite3.connect(f"file:{db}?mode=ro", uri=True)
    try:
        rows = connection.execute(
            "SELECT e.name, e.problemkind, r.solved, r.execution_time, r.arc_mode, r.solve_time, r.time, "
            "r.run_seed FROM runs r JOIN experiments e ON r.experimentid = e.id "
            "JOIN plannerConfigs p ON r.plannerid = p.id WHERE p.name IN (?, ?)",
            (planner, "geometric_" + planner)).fetchall()
    except sqlite3.OperationalError as error:
        sys.exit(f"{db}: not an arcplan campaign database with run seeds ({error})")
    problems = {}
    for name, family, solved, execution, mode, solve, time, seed in rows:
        problem = name.split("/", 1)[-1]
        run = {"ok": bool(solved) and execution is not None, "exec": execution, "mode": ARC_MODE.get(mode),
               "solve": solve if solve is not None else time, "seed": seed}
        problems.setdefault(problem, (family, []))[1].append(run)
    if not problems:
        sys.exit(f"{db}: no runs of planner '{planner}'")
    return problems


def median(values):
    return statistics.median(values) if values else None


def fmt(value, digits=3):
    return "-" if value is None else f"{value:.{digits}f}"


def family_table(arc, base, arc_label, base_label):
    print(f"| family | problems | {arc_label} success | mode \"arc\" | mode \"fallback\" | {arc_label} exec (s) "
          f"| {base_label} success | {base_label} + simplifier exec (s) | {arc_label} solve (ms) "
          f"| {base_label} solve (ms) |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    families = sorted({family for family, _ in arc.values()})
    totals = {"problems": 0, "runs": 0, "ok": 0, "arc": 0, "fallback": 0}
    for family in families + ["all"]:
        names = [p for p, (f, _) in arc.items() if family in ("all", f)]
        arc_runs = [r for p in names for r in arc[p][1]]
        base_runs = [r for p in names if p in base for r in base[p][1]]
        ok = [r for r in arc_runs if r["ok"]]
        base_ok = [r for r in base_runs if r["ok"]]
        in_arc = sum(r["ok"] and r["mode"] == "arc" for r in arc_runs)
        in_fallback = sum(r["ok"] and r["mode"] == "fallback" for r in arc_runs)
        label = f"**{family}**" if family in NEW_FAMILIES + ("all",) else family
        print(f"| {label} | {len(names)} | {len(ok)}/{len(arc_runs)} | {in_arc}/{len(arc_runs)} "
              f"({100.0 * in_arc / len(arc_runs):.0f} %) | {in_fallback} | {fmt(median([r['exec'] for r in ok]))} "
              f"| {len(base_ok)}/{len(base_runs)} | {fmt(median([r['exec'] for r in base_ok]))} "
              f"| {fmt(1e3 * median([r['solve'] for r in ok]) if ok else None, 2)} "
              f"| {fmt(1e3 * median([r['solve'] for r in base_ok]) if base_ok else None, 2)} |")


def fallback_table(arc, base, arc_label, base_label):
    # Run by run against the base planner's run of the same run seed (one seed per problem and run for
    # every planner, docs/reproducibility.md): the "same problem and seed".
    print(f"| problem | run seed | {arc_label} fallback exec (s) | {base_label} + simplifier exec (s), same seed "
          f"| fallback no slower? |")
    print("|---|---:|---:|---:|---|")
    slower = 0
    runs_shown = 0
    for problem in sorted(arc):
        theirs = {r["seed"]: r for r in base.get(problem, ("", []))[1]}
        for run in arc[problem][1]:
            if not (run["ok"] and run["mode"] == "fallback"):
                continue
            runs_shown += 1
            other = theirs.get(run["seed"])
            if other is None or not other["ok"]:
                verdict, their_exec = f"{base_label} did not solve it", "-"
            else:
                verdict = "yes" if run["exec"] <= other["exec"] else "**no**"
                slower += run["exec"] > other["exec"]
                their_exec = fmt(other["exec"])
            print(f"| {problem} | {run['seed']} | {fmt(run['exec'])} | {their_exec} | {verdict} |")
    print(f"\n{runs_shown} fallback run(s), {slower} of them slower to execute than {base_label}'s run of the same seed.")


def solve_time_table(arc, base, arc_label, base_label, factor):
    # Wall-clock solve times of sub-millisecond queries move several-fold with the machine's load (the arc
    # planner's runs are identical work, yet differ), so the ratio of the fastest runs is shown beside the
    # medians': a problem over the factor by both is a finding, one over it by the medians alone may be load.
    print(f"| problem | {arc_label} solve (ms) | {base_label} solve (ms) | ratio of medians | ratio of fastest runs |")
    print("|---|---:|---:|---:|---:|")
    violators = robust = 0
    for problem in sorted(arc):
        mine = [r["solve"] for r in arc[problem][1] if r["solve"] is not None]
        theirs = [r["solve"] for r in base.get(problem, ("", []))[1] if r["solve"] is not None]
        if not mine or not theirs or median(mine) <= factor * median(theirs):
            continue
        violators += 1
        fastest = min(mine) / min(theirs)
        robust += fastest > factor
        print(f"| {problem} | {fmt(1e3 * median(mine), 2)} | {fmt(1e3 * median(theirs), 2)} "
              f"| {median(mine) / median(theirs):.1f} | {fastest:.1f} |")
    print(f"\n{violators} of {len(arc)} problems with the {arc_label} median solve time over {factor:g}x "
          f"{base_label}'s; {robust} of them also by the fastest runs.")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("db", nargs="?", help="benchmark.db of a finished campaign")
    parser.add_argument("--arcplan", help="run the campaign first with this arcplan binary (needs --out)")
    parser.add_argument("--out", help="campaign folder for --arcplan")
    parser.add_argument("--arc", default="arc-auto", help="arc planner label (default arc-auto)")
    parser.add_argument("--baseline", default="RRTConnect", help="baseline planner label (default RRTConnect)")
    parser.add_argument("--factor", type=float, default=5.0, help="solve-time factor (default 5)")
    args = parser.parse_args()
    if args.arcplan:
        if not args.out:
            parser.error("--arcplan needs --out")
        db = run_campaign(args.arcplan, args.out, args.arc, args.baseline)
    elif args.db:
        db = args.db
    else:
        parser.error("give a benchmark.db or --arcplan and --out")
    arc, base = read_runs(db, args.arc), read_runs(db, args.baseline)
    print(f"## {args.arc} against {args.baseline} ({db})\n")
    family_table(arc, base, args.arc, args.baseline)
    print(f"\n### Where the fallback ran\n")
    fallback_table(arc, base, args.arc, args.baseline)
    print(f"\n### Solve time over {args.factor:g}x {args.baseline}'s\n")
    solve_time_table(arc, base, args.arc, args.baseline, args.factor)


if __name__ == "__main__":
    main()
