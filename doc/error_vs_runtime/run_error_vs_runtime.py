#!/usr/bin/python3
"""Error against run time (issue 6): experiment 1 (vertical oscillation,
Dragon Skin 20, baseline parameter set) with the 3D quarter model and the
reduced 1D column, over meshes, element degrees, volumetric formulations and
time steps. Each point is one run of the Release build of soft-robot with
its wall time; the errors of the tip frequency, the damping ratio and the
tip trajectory are measured against a fine reference solution. Writes
doc/error-vs-runtime.md and its figures in doc/figures/error_vs_runtime/.

    /usr/bin/python3 doc/error_vs_runtime/run_error_vs_runtime.py build-release
        [--cases a,b] [--timeout 1800] [--threads 1] [--report-only]

The record. Every case runs `Time integration/End time = 2.5` (about six
to nine periods) without VTU output, as the locking study does
(doc/locking/run_locking.py). Its cases at kappa/mu = 100 (the scene's own
value) at dt = 0.01 s are the 3D spatial series here: the script reads them
from that study's output directory (output/locking) instead of running them
again; the report names the commit and date of those runs. The others run
here.

The reference. The 3D reference is the discretisation that neither locks
nor is coarse: quadratic tetrahedra in the mean-dilatation formulation on
the medium mesh (`p2md_medium`, dt = 0.01 s). Its own errors are estimated
from the series: the time-step error from the dt series of the
mean-dilatation P2 coarse model, the mesh error from its coarse-to-medium
change. The 1D column is measured twice: against the 3D reference (the
error a user of the reduced model gets) and against its own finest run (P2,
mesh refined twice, dt = 0.00125 s), which separates its discretisation
error from its model error.

The errors.
- frequency: the modal-fit damped frequency of the vertical tip motion
  (`f_damped_fit_Hz` of tip_spectrum.csv), relative to the reference's;
- damping: the modal-fit damping ratio `xi_fit`, relative;
- trajectory: the root mean square over the record of u_x(t) - u_x,ref(t)
  (the tip's vertical displacement, linearly interpolated to the
  reference's output times), divided by the root mean square of the
  reference's oscillation about its mean.

Nothing here is a test: the numbers are reported, not checked.
"""

import argparse
import csv
import json
import math
import os
import shutil
import sys
import time
from pathlib import Path

import numpy as np
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

REPOSITORY = Path(__file__).resolve().parents[2]
FIGURES = "doc/figures/error_vs_runtime"
sys.path.insert(0, str(REPOSITORY / "doc" / "performance"))
sys.path.insert(0, str(REPOSITORY / "doc" / "stability"))
from run_benchmarks import (commit, machine_description,  # noqa: E402
                            write_with_discussion)
from run_stability import read_trajectory, run_program  # noqa: E402

SCENE_3D = "parameters/bellows/vertical_ds20_3d.prm"
SCENE_1D = "parameters/bellows/column_ds20_1d.prm"
MESHES = "../../meshes/bellows_quarter"  # relative to the scene's directory
RECORD = 2.5
QUIET = ["Output/Progress interval=0", "Output/Write VTU=false",
         f"Time integration/End time={RECORD:g}"]
P2 = ["Finite element/Polynomial degree=2"]
P1 = ["Finite element/Polynomial degree=1"]
MD = ["Finite element/Volumetric formulation=mean dilatation"]
MEDIUM = [f"Geometry/Mesh file={MESHES}_medium.msh"]
FINE = [f"Geometry/Mesh file={MESHES}_fine.msh"]


def dt_entry(dt):
    return [f"Time integration/Time step={dt:g}"]


# name, model ("3D" or "1D"), family (one line in the figures), label,
# scene, overrides, dt, source ("run", or "locking:<case>" for a case of the
# locking study).
CASES = []
for key, label, source in (
        ("p1_coarse", "P1 coarse", "p1_coarse_k1e2"),
        ("p1_medium", "P1 medium", "p1_medium_k1e2"),
        ("p1_fine", "P1 fine", "p1_fine_k1e2"),
        ("p1_refined", "P1 coarse refined once", "p1_refined_k1e2"),
        ("p2_coarse", "P2 coarse", "p2_coarse_k1e2"),
        ("p2_medium", "P2 medium", "p2_medium_k1e2"),
        ("p2md_coarse", "P2 mean dilatation coarse", "p2md_coarse_k1e2"),
        ("p2md_medium", "P2 mean dilatation medium", "p2md_medium_k1e2")):
    family = ("3D P1" if key.startswith("p1") else
              "3D P2 mean dilatation" if key.startswith("p2md") else "3D P2")
    CASES.append((f"{key}_dt0.01", "3D", family, f"{label}, dt = 0.01",
                  SCENE_3D, [], 0.01, f"locking:{source}"))
for dt in (0.02, 0.005, 0.0025, 0.00125):
    CASES.append((f"p1_coarse_dt{dt:g}", "3D", "3D P1 coarse, dt series",
                  f"P1 coarse, dt = {dt:g}", SCENE_3D, dt_entry(dt), dt, "run"))
for dt in (0.02, 0.005, 0.0025):
    CASES.append((f"p2md_coarse_dt{dt:g}", "3D", "3D P2 mean dilatation coarse, dt series",
                  f"P2 mean dilatation coarse, dt = {dt:g}", SCENE_3D,
                  P2 + MD + dt_entry(dt), dt, "run"))
for degree, entries in ((1, P1), (2, P2)):
    for refinements in (0, 1, 2):
        for dt in ((0.02, 0.01, 0.005, 0.0025, 0.00125) if (degree, refinements) == (2, 0)
                   else (0.01,) if (degree, refinements) != (2, 2) else (0.01, 0.00125)):
            CASES.append((f"column_p{degree}_r{refinements}_dt{dt:g}", "1D",
                          f"1D column P{degree}" + (
                              ", dt series" if (degree, refinements) == (2, 0)
                              and dt != 0.01 else ", reference run" if dt != 0.01
                              else ""),
                          f"1D column P{degree}, {22 * 2 ** refinements} cells, dt = {dt:g}",
                          SCENE_1D,
                          entries + [f"Geometry/Global refinements={refinements}"]
                          + dt_entry(dt), dt, "run"))
# The 1D column with its section computed from the 3D model that does not
# lock: `calibrate reduced-models` run on the quarter and half scenes with
# `Finite element/Polynomial degree = 2` and `Volumetric formulation = mean
# dilatation` (coarse meshes; see the report) gave 16.945 mm^2 instead of
# the scenes' 29.436 mm^2 (which comes from the linear tetrahedra).
P2MD_SECTION = 16.945
for dt in (0.01, 0.0025):
    CASES.append((f"column_p2md_section_dt{dt:g}", "1D",
                  "1D column, section from 3D P2 mean dilatation",
                  f"1D column P2, section from 3D P2 mean dilatation, dt = {dt:g}",
                  SCENE_1D,
                  [f"Material 1/Section={P2MD_SECTION}", f"Material 2/Section={P2MD_SECTION}",
                   f"Loads and constraints/Function constants=force=958.4, "
                   f"section={P2MD_SECTION}"] + dt_entry(dt), dt, "run"))
CASE_NAMES = [c[0] for c in CASES]
REFERENCE_3D = "p2md_medium_dt0.01"
REFERENCE_1D = "column_p2_r2_dt0.00125"


def read_spectrum(output):
    path = output / "tip_spectrum.csv"
    if not path.exists():
        return None
    with open(path) as file:
        for row in csv.DictReader(file):
            if row["direction"] == "vertical":
                return {k: float(row[k]) if row[k] else None
                        for k in ("f_damped_fit_Hz", "xi_fit", "f_peak_Hz")}
    return None


def collect(name, output, run_result):
    """What the report needs of one run: its status, wall time, dofs,
    spectrum and tip trajectory (t, u_x)."""
    result = dict(run_result)
    result["name"] = name
    statistics = output / "run_statistics.json"
    if statistics.exists():
        s = json.loads(statistics.read_text())
        result["wall"] = s["wall_seconds"]
        result["dofs"] = s["dofs"]
        result["steps"] = s["steps"]
        result["newton"] = s["newton_iterations"]
    result["spectrum"] = read_spectrum(output)
    trajectory = output / "tip_trajectory.csv"
    if trajectory.exists():
        d, finite = read_trajectory(trajectory)
        result["finite"] = finite
        result["t"] = d["t"].tolist()
        result["u_x"] = d["u_x"].tolist()
    return result


def run_case(build, output_root, case, timeout, threads):
    name, model, family, label, scene, overrides, dt, source = case
    output = output_root / name
    if output.exists():
        shutil.rmtree(output)
    output.mkdir(parents=True)
    if source.startswith("locking:"):
        # a case of the locking study: its output is read, not run again
        locking = REPOSITORY / "output" / "locking" / source.split(":", 1)[1]
        if not (locking / "result.json").exists():
            sys.exit(f"{locking} has no result: run doc/locking/run_locking.py first")
        previous = json.loads((locking / "result.json").read_text())
        result = collect(name, locking, {k: previous[k] for k in
                                         ("status", "exit_code", "measured_seconds")})
        result["from"] = f"the locking study's case {source.split(':', 1)[1]}"
    else:
        command = [str(build / "soft-robot"), scene,
                   "--set", f"Problem/Output directory={output}"]
        for entry in QUIET + overrides:
            command += ["--set", entry]
        environment = dict(os.environ, OMP_NUM_THREADS="1",
                           DEAL_II_NUM_THREADS=str(threads))
        print(f"[{name}] {label}", flush=True)
        _, outcome = run_program(command, environment, output, timeout)
        result = collect(name, output, outcome)
        result["from"] = "this study"
    result.update({"model": model, "family": family, "label": label, "dt": dt,
                   "overrides": overrides})
    (output / "result.json").write_text(json.dumps(result))
    f = (result.get("spectrum") or {}).get("f_damped_fit_Hz")
    print(f"    {result['status']} in {result.get('wall', float('nan')):.1f} s, "
          f"{result.get('dofs')} dofs, f fit = {f}", flush=True)
    return result


def load_case(output_root, name):
    """A stored result, with the description of its case as the script
    defines it now."""
    path = output_root / name / "result.json"
    if not path.exists():
        return None
    result = json.loads(path.read_text())
    case = next(c for c in CASES if c[0] == name)
    result.update({"model": case[1], "family": case[2], "label": case[3]})
    return result


# @sect{Errors}

def errors_against(result, reference):
    """Relative errors of frequency, damping ratio and trajectory."""
    if not result or not reference or result["status"] != "finished":
        return None
    s, r = result.get("spectrum"), reference.get("spectrum")
    if not s or not r or not s["f_damped_fit_Hz"] or not r["f_damped_fit_Hz"]:
        return None
    t_ref, u_ref = np.array(reference["t"]), np.array(reference["u_x"])
    u = np.interp(t_ref, np.array(result["t"]), np.array(result["u_x"]))
    oscillation = math.sqrt(np.mean((u_ref - u_ref.mean()) ** 2))
    return {"frequency": s["f_damped_fit_Hz"] / r["f_damped_fit_Hz"] - 1.,
            "damping": s["xi_fit"] / r["xi_fit"] - 1.,
            "trajectory": math.sqrt(np.mean((u - u_ref) ** 2)) / oscillation}


FAMILY_STYLE = {
    "3D P1": ("tab:blue", "-o"),
    "3D P2": ("tab:orange", "-*"),
    "3D P2 mean dilatation": ("tab:red", "-D"),
    "3D P1 coarse, dt series": ("tab:blue", ":s"),
    "3D P2 mean dilatation coarse, dt series": ("tab:red", ":v"),
    "1D column P1": ("tab:green", "-^"),
    "1D column P2": ("tab:purple", "-^"),
    "1D column P2, dt series": ("tab:purple", ":x"),
    "1D column P2, reference run": ("tab:purple", "s"),
    "1D column, section from 3D P2 mean dilatation": ("tab:brown", "-P"),
}


# A time-step series also shows the run of its discretisation at the
# scenes' dt = 0.01 s, which belongs to the spatial series.
SERIES_ALSO = {"3D P1 coarse, dt series": "p1_coarse_dt0.01",
               "3D P2 mean dilatation coarse, dt series": "p2md_coarse_dt0.01",
               "1D column P2, dt series": "column_p2_r0_dt0.01"}



def family_points(results, errors, measure, reference):
    """Per family the (wall time, |error|, run) points, without the
    reference run itself."""
    by_family = {}
    by_name = {r["name"]: r for r in results}
    for r in results:
        e = errors.get(r["name"])
        if e is None or not r.get("wall") or r["name"] == reference:
            continue
        by_family.setdefault(r["family"], []).append((r["wall"], abs(e[measure]), r))
    for family, name in SERIES_ALSO.items():
        if family in by_family and errors.get(name) and by_name[name].get("wall"):
            by_family[family].append((by_name[name]["wall"],
                                      abs(errors[name][measure]), by_name[name]))
    for points in by_family.values():
        points.sort(key=lambda p: p[0])
    return by_family


def plot_work_precision(results, errors, path, title, reference):
    figure, axes = plt.subplots(1, 3, figsize=(16, 5.2))
    for ax, measure, name in zip(axes, ("frequency", "damping", "trajectory"),
                                 ("tip frequency", "damping ratio ξ", "tip trajectory u_x(t)")):
        for family, points in family_points(results, errors, measure, reference).items():
            color, style = FAMILY_STYLE.get(family, ("k", "-o"))
            walls = [p[0] for p in points]
            values = [max(p[1], 1e-6) for p in points]
            ax.plot(walls, values, style, color=color, ms=6, label=family,
                    mfc="none" if ":" in style else color)
        if measure == "frequency":
            ax.axhline(0.01, color="k", lw=0.8, ls="--")
            ax.annotate("1 %", (0.01, 0.01), xycoords=("axes fraction", "data"),
                        xytext=(2, 2), textcoords="offset points", fontsize=8)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("wall time of the run (s, one thread)")
        ax.set_ylabel(f"relative error of the {name}")
        ax.grid(alpha=0.3, which="both")
    handles, labels = axes[0].get_legend_handles_labels()
    figure.legend(handles, labels, fontsize=8, ncol=4, loc="lower center")
    figure.suptitle(title, fontsize=10)
    figure.tight_layout(rect=(0, 0.1, 1, 0.95))
    figure.savefig(path, dpi=110)
    plt.close(figure)


def fmt_error(value):
    return "–" if value is None else f"{100 * value:+.2f} %"


def write_report(path, results, session):
    figures = REPOSITORY / FIGURES
    figures.mkdir(parents=True, exist_ok=True)
    by_name = {r["name"]: r for r in results}
    reference_3d, reference_1d = by_name.get(REFERENCE_3D), by_name.get(REFERENCE_1D)
    errors = {r["name"]: errors_against(r, reference_3d) for r in results}
    errors_1d = {r["name"]: errors_against(r, reference_1d) for r in results
                 if r["model"] == "1D" and "p2md_section" not in r["name"]}
    plot_work_precision(results, errors, figures / "against_3d_reference.png",
                        "Experiment 1, Dragon Skin 20: error against the 3D reference "
                        "(P2 mean dilatation, medium mesh, dt = 0.01 s) and wall time; "
                        "errors below 1e-6 are drawn at 1e-6", REFERENCE_3D)
    plot_work_precision([r for r in results if r["name"] in errors_1d], errors_1d,
                        figures / "column_against_own_reference.png",
                        "The 1D column against its own finest run (P2, 88 cells, "
                        "dt = 0.00125 s): its discretisation error alone; errors below "
                        "1e-6 are drawn at 1e-6", REFERENCE_1D)

    lines = ["<!-- Written by doc/error_vs_runtime/run_error_vs_runtime.py; the "
             "discussion is in doc/error-vs-runtime_discussion.md. -->",
             "# Error against run time: experiment 1\n"]
    for run in session["runs"]:
        lines.append(f"- `{run['command']}`: commit `{run['commit']}`, {run['date']}, "
                     f"{run['total_seconds']:.0f} s; {run['machine']}; load average at "
                     f"the start {run['load']}; the program ran with {run['threads']} "
                     "thread(s), one case at a time")
    locking = REPOSITORY / "output" / "locking" / "locking_run.json"
    if locking.exists():
        for run in json.loads(locking.read_text()).get("runs", []):
            lines.append(f"- the dt = 0.01 s 3D cases come from the locking study: "
                         f"`{run['command']}`, commit `{run['commit']}`, {run['date']}")
    lines.append("")
    lines.append(
        f"Scenes: `{SCENE_3D}` (the quarter model) and `{SCENE_1D}` (the reduced "
        f"column), both Dragon Skin 20 with the baseline moduli (μ = C1, κ = 100 μ), "
        f"HHT α = −0.25, each with `Time integration/End time={RECORD:g}` and without "
        "VTU output. Errors are relative; the frequency and damping ratio are the "
        "modal fit of the vertical tip motion, the trajectory error is the RMS of "
        "the difference of the tip's vertical displacement over the record divided "
        "by the RMS of the reference's oscillation. Wall times are the program's "
        "own (`run_statistics.json`), one thread, on a machine shared with other "
        "work: indicative to some ten percent.\n")
    if reference_3d and reference_3d.get("spectrum"):
        s = reference_3d["spectrum"]
        lines.append(f"**3D reference** (`{REFERENCE_3D}`): f = "
                     f"{s['f_damped_fit_Hz']:.4f} Hz, ξ = {s['xi_fit']:.5f}, "
                     f"{reference_3d.get('dofs')} dofs, {reference_3d.get('wall', 0):.0f} s.\n")
    lines.append(
        f"The 1D column's section in the scene (29.436 mm²) was computed by "
        "`calibrate reduced-models` from the 3D model with linear tetrahedra. The "
        f"cases \"section from 3D P2 mean dilatation\" use {P2MD_SECTION} mm², which the "
        "same command computes from the 3D scenes set to `Polynomial degree = 2` and "
        "`Volumetric formulation = mean dilatation` (coarse quarter and half meshes; "
        "52 s). Nothing in either section is fitted to a frequency.\n")
    lines.append("## All runs against the 3D reference\n")
    lines.append("| case | model | dofs | dt s | wall s | f fit Hz | ξ fit | error f "
                 "| error ξ | error trajectory | from |")
    lines.append("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---|")
    for r in results:
        s = r.get("spectrum") or {}
        e = errors.get(r["name"]) or {}
        wall = f"{r['wall']:.1f}" if r.get("wall") else "–"
        f = f"{s['f_damped_fit_Hz']:.4f}" if s.get("f_damped_fit_Hz") else "–"
        xi = f"{s['xi_fit']:.5f}" if s.get("xi_fit") else "–"
        status = "" if r["status"] == "finished" else f" **{r['status']}**"
        lines.append(f"| {r['label']}{status} | {r['model']} | {r.get('dofs', '–')} "
                     f"| {r['dt']:g} | {wall} | {f} | {xi} | {fmt_error(e.get('frequency'))} "
                     f"| {fmt_error(e.get('damping'))} | {fmt_error(e.get('trajectory'))} "
                     f"| {r.get('from', '')} |")
    lines.append("")

    within = [(r["wall"], r) for r in results if errors.get(r["name"]) and r.get("wall")
              and abs(errors[r["name"]]["frequency"]) <= 0.01
              and r["name"] != REFERENCE_3D]
    lines.append("## Which model reaches 1 % frequency error fastest\n")
    if within:
        wall, best = min(within, key=lambda p: p[0])
        lines.append(f"Against the 3D reference, the cheapest run within 1 % of its "
                     f"frequency is **{best['label']}** ({best['model']}): "
                     f"{100 * errors[best['name']]['frequency']:+.2f} % in {wall:.1f} s. "
                     "All runs within 1 %: " + ", ".join(
                         f"{r['label']} ({w:.1f} s)" for w, r in sorted(within, key=lambda p: p[0]))
                     + ".\n")
    else:
        lines.append("No run other than the reference is within 1 % of the 3D "
                     "reference's frequency.\n")
    own = [(r["wall"], r) for r in results if errors_1d.get(r["name"]) and r.get("wall")
           and abs(errors_1d[r["name"]]["frequency"]) <= 0.01 and r["name"] != REFERENCE_1D]
    if own:
        wall, best = min(own, key=lambda p: p[0])
        lines.append(f"Against its own finest run, the 1D column is within 1 % already "
                     f"with **{best['label']}** ({wall:.2f} s).\n")

    lines.append("## The 1D column against its own finest run\n")
    if reference_1d and reference_1d.get("spectrum"):
        s = reference_1d["spectrum"]
        lines.append(f"Reference `{REFERENCE_1D}`: f = {s['f_damped_fit_Hz']:.4f} Hz, "
                     f"ξ = {s['xi_fit']:.5f}.\n")
    lines.append("| case | dofs | dt s | wall s | error f | error ξ | error trajectory |")
    lines.append("|---|---:|---:|---:|---:|---:|---:|")
    for r in results:
        if r["name"] not in errors_1d:
            continue
        e = errors_1d.get(r["name"]) or {}
        lines.append(f"| {r['label']} | {r.get('dofs', '–')} | {r['dt']:g} "
                     f"| {r.get('wall', 0):.2f} | {fmt_error(e.get('frequency'))} "
                     f"| {fmt_error(e.get('damping'))} | {fmt_error(e.get('trajectory'))} |")
    lines.append("")
    lines.append("## Figures\n")
    lines.append("![against the 3D reference](figures/error_vs_runtime/"
                 "against_3d_reference.png)\n")
    lines.append("![the column against its own reference](figures/error_vs_runtime/"
                 "column_against_own_reference.png)\n")
    write_with_discussion(path, lines, "error-vs-runtime_discussion.md")


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("build", help="the Release build directory (with soft-robot)")
    parser.add_argument("--cases", help="comma-separated case names (default: all)")
    parser.add_argument("--output", default="output/error_vs_runtime")
    parser.add_argument("--report", default="doc/error-vs-runtime.md")
    parser.add_argument("--timeout", type=float, default=1800.)
    parser.add_argument("--threads", type=int, default=1)
    parser.add_argument("--report-only", action="store_true")
    arguments = parser.parse_args()

    build = Path(arguments.build).resolve()
    output_root = (REPOSITORY / arguments.output).resolve()
    output_root.mkdir(parents=True, exist_ok=True)
    selected = CASE_NAMES
    if arguments.cases:
        selected = arguments.cases.split(",")
        unknown = set(selected) - set(CASE_NAMES)
        if unknown:
            sys.exit(f"unknown case(s): {', '.join(sorted(unknown))}; "
                     f"known: {', '.join(CASE_NAMES)}")
    session_path = output_root / "error_vs_runtime_run.json"
    session = json.loads(session_path.read_text()) if session_path.exists() else {"runs": []}
    if not arguments.report_only:
        if not (build / "soft-robot").exists():
            sys.exit(f"{build / 'soft-robot'} does not exist: build in Release first")
        try:
            shown = str(build.relative_to(REPOSITORY))
        except ValueError:
            shown = "<Release build directory>"
        run = {"command": f"/usr/bin/python3 doc/error_vs_runtime/run_error_vs_runtime.py "
                          f"{shown}" + (f" --cases {arguments.cases}" if arguments.cases else ""),
               "commit": commit(), "machine": machine_description(),
               "load": ", ".join(f"{x:.2f}" for x in os.getloadavg()),
               "date": time.strftime("%Y-%m-%d"), "threads": arguments.threads}
        start = time.perf_counter()
        by_name = {c[0]: c for c in CASES}
        for name in selected:
            run_case(build, output_root, by_name[name], arguments.timeout, arguments.threads)
        run["total_seconds"] = time.perf_counter() - start
        session["runs"] = (session["runs"] if arguments.cases else []) + [run]
        session_path.write_text(json.dumps(session, indent=1) + "\n")
    results = [r for r in (load_case(output_root, n) for n in CASE_NAMES) if r]
    write_report(REPOSITORY / arguments.report, results, session)


if __name__ == "__main__":
    main()
