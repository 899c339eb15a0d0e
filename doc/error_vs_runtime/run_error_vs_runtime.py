#!/usr/bin/python3
# SPDX-License-Identifier: LGPL-2.1-or-later
"""Error against run time (issue 6): the three experiments with Dragon Skin
20 (baseline parameter set) over meshes, element degrees, volumetric
formulations and time steps, with the 3D models and the reduced ones (the
1D column for experiment 1, the 2D strip for experiment 2). Each point is
one run of the Release build of soft-robot with its wall time; the errors
of the tip frequency, the damping ratio and the tip trajectory are measured
against a fine reference solution of the same experiment, and the reduced
models also against their own finest run. Writes doc/error-vs-runtime.md
and its figures in doc/figures/error_vs_runtime/.

    /usr/bin/python3 doc/error_vs_runtime/run_error_vs_runtime.py build-release
        [--cases a,b] [--timeout 1800] [--threads 1] [--report-only]

The record. Every case of experiment 1 runs `Time integration/End time =
2.5` (about six to nine periods), those of experiments 2 and 3 `End time =
4` (about six swings), without VTU output; experiment 1 as the locking
study does
(doc/locking/run_locking.py). Its cases at kappa/mu = 100 (the scene's own
value) at dt = 0.01 s are the 3D spatial series here: the script reads them
from that study's output directory (output/locking) instead of running them
again; the report names the commit and date of those runs. The others run
here.

The reference. The 3D reference of experiment 1 is the discretisation
that neither locks nor is coarse: quadratic tetrahedra in the
mean-dilatation formulation on the medium mesh (`p2md_medium`, dt = 0.01
s). For experiments 2 and 3 it is the same discretisation on the medium
half and full meshes (the coarse-mesh run where the medium one has not
finished). Its own errors are estimated from the series: the time-step
error from the dt series of the mean-dilatation P2 coarse model, the mesh
error from its coarse-to-medium change. The 1D column is measured twice: against the 3D reference (the
error a user of the reduced model gets) and against its own finest run (P2,
mesh refined twice, dt = 0.00125 s), which separates its discretisation
error from its model error.

The errors.
- frequency: the modal-fit damped frequency of the vertical tip motion
  (experiment 1) or of the swing (the `horizontal` direction, experiments
  2 and 3) (`f_damped_fit_Hz` of tip_spectrum.csv), relative to the
  reference's;
- damping: the modal-fit damping ratio `xi_fit`, relative;
- trajectory: the root mean square over the record of u(t) - u_ref(t) (the
  tip's vertical displacement u_x in experiment 1, its displacement vector
  in the components both runs have in experiments 2 and 3, linearly
  interpolated to the reference's output times), divided by the root mean
  square of the reference's oscillation about its mean.

Nothing here is a test: the numbers are reported, not checked.
"""

import csv
import json
import math
import os
import shutil
import sys
from pathlib import Path

import numpy as np
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

REPOSITORY = Path(__file__).resolve().parents[2]
FIGURES = "doc/figures/error_vs_runtime"
sys.path.insert(0, str(REPOSITORY / "doc" / "performance"))
sys.path.insert(0, str(REPOSITORY / "doc" / "stability"))
sys.path.insert(0, str(REPOSITORY / "doc"))
from run_benchmarks import write_with_discussion_link  # noqa: E402
from study_session import run_lines, study_main, tetrahedral_defaults  # noqa: E402
from run_stability import read_trajectory, run_program  # noqa: E402

SCENE_3D = "parameters/bellows/vertical_ds20_3d.prm"
SCENE_1D = "parameters/bellows/column_ds20_1d.prm"
MESHES = "../../meshes/bellows_quarter"  # relative to the scene's directory
SCENE_PLANAR_3D = "parameters/bellows/planar_ds20_3d.prm"
SCENE_PLANAR_2D = "parameters/bellows/planar_ds20_2d.prm"
SCENE_SPHERICAL_3D = "parameters/bellows/spherical_ds20_3d.prm"
RECORD = 2.5         # s, experiment 1 (as the locking study)
RECORD_SWING = 4.0   # s, experiments 2 and 3 (about six swings)
QUIET = ["Output/Progress interval=0", "Output/Write VTU=false"]


def record_of(name):
    return RECORD_SWING if experiment_of(name) != "1" else RECORD


def experiment_of(name):
    """Experiment 1 (vertical), 2 (planar pendulum) or 3 (spherical)."""
    return ("2" if name.startswith("planar") else
            "3" if name.startswith("spherical") else "1")
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
# Experiments 2 and 3: the 3D half and full models with linear tetrahedra
# (the scenes', restored by tetrahedral_defaults) and with quadratic ones in
# the mean-dilatation formulation on the same coarse meshes and on the
# medium ones (the references), and the reduced 2D strip of experiment 2.
for scene, experiment in ((SCENE_PLANAR_3D, "planar"), (SCENE_SPHERICAL_3D, "spherical")):
    CASES.append((f"{experiment}_p1_coarse_dt0.01", "3D", "3D P1",
                  "P1 coarse, dt = 0.01", scene, [], 0.01, "run"))
    CASES.append((f"{experiment}_p2md_coarse_dt0.01", "3D", "3D P2 mean dilatation",
                  "P2 mean dilatation coarse, dt = 0.01", scene, P2 + MD, 0.01, "run"))
    for dt in (0.02, 0.005, 0.0025):
        CASES.append((f"{experiment}_p1_coarse_dt{dt:g}", "3D", "3D P1 coarse, dt series",
                      f"P1 coarse, dt = {dt:g}", scene, dt_entry(dt), dt, "run"))
    # The reference discretisation's own time-step series (for the full
    # model without dt = 0.005 s, which would take over half an hour more).
    for dt in (0.02, 0.005) if experiment == "planar" else (0.02,):
        CASES.append((f"{experiment}_p2md_coarse_dt{dt:g}", "3D",
                      "3D P2 mean dilatation coarse, dt series",
                      f"P2 mean dilatation coarse, dt = {dt:g}", scene,
                      P2 + MD + dt_entry(dt), dt, "run"))
# The pendulums' reference discretisation on the medium half and full
# meshes (35,238 and 62,208 unknowns; about 20 and 60 minutes on one core),
# the full model with the multifrontal direct solver, which factorizes
# matrices of this size twice as fast as KLU.
for scene, experiment, mesh, solver in ((SCENE_PLANAR_3D, "planar", "half", []),
                                        (SCENE_SPHERICAL_3D, "spherical", "full",
                                         ["Linear solver/Direct solver=MUMPS"])):
    CASES.append((f"{experiment}_p2md_medium_dt0.01", "3D", "3D P2 mean dilatation",
                  "P2 mean dilatation medium, dt = 0.01", scene,
                  P2 + MD + [f"Geometry/Mesh file=../../meshes/bellows_{mesh}_medium.msh"]
                  + solver, 0.01, "run"))
for degree, refinements, dt in ((1, 0, 0.01), (2, 0, 0.02), (2, 0, 0.01), (2, 0, 0.005),
                                (2, 0, 0.0025), (2, 0, 0.00125), (2, 1, 0.01)):
    CASES.append((f"planar_2d_p{degree}_r{refinements}_dt{dt:g}", "2D",
                  f"2D strip P{degree}" + (", dt series" if (degree, refinements) == (2, 0)
                                           and dt != 0.01 else ""),
                  f"2D strip P{degree}, {88 * 4 ** refinements} cells, dt = {dt:g}",
                  SCENE_PLANAR_2D, [f"Finite element/Polynomial degree={degree}",
                                    f"Geometry/Global refinements={refinements}"]
                  + dt_entry(dt), dt, "run"))
# The 2D strip with the width and thickness that `calibrate reduced-models`
# computes from the P2 mean-dilatation 3D models (same run as the column's
# section above).
P2MD_STRIP = ["Geometry/Generator arguments=" + ",".join(["5.225"] * 20) + ",5,5; "
              + ",".join(["6.35625"] * 4) + ": -15.25, -12.7125: 99.25, 12.7125: true",
              "Material 1/Section=0.66071", "Material 2/Section=0.66071",
              "Loads and constraints/Function constants=force=958.4, end_area=16.799"]
CASES.append(("planar_2d_p2md_geometry_dt0.01", "2D",
              "2D strip, geometry from 3D P2 mean dilatation",
              "2D strip P2, geometry from 3D P2 mean dilatation, dt = 0.01",
              SCENE_PLANAR_2D, P2MD_STRIP + dt_entry(0.01), 0.01, "run"))
CASE_NAMES = [c[0] for c in CASES]
# The reference of each experiment: the first of these that has finished.
REFERENCES = {"1": ["p2md_medium_dt0.01"],
              "2": ["planar_p2md_medium_dt0.01", "planar_p2md_coarse_dt0.01"],
              "3": ["spherical_p2md_medium_dt0.01", "spherical_p2md_coarse_dt0.01"]}
REFERENCE_TEXT = {
    "p2md_medium_dt0.01": "quadratic tetrahedra in the mean-dilatation formulation "
                          "on the medium quarter mesh",
    "planar_p2md_medium_dt0.01": "quadratic tetrahedra in the mean-dilatation "
                                 "formulation on the medium half mesh",
    "planar_p2md_coarse_dt0.01": "quadratic tetrahedra in the mean-dilatation "
                                 "formulation on the coarse half mesh (the medium-mesh "
                                 "run has not finished)",
    "spherical_p2md_medium_dt0.01": "quadratic tetrahedra in the mean-dilatation "
                                    "formulation on the medium full mesh",
    "spherical_p2md_coarse_dt0.01": "quadratic tetrahedra in the mean-dilatation "
                                    "formulation on the coarse full mesh (the medium-mesh "
                                    "run has not finished)"}


def reference_of(key, by_name):
    """The name of the experiment's reference run."""
    for name in REFERENCES[key]:
        result = by_name.get(name)
        if result and result.get("status") == "finished" and result.get("spectrum"):
            return name
    return REFERENCES[key][-1]


def read_spectrum(output, direction):
    path = output / "tip_spectrum.csv"
    if not path.exists():
        return None
    with open(path) as file:
        for row in csv.DictReader(file):
            if row["direction"] == direction:
                return {k: float(row[k]) if row[k] else None
                        for k in ("f_damped_fit_Hz", "xi_fit", "f_peak_Hz")}
    return None


def collect(name, output, run_result):
    """What the report needs of one run: its status, wall time, dofs,
    spectrum, and whether its tip trajectory is finite."""
    result = dict(run_result)
    result["name"] = name
    statistics = output / "run_statistics.json"
    if statistics.exists():
        s = json.loads(statistics.read_text())
        result["wall"] = s["wall_seconds"]
        result["dofs"] = s["dofs"]
        result["steps"] = s["steps"]
        result["newton"] = s["newton_iterations"]
    # The vertical motion in experiment 1, the swing in experiments 2 and 3.
    result["spectrum"] = read_spectrum(
        output, "vertical" if experiment_of(name) == "1" else "horizontal")
    # The trajectory itself is read by load_case() from the run's output.
    trajectory = output / "tip_trajectory.csv"
    if trajectory.exists():
        result["finite"] = read_trajectory(trajectory)[1]
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
        for entry in (tetrahedral_defaults(scene) + QUIET
                      + [f"Time integration/End time={record_of(name):g}"] + overrides):
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
    # The spectrum is read again from the run's own output, so that the
    # report always uses the direction this script asks for.
    source = (REPOSITORY / "output" / "locking" / case[7].split(":", 1)[1]
              if case[7].startswith("locking:") else output_root / name)
    if (source / "tip_spectrum.csv").exists():
        result["spectrum"] = read_spectrum(
            source, "vertical" if experiment_of(name) == "1" else "horizontal")
    # So is the trajectory (results stored by earlier versions of this
    # script kept a copy of it, some with u_x only).
    if (source / "tip_trajectory.csv").exists():
        d, _ = read_trajectory(source / "tip_trajectory.csv")
        result["t"] = d["t"].tolist()
        for component in ("u_x", "u_y", "u_z"):
            if component in d:
                result[component] = d[component].tolist()
    return result


# @sect{Errors}

def errors_against(result, reference):
    """Relative errors of frequency, damping ratio and trajectory."""
    if not result or not reference or result["status"] != "finished":
        return None
    s, r = result.get("spectrum"), reference.get("spectrum")
    if not s or not r or not s["f_damped_fit_Hz"] or not r["f_damped_fit_Hz"]:
        return None
    # Experiment 1: the vertical displacement u_x; the pendulums: the
    # displacement vector, in the components both runs have.
    components = (["u_x"] if experiment_of(result["name"]) == "1" else
                  [c for c in ("u_x", "u_y", "u_z") if c in result and c in reference])
    t_ref = np.array(reference["t"])
    difference, oscillation = 0., 0.
    for c in components:
        u_ref = np.array(reference[c])
        u = np.interp(t_ref, np.array(result["t"]), np.array(result[c]))
        difference += np.mean((u - u_ref) ** 2)
        oscillation += np.mean((u_ref - u_ref.mean()) ** 2)
    return {"frequency": s["f_damped_fit_Hz"] / r["f_damped_fit_Hz"] - 1.,
            "damping": s["xi_fit"] / r["xi_fit"] - 1.,
            "trajectory": math.sqrt(difference / oscillation)}


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
    "2D strip P1": ("tab:green", "-v"),
    "2D strip P2": ("tab:purple", "-v"),
    "2D strip P2, dt series": ("tab:purple", ":x"),
    "2D strip, geometry from 3D P2 mean dilatation": ("tab:brown", "-P"),
}


# A time-step series also shows the run of its discretisation at the
# scenes' dt = 0.01 s, which belongs to the spatial series.
SERIES_ALSO = [("3D P1 coarse, dt series", "p1_coarse_dt0.01"),
               ("3D P1 coarse, dt series", "planar_p1_coarse_dt0.01"),
               ("3D P1 coarse, dt series", "spherical_p1_coarse_dt0.01"),
               ("3D P2 mean dilatation coarse, dt series", "p2md_coarse_dt0.01"),
               ("1D column P2, dt series", "column_p2_r0_dt0.01"),
               ("2D strip P2, dt series", "planar_2d_p2_r0_dt0.01")]



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
    for family, name in SERIES_ALSO:
        if (family in by_family and name in by_name and errors.get(name)
                and by_name[name].get("wall")):
            by_family[family].append((by_name[name]["wall"],
                                      abs(errors[name][measure]), by_name[name]))
    for points in by_family.values():
        points.sort(key=lambda p: p[0])
    return by_family


def plot_work_precision(results, errors, path, title, reference):
    figure, axes = plt.subplots(1, 3, figsize=(16, 5.2))
    trajectory = ("tip trajectory u_x(t)" if experiment_of(reference) == "1"
                  else "tip displacement u(t)")
    for ax, measure, name in zip(axes, ("frequency", "damping", "trajectory"),
                                 ("tip frequency", "damping ratio ξ", trajectory)):
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


# What each experiment's section of the report says about its cases.
EXPERIMENTS = {
    "1": {"title": "Experiment 1: vertical oscillation",
          "scenes": f"`{SCENE_3D}` (quarter model) and `{SCENE_1D}` (reduced column)",
          "record": RECORD, "motion": "vertical tip motion (the `vertical` row of "
          "`tip_spectrum.csv`); the trajectory error is that of the tip's vertical "
          "displacement u_x",
          "figure": "against_3d_reference.png"},
    "2": {"title": "Experiment 2: planar pendulum",
          "scenes": f"`{SCENE_PLANAR_3D}` (half model) and `{SCENE_PLANAR_2D}` "
          "(reduced strip)", "record": RECORD_SWING,
          "motion": "swing (the `horizontal` row of `tip_spectrum.csv`); the trajectory "
          "error is that of the tip's displacement vector (the components both runs "
          "have)", "figure": "experiment_2.png"},
    "3": {"title": "Experiment 3: spherical pendulum",
          "scenes": f"`{SCENE_SPHERICAL_3D}` (full model)", "record": RECORD_SWING,
          "motion": "swing (the `horizontal` row of `tip_spectrum.csv`); the trajectory "
          "error is that of the tip's displacement vector",
          "figure": "experiment_3.png"},
}
# The reduced models against their own finest run.
OWN_REFERENCES = {"1D": ("column_p2_r2_dt0.00125", "the 1D column",
                         "column_against_own_reference.png"),
                  "2D": ("planar_2d_p2_r0_dt0.00125", "the 2D strip",
                         "strip_against_own_reference.png")}


def case_table(lines, results, errors):
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


def fastest_within(results, errors, reference, what):
    within = [(r["wall"], r) for r in results if errors.get(r["name"]) and r.get("wall")
              and abs(errors[r["name"]]["frequency"]) <= 0.01 and r["name"] != reference]
    if not within:
        return f"No run other than the reference is within 1 % of {what}'s frequency."
    wall, best = min(within, key=lambda p: p[0])
    return (f"The cheapest run within 1 % of {what}'s frequency is **{best['label']}** "
            f"({best['model']}): {100 * errors[best['name']]['frequency']:+.2f} % in "
            f"{wall:.2f} s. All runs within 1 %: " + ", ".join(
                f"{r['label']} ({w:.2f} s)" for w, r in sorted(within, key=lambda p: p[0]))
            + ".")


def write_report(path, results, session):
    figures = REPOSITORY / FIGURES
    figures.mkdir(parents=True, exist_ok=True)
    by_name = {r["name"]: r for r in results}

    lines = ["<!-- Written by doc/error_vs_runtime/run_error_vs_runtime.py; the "
             "discussion is in doc/error-vs-runtime_discussion.md. -->",
             "# Error against run time\n"]
    lines += run_lines(session)
    locking = REPOSITORY / "output" / "locking" / "session.json"
    if locking.exists():
        for run in json.loads(locking.read_text()).get("runs", []):
            lines.append(f"- the dt = 0.01 s 3D cases of experiment 1 come from the "
                         f"locking study: `{run['command']}`, commit `{run['commit']}`, "
                         f"{run['date']}")
    lines.append("")
    lines.append(
        "All scenes are Dragon Skin 20 with the baseline moduli (μ = C1, κ = 100 μ), "
        "HHT α = −0.25, without VTU output. Errors are relative to the reference of the "
        "experiment: the frequency and damping ratio of the modal fit, and the RMS over "
        "the record of the difference of the tip trajectory divided by the RMS of the "
        "reference's oscillation about its mean. Wall times are the program's own "
        "(`run_statistics.json`), one thread, on a machine shared with other work "
        "(two cases ran at the same time in places): indicative to some ten percent; "
        "errors below 1e-6 are drawn at 1e-6 in the figures.\n")
    lines.append(
        "The reduced models' geometry in the scenes (the column's section 29.436 mm², "
        "the strip's width 31.9 mm and thickness 0.909 mm) was computed by "
        "`calibrate reduced-models` from the 3D models with linear tetrahedra. The "
        "cases \"from 3D P2 mean dilatation\" use the geometry the same command "
        f"computes from the 3D scenes set to `Polynomial degree = 2` and `Volumetric "
        f"formulation = mean dilatation` (coarse quarter and half meshes, 52 s): a "
        f"section of {P2MD_SECTION} mm², a strip 25.4 mm wide and 0.661 mm thick. "
        "Nothing in either is fitted to a frequency.\n")

    for key, experiment in EXPERIMENTS.items():
        cases = [r for r in results if experiment_of(r["name"]) == key]
        if not cases:
            continue
        reference_name = reference_of(key, by_name)
        reference = by_name.get(reference_name)
        errors = {r["name"]: errors_against(r, reference) for r in cases}
        plot_work_precision(cases, errors, figures / experiment["figure"],
                            f"{experiment['title']}, Dragon Skin 20: error against the "
                            f"reference ({reference_name}) and wall time", reference_name)
        lines.append(f"## {experiment['title']}\n")
        lines.append(f"Scenes: {experiment['scenes']}, each with `Time integration/End "
                     f"time={experiment['record']:g}`. The frequency is that of the "
                     f"{experiment['motion']}.\n")
        if reference and reference.get("spectrum"):
            s = reference["spectrum"]
            lines.append(f"**Reference** (`{reference_name}`): {REFERENCE_TEXT[reference_name]}; "
                         f"f = {s['f_damped_fit_Hz']:.4f} Hz, ξ = {s['xi_fit']:.5f}, "
                         f"{reference.get('dofs')} dofs, {reference.get('wall', 0):.0f} s.\n")
        else:
            lines.append(f"**Reference** (`{reference_name}`): not run yet.\n")
        case_table(lines, cases, errors)
        lines.append("**Which model reaches 1 % frequency error fastest:** "
                     + fastest_within(cases, errors, reference_name, "the reference") + "\n")
        lines.append(f"![{experiment['title']}](figures/error_vs_runtime/"
                     f"{experiment['figure']})\n")

    for model, (reference_name, what, figure) in OWN_REFERENCES.items():
        reference = by_name.get(reference_name)
        own = [r for r in results if r["model"] == model and "p2md" not in r["name"]]
        if not own or not reference:
            continue
        errors = {r["name"]: errors_against(r, reference) for r in own}
        plot_work_precision(own, errors, figures / figure,
                            f"{what[0].upper() + what[1:]} against its own finest run "
                            f"({reference_name}): its discretisation error alone",
                            reference_name)
        lines.append(f"## {what[0].upper() + what[1:]} against its own finest run\n")
        s = reference["spectrum"] or {}
        lines.append(f"Reference `{reference_name}`: f = {s.get('f_damped_fit_Hz', 0):.4f} "
                     f"Hz, ξ = {s.get('xi_fit', 0):.5f}. "
                     + fastest_within(own, errors, reference_name, "this run") + "\n")
        lines.append("| case | dofs | dt s | wall s | error f | error ξ | error trajectory |")
        lines.append("|---|---:|---:|---:|---:|---:|---:|")
        for r in own:
            e = errors.get(r["name"]) or {}
            lines.append(f"| {r['label']} | {r.get('dofs', '–')} | {r['dt']:g} "
                         f"| {r.get('wall', 0):.2f} | {fmt_error(e.get('frequency'))} "
                         f"| {fmt_error(e.get('damping'))} | {fmt_error(e.get('trajectory'))} |")
        lines.append("")
        lines.append(f"![{what}](figures/error_vs_runtime/{figure})\n")
    write_with_discussion_link(path, lines, "error-vs-runtime_discussion.md")


def main():
    by_name = {case[0]: case for case in CASES}
    study_main(__doc__, "doc/error_vs_runtime/run_error_vs_runtime.py", "output/error_vs_runtime", "doc/error-vs-runtime.md", CASE_NAMES,
               lambda build, output_root, name, timeout, threads: run_case(
                   build, output_root, by_name[name], timeout, threads),
               load_case, write_report)


if __name__ == "__main__":
    main()
