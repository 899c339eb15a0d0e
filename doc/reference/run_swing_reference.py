#!/usr/bin/python3
# SPDX-License-Identifier: LGPL-2.1-or-later
"""Toward the references of experiments 2 and 3 (issue 23): how far
quadratic tetrahedra in the mean-dilatation formulation are from converged,
in time and in space, on the planar pendulum (half model) and the spherical
pendulum (full model). The companion of run_reference.py, which does the
same for experiment 1; the same solver settings (its SOLVER list), the
scenes `parameters/bellows/planar_<silicone>_3d.prm` and
`spherical_<silicone>_3d.prm` with `Time integration/End time = 4` (the
spectral analysis skips the first second, as in the scenes) and without
VTU output; on the meshes finer than the coarse one (35,000 unknowns
and more) the direct solver is MUMPS. The report doc/reference_swing.md gives, per run and per
direction of the tip motion, the frequency and damping ratio of the
dominant peak's modal fit (`tip_spectrum.csv`), and their changes under
halving the step and under refining the mesh. Its discussion is the
section on the swing in doc/reference_discussion.md.

    /usr/bin/python3 doc/reference/run_swing_reference.py build-release
        [--cases a,b] [--timeout 3600] [--threads 1] [--report-only]

Nothing here is a test: the numbers are reported, not checked.
"""

import csv
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from run_reference import (SILICONES, SOLVER, load_case, percent,  # noqa: E402
                           run_scene)
from run_benchmarks import write_with_discussion_link  # noqa: E402
from study_session import run_lines, study_main  # noqa: E402

RECORD = 4.  # s
# experiment key: (title, scene prefix, model of the mesh, directions reported)
EXPERIMENTS = {
    "planar": ("Experiment 2, the planar pendulum (half model)", "planar", "half",
               ("horizontal", "vertical")),
    "spherical": ("Experiment 3, the spherical pendulum (full model)", "spherical",
                  "full", ("horizontal", "depth", "vertical")),
}
LEVELS = ("coarse", "medium", "fine")
STEPS = (0.01, 0.005)

# name, experiment, silicone key, mesh level, time step
CASES = ([(f"{e}_ds20_{level}_dt{dt:g}", e, "ds20", level, dt)
          for e in EXPERIMENTS for level, dt in
          (("coarse", 0.01), ("coarse", 0.005), ("medium", 0.01))] +
         [(f"{e}_{s}_{level}_dt0.01", e, s, level, 0.01)
          for e in EXPERIMENTS for s in ("ds30", "ef50")
          for level in ("coarse", "medium")])
CASE_NAMES = [c[0] for c in CASES]


def read_directions(output):
    """Frequency and damping ratio of the dominant peak's modal fit in every
    direction of the tip motion."""
    path = output / "tip_spectrum.csv"
    if not path.exists():
        return None
    found = {}
    with open(path) as file:
        for row in csv.DictReader(file):
            if row["peak"] == "dominant":
                found[row["direction"]] = {"f": float(row["f_damped_fit_Hz"]),
                                           "xi": float(row["xi_fit"])}
    return found


def run_case(build, output_root, name, timeout, threads):
    _, experiment, silicone, level, dt = next(c for c in CASES if c[0] == name)
    _, prefix, model, _ = EXPERIMENTS[experiment]
    entries = SOLVER + [f"Time integration/End time={RECORD:g}",
                        f"Geometry/Mesh file=../../meshes/bellows_{model}_{level}.msh",
                        f"Time integration/Time step={dt:g}"]
    if level != "coarse":
        entries.append("Linear solver/Direct solver=MUMPS")
    run_scene(build, output_root / name, name,
              f"parameters/bellows/{prefix}_{silicone}_3d.prm", entries, timeout,
              threads, read_directions)


def cell(r, direction, key, digits):
    value = (r["spectrum"] or {}).get(direction, {}).get(key)
    return f"{value:.{digits}f}" if value is not None else "–"


def change(a, b, direction, key):
    x = (a["spectrum"] or {}).get(direction, {}).get(key)
    y = (b["spectrum"] or {}).get(direction, {}).get(key)
    return percent(x, y) if x is not None and y is not None else "–"


def runs_table(cases, by_name, directions):
    """The table of the runs (name, mesh, time step) in `cases`: unknowns,
    silicone volume, f and ξ per direction, and the cost; a case without a
    result is marked 'not run'. Shared with run_swing_hex_reference.py."""
    lines = ["| case | mesh | dofs | silicone volume mm³ | dt s | "
             + " | ".join(f"f {d} Hz | ξ {d}" for d in directions)
             + " | wall s | s/step | Newton/step | factorizations/step | cutbacks "
             "| peak MB | kB/dof |",
             "|---|---|---:|---:|---:|" + "---:|" * (2 * len(directions) + 7)]
    for name, mesh, dt in cases:
        r = by_name.get(name)
        if not r:
            lines.append(f"| {name} | {mesh} | | | {dt:g} | not run |"
                         + " |" * (2 * len(directions) + 6))
            continue
        lines.append(
            f"| {name} | {mesh} | {r['dofs']} | {r['volume']:.0f} | {dt:g} | "
            + " | ".join(f"{cell(r, d, 'f', 5)} | {cell(r, d, 'xi', 5)}"
                         for d in directions)
            + f" | {r['wall_seconds']:.1f} | {r['wall_seconds'] / r['steps']:.2f} | "
            f"{r['newton_iterations'] / r['steps']:.2f} | "
            f"{r['factorizations_or_amg_setups'] / r['steps']:.2f} | "
            f"{r['cutbacks']} | {r['peak_memory_mb']:.0f} | "
            f"{1024. * r['peak_memory_mb'] / r['dofs']:.1f} |")
    return lines


def change_rows(label, silicone, a, b, directions):
    """One row of a change table: the changes of f and ξ of run a relative
    to run b in every direction."""
    return (f"| {label} | {SILICONES[silicone]} | " + " | ".join(
        f"{change(a, b, d, 'f')} | {change(a, b, d, 'xi')}" for d in directions)
        + " |")


def write_report(path, results, session):
    by_name = {r["name"]: r for r in results
               if r.get("status") == "finished" and r.get("spectrum")}
    lines = ["<!-- Written by doc/reference/run_swing_reference.py; the discussion "
             "is in doc/reference_discussion.md. -->",
             "# Toward the references of experiments 2 and 3", ""]
    lines += run_lines(session)
    lines += ["",
              "Quadratic tetrahedra in the mean-dilatation formulation, HHT α = "
              "−0.25, baseline parameter set, 4 s of the swing; f and ξ are the "
              "modal fit of the dominant peak of each direction of the tip motion "
              "after the first second (horizontal: the principal direction of the "
              "swing; depth: across it). s/step is the wall time over the steps "
              "(the static start included); peak MB is the process's peak "
              "resident memory, and kB/dof that over the unknowns. Wall times are the program's own, with "
              "the threads the line of each run above gives; sessions listed with "
              "the same start load ran at the same time, one on each core."]
    for experiment, (title, _, _, directions) in EXPERIMENTS.items():
        lines += ["", f"## {title}", ""]
        lines += runs_table([(name, level, dt) for name, e, _, level, dt in CASES
                             if e == experiment], by_name, directions)
        lines += ["", "| change | silicone | " + " | ".join(
                      f"f {d} | ξ {d}" for d in directions) + " |",
                  "|---|---|" + "---:|" * (2 * len(directions))]
        for silicone in SILICONES:
            pairs = []
            for level in LEVELS:
                a = by_name.get(f"{experiment}_{silicone}_{level}_dt0.01")
                b = by_name.get(f"{experiment}_{silicone}_{level}_dt0.005")
                if a and b:
                    pairs.append((f"{level} mesh, dt 0.01 against 0.005", a, b))
            for dt in STEPS:
                for coarse, fine in zip(LEVELS, LEVELS[1:]):
                    a = by_name.get(f"{experiment}_{silicone}_{coarse}_dt{dt:g}")
                    b = by_name.get(f"{experiment}_{silicone}_{fine}_dt{dt:g}")
                    if a and b:
                        pairs.append((f"dt {dt:g}, {coarse} mesh against {fine}",
                                      a, b))
            for label, a, b in pairs:
                lines.append(change_rows(label, silicone, a, b, directions))
        lines += ["", "A change is that of the first run relative to the second."]
    write_with_discussion_link(path, lines, "reference_discussion.md")


if __name__ == "__main__":
    study_main(__doc__, "doc/reference/run_swing_reference.py",
               "output/reference_swing", "doc/reference_swing.md", CASE_NAMES,
               run_case, load_case, write_report)
