#!/usr/bin/python3
# SPDX-License-Identifier: LGPL-2.1-or-later
"""The locking study (issue 6, "show locking and its cure"): the
experiment-1 tip frequency against refinement for kappa/mu = 1e2, 1e3 and
1e4, with linear and with quadratic tetrahedra. Runs the cases with the
Release build of soft-robot, one at a time, and writes doc/locking.md with
its figures in doc/figures/locking/.

    /usr/bin/python3 doc/locking/run_locking.py build-release
        [--cases a,b] [--timeout 900] [--threads 1] [--report-only]

What the program offers against locking: quadratic tetrahedra (`Finite
element/Polynomial degree = 2`), which lock much less than linear ones, and
the mean-dilatation formulation (`Finite element/Volumetric formulation =
mean dilatation`: the three-field formulation with pressure and dilatation
constant per cell, condensed cell by cell), which with quadratic
tetrahedra is the stable P2-P0 pair. With linear tetrahedra the
mean-dilatation formulation is identical to the displacement one (their
volume ratio is constant per cell), so it is run with P2 only. The study
measures all three.

Every case is parameters/bellows/vertical_ds20_3d.prm (experiment 1,
Dragon Skin 20, quarter model) with `--set` overrides: the silicone's
`Bulk-to-shear ratio` in its library entry (kappa/mu), the mesh (coarse,
medium, fine, or the coarse mesh refined once), the polynomial degree
(1 on every mesh, 2 on the coarse and the medium one) and the volumetric
formulation (displacement everywhere; mean dilatation with degree 2 on
the coarse and the medium mesh).
All frequency cases run the same shortened record, `Time integration/End
time = 2.5` (about 9 periods), without VTU output; the baseline (P1 coarse,
kappa/mu = 100) also runs the scene's full 5.25 s once, to show what the
shorter record changes.

For each case the script records whether the run finished (exit code; a run
that stops prints "The simulation stopped:" and exits 2, a result in its
own right), the number of steps, time-step cutbacks, Newton iterations and
wall time (`run_statistics.json`, written by a run that finishes, else the
trajectory and the log), and the `vertical` row of `tip_spectrum.csv`: the
FFT peak `f_peak_Hz` (interpolated between bins) and the modal fit's damped
frequency `f_damped_fit_Hz` and damping ratio `xi_fit`.

The log prints each material's shear modulus but not its bulk modulus. So
the three P1 coarse cases write the initial (held, static) state as VTU,
from which the script reads the volume-weighted mean |1 - J| of the
silicone: it must fall as kappa rises, if the override took effect.

Without --cases the script runs every case and the report shows them.
With --cases it runs only those and the report shows them together with the
cases of earlier runs found in the output directory; the file
session.json there keeps each run's command, commit, date and duration
for the report's header (a run of all cases starts it afresh).
--report-only writes the report from the output directory alone.

The cost. On 2 shared cores with one thread the P1 cases and P2 on the
coarse mesh took 18 minutes together, P2 on the medium mesh 28 more (the
one with kappa/mu = 1e4 alone 15 minutes); leave the p2_medium cases out
with --cases for a quicker run.

A case that runs longer than --timeout seconds (default 1800) is killed (its whole process
group) and reported as a hang. The program runs with --threads threads
(DEAL_II_NUM_THREADS; default 1, so that a shared machine keeps a core).

Nothing here is a test: the numbers are reported, not checked.
"""

import csv
import json
import math
import os
import re
import shutil
import sys
from pathlib import Path

import numpy as np
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

REPOSITORY = Path(__file__).resolve().parents[2]
FIGURES = "doc/figures/locking"

# The report helpers of the other studies: the machine and the commit as in
# the speed benchmark, the VTU reader and the log parsers of the stability
# study.
sys.path.insert(0, str(REPOSITORY / "doc" / "performance"))
sys.path.insert(0, str(REPOSITORY / "doc" / "stability"))
sys.path.insert(0, str(REPOSITORY / "doc"))
from run_benchmarks import write_with_discussion_link  # noqa: E402
from study_session import study_main, tetrahedral_defaults  # noqa: E402
from run_stability import (cutbacks_from_log, deformation_of_cells,  # noqa: E402
                           read_trajectory, read_vtu, run_program)

SCENE = "parameters/bellows/vertical_ds20_3d.prm"
# Dragon Skin 20's entry in parameters/silicones.prm.
DS20 = "Silicone library/Silicone 2"
MESHES = "../../meshes/bellows_quarter"  # relative to the scene's directory

QUIET = ["Output/Progress interval=0"]
RECORD = 2.5     # s, the shortened record of every frequency case
FULL = 5.25      # s, the scene's own record

KAPPAS = [100., 1000., 10000.]

# name, label, overrides, marker in the figures
DISCRETISATIONS = [
    ("p1_coarse", "P1 coarse", [], "o"),
    ("p1_medium", "P1 medium", [f"Geometry/Mesh file={MESHES}_medium.msh"], "o"),
    ("p1_fine", "P1 fine", [f"Geometry/Mesh file={MESHES}_fine.msh"], "o"),
    ("p1_refined", "P1 coarse refined once", ["Geometry/Global refinements=1"], "s"),
    ("p2_coarse", "P2 coarse", ["Finite element/Polynomial degree=2"], "*"),
    ("p2_medium", "P2 medium", [f"Geometry/Mesh file={MESHES}_medium.msh",
                                "Finite element/Polynomial degree=2"], "*"),
    ("p2md_coarse", "P2 mean dilatation coarse",
     ["Finite element/Polynomial degree=2",
      "Finite element/Volumetric formulation=mean dilatation"], "D"),
    ("p2md_medium", "P2 mean dilatation medium",
     [f"Geometry/Mesh file={MESHES}_medium.msh", "Finite element/Polynomial degree=2",
      "Finite element/Volumetric formulation=mean dilatation"], "D"),
]
LABEL = {d[0]: d[1] for d in DISCRETISATIONS}
MARKER = {d[0]: d[3] for d in DISCRETISATIONS}
# The result a table's "change" column compares with: the first of these
# that finished (quadratic elements in the mean-dilatation formulation do not
# lock, and quadratic elements are the most accurate per unknown), else the
# finished linear case with the most dofs.
REFERENCES = ["p2md_medium", "p2md_coarse", "p2_medium", "p2_coarse"]


def kappa_tag(kappa):
    return f"k1e{round(math.log10(kappa))}"


def kappa_text(kappa):
    return f"1e{round(math.log10(kappa))}"


# name, discretisation, kappa/mu, overrides, kind, VTU of the initial state,
# description. kind: "record" (the study's shortened record) or "full" (the
# scene's 5.25 s).
CASES = []
for key, label, overrides, _ in DISCRETISATIONS:
    for kappa in KAPPAS:
        CASES.append((f"{key}_{kappa_tag(kappa)}", key, kappa,
                      overrides + [f"{DS20}/Bulk-to-shear ratio={kappa:g}",
                                   f"Time integration/End time={RECORD:g}"],
                      "record", key == "p1_coarse",
                      f"{label}, kappa/mu = {kappa_text(kappa)}, {RECORD:g} s"))
CASES.append(("p1_coarse_k1e2_full", "p1_coarse", 100.,
              [f"{DS20}/Bulk-to-shear ratio=100"], "full", False,
              f"P1 coarse, kappa/mu = 1e2, the scene's full {FULL:g} s"))
CASE_NAMES = [case[0] for case in CASES]
# The order of the runs: the cheap cases first.
RUN_ORDER = (["p1_coarse_k1e2_full"]
             + [n for d in ("p1_coarse", "p1_medium", "p1_fine", "p2_coarse",
                            "p2md_coarse", "p1_refined", "p2_medium", "p2md_medium")
                for n in CASE_NAMES if n.startswith(d + "_k") and not n.endswith("_full")])
assert sorted(RUN_ORDER) == sorted(CASE_NAMES)


# @sect{Running a case}

def read_spectrum(output):
    """The `vertical` row of tip_spectrum.csv, numbers as floats."""
    path = output / "tip_spectrum.csv"
    if not path.exists():
        return None
    with open(path) as file:
        for row in csv.DictReader(file):
            if row["direction"] != "vertical":
                continue
            result = {"peak": row["peak"], "warnings": row["warnings"]}
            for key in ("f_peak_Hz", "xi_fit", "f_damped_fit_Hz", "f_natural_fit_Hz",
                        "xi_log_decrement", "cycles", "resolution_Hz", "duration_s",
                        "magnitude"):
                try:
                    result[key] = float(row[key])
                except (KeyError, ValueError):
                    result[key] = None
            return result
    return None


def mean_volume_change(output):
    """Volume-weighted mean |1 - J| of the silicone (material 1) and of the
    tip block in the VTU file of the initial state; the VTU files are
    deleted after they have been read."""
    files = sorted(output.glob("solution_*.vtu"))
    result = None
    if files:
        arrays = read_vtu(files[0])
        _, J, material, volume = deformation_of_cells(arrays)
        result = {"t": float(arrays["TIME"][0])}
        for id, key in ((1, "silicone"), (2, "block")):
            m = material == id
            result[key] = float(np.sum(volume[m] * np.abs(1. - J[m])) / np.sum(volume[m]))
    for pattern in ("solution_*.vtu", "solution_*.pvtu", "solution.pvd"):
        for path in output.glob(pattern):
            path.unlink()
    return result


def run_case(build, output_root, case, timeout, threads):
    name, key, kappa, overrides, kind, vtu, description = case
    output = output_root / name
    if output.exists():
        shutil.rmtree(output)
    output.mkdir(parents=True)
    entries = tetrahedral_defaults(SCENE) + QUIET
    if vtu:
        entries += ["Output/Write VTU=true", "Output/Output interval=1e9"]
    else:
        entries.append("Output/Write VTU=false")
    entries += overrides
    command = [str(build / "soft-robot"), SCENE,
               "--set", f"Problem/Output directory={output}"]
    for entry in entries:
        command += ["--set", entry]
    environment = dict(os.environ, OMP_NUM_THREADS="1", DEAL_II_NUM_THREADS=str(threads))
    print(f"[{name}] {description}", flush=True)

    log, outcome = run_program(command, environment, output, timeout)
    result = {"name": name, "discretisation": key, "kappa": kappa, "kind": kind,
              "overrides": overrides, **outcome}
    dofs = re.search(r"Degrees of freedom: (\d+)", log)
    cells = re.search(r"Mesh: (\d+) simplex cells", log)
    result["dofs"] = int(dofs.group(1)) if dofs else None
    result["cells_in_log"] = int(cells.group(1)) if cells else None
    events, reasons = cutbacks_from_log(log)
    result["cutbacks_in_log"] = len(events)
    result["cutback_reasons"] = reasons

    statistics_path = output / "run_statistics.json"
    if statistics_path.exists():
        result["statistics"] = json.loads(statistics_path.read_text())
    trajectory_path = output / "tip_trajectory.csv"
    if trajectory_path.exists():
        d, finite = read_trajectory(trajectory_path)
        steps = d["t"] > 0
        result["trajectory"] = {
            "finite": finite, "end_time": float(d["t"][-1]), "steps": int(steps.sum()),
            "newton_mean": float(d["newton_iterations"][steps].mean()) if steps.any() else None,
            "newton_max": int(d["newton_iterations"][steps].max()) if steps.any() else None,
            "u_x_range": [float(d["u_x"].min()), float(d["u_x"].max())]}
    result["spectrum"] = read_spectrum(output)
    if vtu:
        result["volume_change"] = mean_volume_change(output)
    (output / "result.json").write_text(json.dumps(result, indent=1))
    f = result["spectrum"]["f_damped_fit_Hz"] if result["spectrum"] else None
    print(f"    {result['status']} (exit {result['exit_code']}) "
          f"in {result['measured_seconds']:.1f} s, "
          f"{result['dofs']} dofs, f fit = {f}", flush=True)
    return result


def load_case(output_root, name):
    path = output_root / name / "result.json"
    return json.loads(path.read_text()) if path.exists() else None


# @sect{What the report shows}

def measures(r):
    """The numbers of one case for the tables; None where the run gave
    none."""
    s = r.get("statistics")
    x = r.get("trajectory") or {}
    spectrum = r.get("spectrum") or {}
    steps = s["steps"] if s else x.get("steps")
    newton = s["newton_iterations"] / max(s["steps"], 1) if s else x.get("newton_mean")
    wall = s["wall_seconds"] if s else r["measured_seconds"]
    loop = None
    if s and s["steps"]:
        # the time loop: the whole run less the mesh, the set-up and the
        # initial static equilibrium
        sections = s["sections"]
        loop = (s["wall_seconds"] - sections.get("Initial state", 0.)
                - sections.get("Make grid", 0.) - sections.get("Setup system", 0.)) / s["steps"]
    return {
        "finished": r["status"] == "finished", "dofs": r.get("dofs"),
        "cells": s["cells"] if s else r.get("cells_in_log"),
        "steps": steps, "cutbacks": s["cutbacks"] if s else r["cutbacks_in_log"],
        "newton": newton, "newton_max": x.get("newton_max"), "wall": wall,
        "ms_per_step": 1000 * loop if loop is not None else None,
        "initial_state": s["sections"].get("Initial state") if s else None,
        "f_peak": spectrum.get("f_peak_Hz"), "f_fit": spectrum.get("f_damped_fit_Hz"),
        "xi": spectrum.get("xi_fit"), "cycles": spectrum.get("cycles"),
        "resolution": spectrum.get("resolution_Hz"),
        "threads": s.get("threads_per_process") if s else None,
        "end_time": x.get("end_time"),
    }


def fmt(value, digits=3):
    if value is None or (isinstance(value, float) and not math.isfinite(value)):
        return "–"
    return f"{value:.{digits}f}"


def status_text(r):
    if r["status"] == "finished":
        return "yes"
    if r["status"] == "stopped":
        return f"**stopped (exit 2)**: {r['message']}"
    if r["status"] == "hang":
        return f"**no: killed at the {r['measured_seconds']:.0f} s timeout**"
    return f"**no: crashed (exit {r['exit_code']})**"


def reference_of(by_key):
    """The case each kappa's "change" column compares with."""
    for key in REFERENCES:
        if key in by_key and by_key[key][1]["finished"] and by_key[key][1]["f_fit"]:
            return key
    p1 = [(m["dofs"], key) for key, (_, m) in by_key.items()
          if key.startswith("p1") and m["finished"] and m["f_fit"]]
    return max(p1)[1] if p1 else None


# One colour per kappa/mu, one per discretisation.
KAPPA_COLORS = ["tab:blue", "tab:green", "tab:red"]
DISCRETISATION_COLORS = ["tab:blue", "tab:orange", "tab:green", "tab:purple", "tab:red",
                         "tab:brown", "tab:pink", "tab:gray"]


def plot_frequency_against_dofs(groups, path):
    """Left: the frequency against the dofs; right: against the cost of a
    step."""
    figure, axes = plt.subplots(1, 2, figsize=(12, 5.0))
    for i, (kappa, by_key) in enumerate(groups):
        color = KAPPA_COLORS[i % len(KAPPA_COLORS)]
        for ax, cost in zip(axes, ("dofs", "ms_per_step")):
            def series(keys):
                return [(by_key[k][1][cost], by_key[k][1]["f_fit"]) for k in keys
                        if k in by_key and by_key[k][1]["f_fit"] and by_key[k][1][cost]]
            p1 = series(("p1_coarse", "p1_medium", "p1_fine"))
            if p1:
                ax.plot(*zip(*p1), "-o", color=color, ms=5,
                        label=f"P1 coarse, medium, fine; κ/μ = {kappa_text(kappa)}")
            refined = series(("p1_coarse", "p1_refined"))
            if len(refined) == 2:
                ax.plot(*zip(*refined), "--", color=color, lw=0.9)
                ax.plot(*refined[1], "s", color=color, ms=7, mfc="none",
                        label=f"P1 coarse refined once; κ/μ = {kappa_text(kappa)}")
            p2 = series(("p2_coarse", "p2_medium"))
            if p2:
                ax.plot(*zip(*p2), "-*", color=color, ms=13, lw=1.6,
                        label=f"P2 coarse, medium; κ/μ = {kappa_text(kappa)}")
            p2md = series(("p2md_coarse", "p2md_medium"))
            if p2md:
                ax.plot(*zip(*p2md), ":D", color=color, ms=8, lw=1.6, mfc="none",
                        label=f"P2 mean dilatation coarse, medium; κ/μ = "
                              f"{kappa_text(kappa)}")
    for ax, label in zip(axes, ("degrees of freedom",
                                "cost: ms per time step (1 process; see the tables)")):
        ax.set_xscale("log")
        ax.set_xlabel(label)
        ax.set_ylabel("tip frequency, modal fit (Hz)")
        ax.grid(alpha=0.3, which="both")
    handles, labels = axes[0].get_legend_handles_labels()
    figure.legend(handles, labels, fontsize=7, ncol=3, loc="lower center")
    figure.suptitle("Experiment 1, Dragon Skin 20: tip frequency against refinement (left) "
                    "and against the cost of a step (right), one colour per κ/μ.\n"
                    "Circles: linear tetrahedra on the coarse, medium and fine meshes; open "
                    "squares (dashed from the coarse mesh): linear, coarse mesh refined "
                    "once;\nstars: quadratic on the coarse and the medium mesh; open "
                    "diamonds (dotted): the same in the mean-dilatation formulation",
                    fontsize=9)
    figure.tight_layout(rect=(0, 0.13, 1, 0.98))
    figure.savefig(path, dpi=110)
    plt.close(figure)


def plot_frequency_against_kappa(groups, path):
    figure, ax = plt.subplots(figsize=(7.5, 4.6))
    for j, (key, label, _, marker) in enumerate(DISCRETISATIONS):
        series = [(kappa, by_key[key][1]["f_fit"]) for kappa, by_key in groups
                  if key in by_key and by_key[key][1]["f_fit"]]
        if series:
            ax.plot(*zip(*series), (":" if key.startswith("p2md") else "--"
                                     if key.startswith("p2") else "-") + marker,
                    color=DISCRETISATION_COLORS[j % len(DISCRETISATION_COLORS)],
                    ms=11 if marker == "*" else 6, label=label)
    ax.set_xscale("log")
    ax.set_xlabel("κ/μ of the silicone")
    ax.set_ylabel("tip frequency, modal fit (Hz)")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=8)
    ax.set_title("Tip frequency against the bulk-to-shear ratio", fontsize=10)
    figure.tight_layout()
    figure.savefig(path, dpi=110)
    plt.close(figure)


def write_report(path, results, session):
    figures = REPOSITORY / FIGURES
    figures.mkdir(parents=True, exist_ok=True)
    m = {r["name"]: measures(r) for r in results}
    by_name = {r["name"]: r for r in results}
    record = [r for r in results if r["kind"] == "record"]
    groups = []
    for kappa in KAPPAS:
        by_key = {r["discretisation"]: (r, m[r["name"]]) for r in record
                  if r["kappa"] == kappa}
        if by_key:
            groups.append((kappa, by_key))
    plot_frequency_against_dofs(groups, figures / "frequency.png")
    plot_frequency_against_kappa(groups, figures / "frequency_against_kappa.png")

    lines = []
    lines.append("<!-- Written by doc/locking/run_locking.py; "
                 "the discussion is in doc/locking_discussion.md. -->")
    lines.append("# Locking: the experiment-1 frequency against refinement and κ/μ\n")
    runs = session["runs"]
    total = sum(run["total_seconds"] for run in runs)
    if len(runs) == 1:
        run = runs[0]
        lines.append(f"Command: `{run['command']}`  ")
        lines.append(f"Commit: `{run['commit']}` (HEAD when the study started), "
                     "Release build  ")
        lines.append(f"Machine: {run['machine']}; load average at the start "
                     f"{run['load']}; the program ran with {run['threads']} "
                     f"thread(s), one case at a time  ")
        lines.append(f"Date: {run['date']}; the whole study took "
                     f"{total:.0f} s ({total / 60:.1f} min)\n")
    else:
        lines.append(f"The results come from {len(runs)} runs of the script (a run "
                     "with `--cases` adds its cases to those of the earlier runs); "
                     f"together they took {total:.0f} s ({total / 60:.1f} min). "
                     "Release build; the program ran one case at a time.\n")
        for run in runs:
            cases = ", ".join(run["cases"]) if run.get("cases") else "all cases"
            lines.append(f"- `{run['command']}`: commit `{run['commit']}`, "
                         f"{run['date']}, {run['total_seconds']:.0f} s, "
                         f"{run['threads']} thread(s), load average at the start "
                         f"{run['load']}; {run['machine']}; {cases}")
        lines.append("")
    lines.append(
        f"Scene: `{SCENE}` (experiment 1, vertical oscillation after the hold is let go; "
        "Dragon Skin 20, baseline μ = 116 kPa; quarter model; HHT α = −0.25, "
        "dt = 0.01 s). Every case is the scene with `--set` overrides: "
        f"`{DS20}/Bulk-to-shear ratio` (κ/μ; entry 2 of `parameters/silicones.prm` "
        "is Dragon Skin 20), the mesh (`Geometry/Mesh file`: the coarse, medium or fine "
        "quarter mesh, or the coarse one with `Geometry/Global refinements=1`) and "
        "`Finite element/Polynomial degree` (1: linear tetrahedra, P1; 2: quadratic, "
        "P2) and `Finite element/Volumetric formulation` (displacement, or mean "
        "dilatation: pressure and dilatation constant per cell and condensed, with "
        "P2 the stable P2–P0 pair; with P1 it would be the displacement formulation "
        "itself, so it runs with P2 only).\n")
    cycles = [m[r["name"]]["cycles"] for r in record if m[r["name"]]["cycles"]]
    periods = f", {min(cycles):.1f} to {max(cycles):.1f} periods" if cycles else ""
    lines.append(
        f"All frequency cases run the same shortened record, `Time integration/End "
        f"time={RECORD:g}` ({RECORD / 0.01:.0f} steps{periods}), with `Output/Write "
        "VTU=false`. The frequencies are the `vertical` row of the program's "
        "`tip_spectrum.csv`: the FFT peak `f_peak_Hz` (interpolated between bins of "
        f"1/T = {1 / (RECORD + 0.01):.3f} Hz) and the damped frequency `f_damped_fit_Hz` "
        "and damping ratio `xi_fit` of the modal fit (a damped sinusoid fitted to the "
        "record). \"change\" is the relative difference of the modal-fit frequency "
        "from the reference of the same κ/μ (marked **ref**): the quadratic elements "
        "in the mean-dilatation formulation on the finest mesh they ran on (medium, "
        "else coarse), the discretisation that does not lock. Newton/step "
        "counts all Newton iterations of the run over its steps; ms/step is the "
        "time loop (the wall time less mesh, set-up and the initial static "
        "equilibrium) per step; wall s is the whole run as the program measures it "
        "(`run_statistics.json`). The machine was shared with other work, so times "
        "are indicative.\n")

    for kappa, by_key in groups:
        reference = reference_of(by_key)
        f_ref = by_key[reference][1]["f_fit"] if reference else None
        lines.append(f"## κ/μ = {kappa_text(kappa)} (κ = {kappa * 116:g} kPa)\n")
        lines.append("| discretisation | cells | dofs | f peak Hz | f fit Hz | change "
                     "| ξ fit | steps | cutbacks | Newton/step (max) | ms/step | wall s "
                     "| finished |")
        lines.append("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|")
        for key, label, _, _ in DISCRETISATIONS:
            if key not in by_key:
                continue
            r, x = by_key[key]
            if key == reference:
                change = "**ref**"
            elif x["f_fit"] and f_ref:
                change = f"{100 * (x['f_fit'] / f_ref - 1):+.1f} %"
            else:
                change = "–"
            newton = "–" if x["newton"] is None else \
                f"{x['newton']:.2f} ({x['newton_max'] if x['newton_max'] is not None else '–'})"
            lines.append(
                f"| {label} | {x['cells'] or '–'} | {x['dofs'] or '–'} | {fmt(x['f_peak'])} "
                f"| {fmt(x['f_fit'])} | {change} | {fmt(x['xi'], 4)} | {x['steps'] or '–'} "
                f"| {x['cutbacks']} | {newton} | {fmt(x['ms_per_step'], 0)} "
                f"| {fmt(x['wall'], 1)} | {status_text(r)} |")
        lines.append("")

    if groups:
        lines.append("## Summary: modal-fit frequency (Hz) by discretisation and κ/μ\n")
        lines.append("The last column is the rise of the frequency from κ/μ = 1e2 to 1e4: "
                     "the stiffening that the bulk modulus adds to a discretisation.\n")
        header = " | ".join(f"κ/μ = {kappa_text(k)}" for k, _ in groups)
        lines.append(f"| discretisation | dofs | {header} | f(1e4) / f(1e2) |")
        lines.append("|---|---:|" + "---:|" * len(groups) + "---:|")
        for key, label, _, _ in DISCRETISATIONS:
            row = [g[1][key][1] if key in g[1] else None for g in groups]
            if not any(row):
                continue
            dofs = next((x["dofs"] for x in row if x and x["dofs"]), None)
            values = [fmt(x["f_fit"]) if x else "–" for x in row]
            first = row[0]["f_fit"] if row[0] else None
            last = row[-1]["f_fit"] if row[-1] and groups[-1][0] == 1e4 else None
            ratio = f"{last / first:.3f}" if first and last and groups[0][0] == 100. else "–"
            lines.append(f"| {label} | {dofs or '–'} | {' | '.join(values)} | {ratio} |")
        lines.append("")

    lines.append("## Figures\n")
    lines.append(f"![frequency against dofs]({FIGURES.replace('doc/', '')}/frequency.png)\n")
    lines.append(f"![frequency against kappa]({FIGURES.replace('doc/', '')}/"
                 "frequency_against_kappa.png)\n")

    full = by_name.get("p1_coarse_k1e2_full")
    short = by_name.get("p1_coarse_k1e2")
    if full and short:
        a, b = m[short["name"]], m[full["name"]]
        lines.append("## The shortened record against the full one\n")
        lines.append(f"P1 coarse, κ/μ = 1e2 (the scene's linear tetrahedra, restored by "
                     f"`tetrahedral_defaults`), with the study's "
                     f"{RECORD:g} s and the scene's {FULL:g} s. \"difference\" is "
                     f"{RECORD:g} s against {FULL:g} s.\n")
        lines.append("| record | cycles | bin 1/T Hz | f peak Hz | f fit Hz | ξ fit | wall s |")
        lines.append("|---|---:|---:|---:|---:|---:|---:|")
        for label, x in ((f"{RECORD:g} s", a), (f"{FULL:g} s", b)):
            lines.append(f"| {label} | {fmt(x['cycles'], 1)} | {fmt(x['resolution'])} "
                         f"| {x['f_peak']:.5f} | {x['f_fit']:.5f} | {fmt(x['xi'], 5)} "
                         f"| {fmt(x['wall'], 1)} |" if x["f_fit"] else f"| {label} |" + " – |" * 6)
        if a["f_fit"] and b["f_fit"]:
            lines.append(
                f"| difference | | | {a['f_peak'] - b['f_peak']:+.5f} "
                f"({100 * (a['f_peak'] / b['f_peak'] - 1):+.3f} %) "
                f"| {a['f_fit'] - b['f_fit']:+.5f} ({100 * (a['f_fit'] / b['f_fit'] - 1):+.3f} %) "
                f"| {a['xi'] - b['xi']:+.5f} ({100 * (a['xi'] / b['xi'] - 1):+.1f} %) | |")
        lines.append("")

    volume = [r for r in record if r.get("volume_change")]
    if volume:
        lines.append("## Does the κ/μ override take effect?\n")
        lines.append("The log prints each material's shear modulus only. The P1 coarse "
                     "cases also wrote their initial state (the static equilibrium "
                     "under gravity and the hold) as VTU; from it the volume-weighted "
                     "mean of |1 − J| per material, with J from the displacements of "
                     "each tetrahedron. A larger κ of the silicone must make the "
                     "silicone's value smaller; the tip block's κ is not changed.\n")
        lines.append("| case | mean \\|1 − J\\| silicone | ratio to κ/μ = 1e2 | mean "
                     "\\|1 − J\\| tip block | printed material data |")
        lines.append("|---|---:|---:|---:|---|")
        base = next((r for r in volume if r["kappa"] == 100.), None)
        for r in volume:
            v = r["volume_change"]
            ratio = f"{base['volume_change']['silicone'] / v['silicone']:.1f}" if base else "–"
            lines.append(f"| {r['name']} | {v['silicone']:.3e} | {ratio} | {v['block']:.3e} "
                         f"| {'<br>'.join(r['materials'])} |")
        lines.append("")

    lines.append("## The cases in detail\n")
    lines.append("Every run also gets `Output/Progress interval=0` and `Output/Write "
                 "VTU=false` (the P1 coarse cases of the study's record instead "
                 "`Output/Write VTU=true` with `Output/Output interval=1e9`: the "
                 "initial state only, read and deleted by the script).\n")
    for r in results:
        sets = " ".join(f"`--set '{entry}'`" for entry in r["overrides"])
        reasons = "; ".join(f"{k} ({v})" for k, v in r["cutback_reasons"].items())
        extra = f" Cutbacks: {reasons}." if reasons else ""
        spectrum = r.get("spectrum") or {}
        if spectrum.get("warnings"):
            extra += f" Spectral analysis: {spectrum['warnings']}"
        lines.append(f"- **{r['name']}**: {sets}.{extra}")
        if r["status"] != "finished":
            lines.append("  Last lines of its output:\n")
            lines.append("  ```")
            lines += [f"  {line}" for line in r["log_tail"]]
            lines.append("  ```")
    lines.append("")

    write_with_discussion_link(path, lines, "locking_discussion.md")


def main():
    by_name = {case[0]: case for case in CASES}
    study_main(__doc__, "doc/locking/run_locking.py", "output/locking", "doc/locking.md",
               RUN_ORDER,
               lambda build, output_root, name, timeout, threads: run_case(
                   build, output_root, by_name[name], timeout, threads),
               load_case,
               # the report lists the cases in the order of CASES, not of the runs
               lambda path, results, session: write_report(
                   path, sorted(results, key=lambda r: CASE_NAMES.index(r["name"])),
                   session))


if __name__ == "__main__":
    main()
