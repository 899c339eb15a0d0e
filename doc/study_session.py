# SPDX-License-Identifier: LGPL-2.1-or-later

"""The command line and the session record shared by the study scripts
doc/locking/run_locking.py, doc/error_vs_runtime/run_error_vs_runtime.py and
doc/twisting_column/run_twisting_column.py: which cases to run, running
them one at a time (in the order the script lists them), and the list of runs (command, commit, machine, load,
date, duration) that the report names. A run of all cases starts the list
afresh; a run with --cases adds itself to it, and the report shows its cases
with those of the earlier runs. --report-only writes the report from the
output directory alone."""

import argparse
import json
import os
import sys
import time
from pathlib import Path

REPOSITORY = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPOSITORY / "doc" / "performance"))
from run_benchmarks import commit, machine_description  # noqa: E402


def run_lines(session):
    """One line of the report per run of the script."""
    return [f"- `{run['command']}`: commit `{run['commit']}`, {run['date']}, "
            f"{run['total_seconds']:.0f} s; {run['machine']}; load average at the "
            f"start {run['load']}; the program ran with {run['threads']} thread(s), "
            "one case at a time" for run in session["runs"]]


def study_main(description, script, output, report, cases, run_case, load_case,
               write_report):
    """Parses the command line, runs the selected cases with
    run_case(build, output_root, name, timeout, threads), and writes the
    report with write_report(path, results, session) from the results
    load_case(output_root, name) finds (None for a case that has not run)."""
    parser = argparse.ArgumentParser(description=description,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("build", help="the Release build directory (with soft-robot)")
    parser.add_argument("--cases", help="comma-separated case names (default: all)")
    parser.add_argument("--output", default=output)
    parser.add_argument("--report", default=report)
    parser.add_argument("--timeout", type=float, default=1800.,
                        help="seconds after which a case is killed (default 1800)")
    parser.add_argument("--threads", type=int, default=1,
                        help="threads of the program (DEAL_II_NUM_THREADS, default 1)")
    parser.add_argument("--report-only", action="store_true",
                        help="write the report from the output of earlier runs")
    arguments = parser.parse_args()

    build = Path(arguments.build).resolve()
    output_root = (REPOSITORY / arguments.output).resolve()
    output_root.mkdir(parents=True, exist_ok=True)
    selected = cases
    if arguments.cases:
        names = arguments.cases.split(",")
        unknown = set(names) - set(cases)
        if unknown:
            sys.exit(f"unknown case(s): {', '.join(sorted(unknown))}; "
                     f"known: {', '.join(cases)}")
        selected = [name for name in cases if name in names]
    session_path = output_root / "session.json"
    session = json.loads(session_path.read_text()) if session_path.exists() else {"runs": []}
    if not arguments.report_only:
        if not (build / "soft-robot").exists():
            sys.exit(f"{build / 'soft-robot'} does not exist: build in Release first")
        try:
            shown = str(build.relative_to(REPOSITORY))
        except ValueError:
            shown = "<Release build directory>"
        run = {"command": f"/usr/bin/python3 {script} {shown}"
                          + (f" --cases {arguments.cases}" if arguments.cases else ""),
               "commit": commit(), "machine": machine_description(),
               "load": ", ".join(f"{x:.2f}" for x in os.getloadavg()),
               "date": time.strftime("%Y-%m-%d"), "threads": arguments.threads,
               "timeout": arguments.timeout,
               "cases": arguments.cases.split(",") if arguments.cases else None}
        start = time.perf_counter()
        for name in selected:
            run_case(build, output_root, name, arguments.timeout, arguments.threads)
        run["total_seconds"] = time.perf_counter() - start
        # Read again: another session of the same study may have finished
        # meanwhile (two studies on the two cores).
        session = (json.loads(session_path.read_text()) if session_path.exists()
                   else {"runs": []})
        # An earlier run whose cases this one has all run again produces no
        # row of the report any more (a run without --cases ran them all).
        kept = [earlier for earlier in session["runs"]
                if arguments.cases
                and not set(earlier.get("cases") or cases) <= set(run["cases"])]
        session["runs"] = kept + [run]
        session_path.write_text(json.dumps(session, indent=1) + "\n")
    results = [r for r in (load_case(output_root, name) for name in cases) if r]
    write_report(REPOSITORY / arguments.report, results, session)
