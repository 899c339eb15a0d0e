#!/usr/bin/python3
# SPDX-License-Identifier: LGPL-2.1-or-later
"""Error against run time (issues 6 and 23): the three experiments with
Dragon Skin 20 (baseline parameter set) on the scenes' default
discretisation (quadratic hexahedra with the dilatation linear in each cell
on the hexahedral mesh hex-1-3-1-2) over time steps, on finer hexahedral
meshes, and on the tetrahedral discretisations the scenes used before,
with the reduced models (the 1D column for experiment 1, the 2D strip for
experiment 2) as the scenes define them. Each point is one run of the
Release build of soft-robot with its wall time; the errors of the tip
frequency, the damping ratio and the tip trajectory are measured against
the reference of the same experiment. Writes doc/error-vs-runtime.md and
its figures in doc/figures/error_vs_runtime/.

    /usr/bin/python3 doc/error_vs_runtime/run_error_vs_runtime.py build-release
        [--cases a,b] [--timeout 1800] [--threads 1] [--report-only]

The record. Every case of experiment 1 runs `Time integration/End time =
2.5` (about six periods), those of experiments 2 and 3 `End time = 4`
(about five swings), without VTU output: the records of the reference
studies (doc/reference/run_hex_reference.py, run_swing_hex_reference.py).

The references (doc/reference_discussion.md). Experiment 1: the default
mesh refined once, at the scene's step of 0.005 s. Experiments 2 and 3:
the finest hexahedral mesh of the swing study at the scenes' step of
0.01 s (hex-2-6-2-2 for the half model, within 0.002 % of the refined
mesh; hex-2-3-1-2 for the full one, a provisional reference). The
tetrahedral cases restore the linear
tetrahedra of the scenes first (tetrahedral_defaults) and then set their
element; the hexahedral cases and the reduced models run the scenes as
they are.

The errors.
- frequency: the modal-fit damped frequency of the vertical tip motion
  (experiment 1) or of the swing (the `horizontal` direction, experiments
  2 and 3) (`f_damped_fit_Hz` of tip_spectrum.csv), relative to the
  reference's;
- damping: the modal-fit damping ratio `xi_fit`, relative;
- damping from the energy: the damping ratio a lightly damped harmonic
  motion of the same frequency would need to lose what the damping
  takes after the first second, xi_E = Delta D / (8 pi f Delta t <T>)
  (D the energy the damping has taken, T the kinetic energy, both of the
  whole body, `tip_trajectory.csv`), relative. It counts every direction
  of the motion, so an exchange of amplitude between the two directions
  of a swing does not move it, unlike the modal fit of one direction;
  it weighs the modes by their kinetic energy, so it is a measure to
  compare two runs with, not a modal damping ratio;
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
from run_benchmarks import HEX_MESHES, write_with_discussion_link  # noqa: E402
from study_session import run_lines, study_main, tetrahedral_defaults  # noqa: E402
from run_stability import read_trajectory, run_program  # noqa: E402

SCENE_3D = "parameters/bellows/vertical_ds20_3d.prm"
SCENE_1D = "parameters/bellows/column_ds20_1d.prm"
SCENE_PLANAR_3D = "parameters/bellows/planar_ds20_3d.prm"
SCENE_PLANAR_2D = "parameters/bellows/planar_ds20_2d.prm"
SCENE_SPHERICAL_3D = "parameters/bellows/spherical_ds20_3d.prm"
RECORD = 2.5         # s, experiment 1 (as the reference study)
RECORD_SWING = 4.0   # s, experiments 2 and 3 (about five swings)
QUIET = ["Output/Progress interval=0", "Output/Write VTU=false"]


def record_of(name):
    return RECORD_SWING if experiment_of(name) != "1" else RECORD


def experiment_of(name):
    """Experiment 1 (vertical), 2 (planar pendulum) or 3 (spherical)."""
    return ("2" if name.startswith("planar") else
            "3" if name.startswith("spherical") else "1")


P2 = ["Finite element/Polynomial degree=2"]
MD = ["Finite element/Volumetric formulation=mean dilatation"]


def dt_entry(dt):
    return [f"Time integration/Time step={dt:g}"]


# name, model ("3D", "1D" or "2D"), family (one line in the figures), label,
# scene, overrides, dt, tetrahedra (whether the scene's linear tetrahedra
# are restored first, by tetrahedral_defaults, as the studies of the
# tetrahedra ran them; otherwise the scene runs as it is, on the hexahedral
# mesh of its default discretisation).
CASES = []
# Experiment 1: the scenes' default (hex-1-3-1-2, quadratic hexahedra with
# the linear dilatation) over time steps, the reference (the default mesh
# refined once, at the scene's step), and the tetrahedra: the linear ones at
# the scene's step (the linear headline) and the quadratic ones in the
# mean-dilatation formulation on the coarse mesh.
for dt in (0.02, 0.01, 0.005):
    CASES.append((f"hex_dt{dt:g}", "3D", "3D hexahedra, default mesh",
                  f"Q2 hex-1-3-1-2 (default), dt = {dt:g}", SCENE_3D,
                  dt_entry(dt), dt, False))
CASES.append(("hex_refined_dt0.005", "3D", "3D hexahedra, finer mesh",
              "Q2 hex-1-3-1-2 refined once, dt = 0.005", SCENE_3D,
              HEX_MESHES["hex-1-3-1-2-refined"][0] + dt_entry(0.005), 0.005, False))
CASES.append(("p1_coarse_dt0.005", "3D", "3D P1 tetrahedra",
              "P1 coarse tetrahedra, dt = 0.005", SCENE_3D, dt_entry(0.005), 0.005,
              True))
CASES.append(("p2md_coarse_dt0.01", "3D", "3D P2 mean dilatation tetrahedra",
              "P2 mean dilatation coarse tetrahedra, dt = 0.01", SCENE_3D,
              P2 + MD + dt_entry(0.01), 0.01, True))
for dt in (0.01, 0.005):
    CASES.append((f"column_dt{dt:g}", "1D", "1D column P2",
                  f"1D column P2, 22 cells, dt = {dt:g}", SCENE_1D, dt_entry(dt), dt,
                  False))
# Experiments 2 and 3: the default at the scenes' step, the finer
# hexahedral mesh of the swing study as the reference (hex-2-6-2-2 for the
# half model, hex-2-3-1-2 for the full one, doc/reference_swing_hex.md),
# the linear tetrahedra, and the reduced 2D strip of experiment 2.
FINER = {"planar": "hex-2-6-2-2", "spherical": "hex-2-3-1-2"}
for scene, experiment in ((SCENE_PLANAR_3D, "planar"), (SCENE_SPHERICAL_3D, "spherical")):
    mesh = FINER[experiment]
    CASES.append((f"{experiment}_hex_dt0.01", "3D", "3D hexahedra, default mesh",
                  "Q2 hex-1-3-1-2 (default), dt = 0.01", scene, dt_entry(0.01), 0.01,
                  False))
    CASES.append((f"{experiment}_{mesh}_dt0.01", "3D", "3D hexahedra, finer mesh",
                  f"Q2 {mesh}, dt = 0.01", scene, HEX_MESHES[mesh][0] + dt_entry(0.01), 0.01,
                  False))
    CASES.append((f"{experiment}_p1_coarse_dt0.01", "3D", "3D P1 tetrahedra",
                  "P1 coarse tetrahedra, dt = 0.01", scene, dt_entry(0.01), 0.01, True))
for dt in (0.01, 0.005):
    CASES.append((f"planar_2d_dt{dt:g}", "2D", "2D strip P2",
                  f"2D strip P2, 88 cells, dt = {dt:g}", SCENE_PLANAR_2D, dt_entry(dt), dt,
                  False))
CASE_NAMES = [c[0] for c in CASES]
# The reference of each experiment (doc/reference_discussion.md): for
# experiment 1 the default mesh refined once at the scene's step; for the
# pendulums the finest mesh of the swing study (for experiment 2 within
# 0.002 % of the refined mesh, for experiment 3 a provisional reference).
REFERENCES = {"1": "hex_refined_dt0.005", "2": "planar_hex-2-6-2-2_dt0.01",
              "3": "spherical_hex-2-3-1-2_dt0.01"}
REFERENCE_TEXT = {
    "hex_refined_dt0.005": "quadratic hexahedra with the linear dilatation on the "
                           "default quarter mesh refined once, at the scene's step",
    "planar_hex-2-6-2-2_dt0.01": "quadratic hexahedra with the linear dilatation on "
                                 "the half mesh hex-2-6-2-2 (twice the cells through "
                                 "the wall and along a flank and per chord), "
                                 "within 0.002 % in f of the default mesh refined "
                                 "once (reference_discussion.md)",
    "spherical_hex-2-3-1-2_dt0.01": "quadratic hexahedra with the linear dilatation "
                                    "on the full mesh hex-2-3-1-2 (two cells through "
                                    "the wall), a provisional reference"}


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
    name, model, family, label, scene, overrides, dt, tetrahedra = case
    output = output_root / name
    if output.exists():
        shutil.rmtree(output)
    output.mkdir(parents=True)
    command = [str(build / "soft-robot"), scene,
               "--set", f"Problem/Output directory={output}"]
    for entry in ((tetrahedral_defaults(scene) if tetrahedra else []) + QUIET
                  + [f"Time integration/End time={record_of(name):g}"] + overrides):
        command += ["--set", entry]
    environment = dict(os.environ, OMP_NUM_THREADS="1",
                       DEAL_II_NUM_THREADS=str(threads))
    print(f"[{name}] {label}", flush=True)
    _, outcome = run_program(command, environment, output, timeout)
    result = collect(name, output, outcome)
    result.update({"model": model, "family": family, "label": label, "dt": dt,
                   "overrides": overrides})
    (output / "result.json").write_text(json.dumps(result))
    f = (result.get("spectrum") or {}).get("f_damped_fit_Hz")
    print(f"    {result['status']} in {result.get('wall', float('nan')):.1f} s, "
          f"{result.get('dofs')} dofs, f fit = {f}", flush=True)
    return result


def load_case(output_root, name):
    """A stored result, with the description of its case as the script
    defines it now, and the spectrum and trajectory read again from the
    run's own output (so that the report always uses the direction this
    script asks for)."""
    path = output_root / name / "result.json"
    if not path.exists():
        return None
    result = json.loads(path.read_text())
    case = next(c for c in CASES if c[0] == name)
    result.update({"model": case[1], "family": case[2], "label": case[3]})
    source = output_root / name
    if (source / "tip_spectrum.csv").exists():
        result["spectrum"] = read_spectrum(
            source, "vertical" if experiment_of(name) == "1" else "horizontal")
    if (source / "tip_trajectory.csv").exists():
        d, _ = read_trajectory(source / "tip_trajectory.csv")
        result["t"] = d["t"].tolist()
        for component in ("u_x", "u_y", "u_z"):
            if component in d:
                result[component] = d[component].tolist()
        frequency = (result.get("spectrum") or {}).get("f_damped_fit_Hz")
        if frequency and result.get("status") == "finished":
            result["xi_energy"] = energy_damping_ratio(d, frequency)
    return result


FIT_START = 1.0  # s: the modal fits leave out the first second, so does xi_E


def energy_damping_ratio(d, frequency):
    """xi_E = Delta D / (8 pi f Delta t <T>) after the first second: a
    lightly damped harmonic motion of energy E = 2 <T> loses 4 pi xi E
    per cycle."""
    window = d["t"] >= FIT_START
    t = d["t"][window]
    duration = t[-1] - t[0]
    mean_kinetic = np.trapz(d["kinetic"][window], t) / duration
    dissipated = d["damping_dissipation"][window][-1] - d["damping_dissipation"][window][0]
    return dissipated / (8. * math.pi * frequency * duration * mean_kinetic)


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
            "damping_energy": (result["xi_energy"] / reference["xi_energy"] - 1.
                               if result.get("xi_energy") and reference.get("xi_energy")
                               else None),
            "trajectory": math.sqrt(difference / oscillation)}


FAMILY_STYLE = {
    "3D hexahedra, default mesh": ("tab:red", "-D"),
    "3D hexahedra, finer mesh": ("tab:red", "s"),
    "3D P1 tetrahedra": ("tab:blue", "o"),
    "3D P2 mean dilatation tetrahedra": ("tab:orange", "*"),
    "1D column P2": ("tab:purple", "-^"),
    "2D strip P2": ("tab:purple", "-v"),
}


def family_points(results, errors, measure, reference):
    """Per family the (wall time, |error|, run) points, without the
    reference run itself."""
    by_family = {}
    for r in results:
        e = errors.get(r["name"])
        if e is None or not r.get("wall") or r["name"] == reference:
            continue
        by_family.setdefault(r["family"], []).append((r["wall"], abs(e[measure]), r))
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
            ax.plot(walls, values, style, color=color, ms=6, label=family)
        tolerance = {"frequency": 0.01, "damping": 0.05}.get(measure)
        if tolerance:
            ax.axhline(tolerance, color="k", lw=0.8, ls="--")
            ax.annotate(f"{100 * tolerance:g} %", (0.01, tolerance),
                        xycoords=("axes fraction", "data"),
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
          "figure": "experiment_1.png"},
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


def case_table(lines, results, errors):
    lines.append("| case | model | dofs | dt s | wall s | f fit Hz | ξ fit | error f "
                 "| error ξ | ξ_E | error ξ_E | error trajectory |")
    lines.append("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for r in results:
        s = r.get("spectrum") or {}
        e = errors.get(r["name"]) or {}
        wall = f"{r['wall']:.1f}" if r.get("wall") else "–"
        f = f"{s['f_damped_fit_Hz']:.4f}" if s.get("f_damped_fit_Hz") else "–"
        xi = f"{s['xi_fit']:.5f}" if s.get("xi_fit") else "–"
        xi_energy = f"{r['xi_energy']:.5f}" if r.get("xi_energy") else "–"
        status = "" if r["status"] == "finished" else f" **{r['status']}**"
        lines.append(f"| {r['label']}{status} | {r['model']} | {r.get('dofs', '–')} "
                     f"| {r['dt']:g} | {wall} | {f} | {xi} | {fmt_error(e.get('frequency'))} "
                     f"| {fmt_error(e.get('damping'))} | {xi_energy} "
                     f"| {fmt_error(e.get('damping_energy'))} | {fmt_error(e.get('trajectory'))} |")
    lines.append("")


def fastest_within(results, errors, reference, what):
    """The cheapest runs within 1 % of the reference's frequency, and within
    that and 5 % of its damping ratio (the converged-default issue's
    tolerances); one sentence when both are the same runs."""
    def within(tolerances):
        return sorted(((r["wall"], r) for r in results
                       if errors.get(r["name"]) and r.get("wall")
                       and r["name"] != reference
                       and all(abs(errors[r["name"]][m]) <= t
                               for m, t in tolerances.items())),
                      key=lambda p: p[0])

    def sentence(runs, criterion):
        if not runs:
            return f"No run other than the reference is within {criterion}."
        wall, best = runs[0]
        e = errors[best["name"]]
        return (f"The cheapest run within {criterion} is **{best['label']}** "
                f"({best['model']}): {100 * e['frequency']:+.2f} % and "
                f"{100 * e['damping']:+.2f} % in {wall:.1f} s; all such runs: "
                + ", ".join(f"{r['label']} ({w:.1f} s)" for w, r in runs) + ".")

    frequency = within({"frequency": 0.01})
    both = within({"frequency": 0.01, "damping": 0.05})
    both_criterion = f"1 % of {what}'s frequency and 5 % of its modal damping ratio"
    if [r["name"] for _, r in frequency] == [r["name"] for _, r in both]:
        return sentence(both, both_criterion)
    return (sentence(frequency, f"1 % of {what}'s frequency") + " "
            + sentence(both, both_criterion))


def write_report(path, results, session):
    figures = REPOSITORY / FIGURES
    figures.mkdir(parents=True, exist_ok=True)
    by_name = {r["name"]: r for r in results}

    lines = ["<!-- Written by doc/error_vs_runtime/run_error_vs_runtime.py; the "
             "discussion is in doc/error-vs-runtime_discussion.md. -->",
             "# Error against run time\n"]
    lines += run_lines(session)
    lines.append("")
    lines.append(
        "All scenes are Dragon Skin 20 with the baseline moduli (μ = C1, κ = 100 μ), "
        "HHT α = −0.25, without VTU output. The hexahedral cases (Q2: quadratic "
        "hexahedra with the dilatation linear in each cell; a mesh hex-T-F-C-Q has T "
        "cells through the wall, F along a flank, C per chord of a fold and Q per "
        "quarter turn, [reference_hex.md](reference_hex.md)) and the reduced models "
        "are the scenes as they are, with the time step and mesh the case names; the "
        "tetrahedral cases restore the scenes' earlier linear tetrahedra and their "
        "box-shaped tip block, the quadratic ones in the mean-dilatation formulation. "
        "The reduced models' geometry is the scenes': `calibrate reduced-models` "
        "computed it from the hexahedral default. Errors are relative to the "
        "reference of the experiment: the frequency and damping ratio of the modal "
        "fit after the first second, and the RMS over the record of the difference "
        "of the tip trajectory divided by the RMS of the reference's oscillation "
        "about its mean. ξ_E is the damping ratio from the energy the damping takes "
        "after the first second, ΔD / (8π f Δt ⟨T⟩) with the whole body's "
        "dissipation D and kinetic energy T: every direction of the motion counts, "
        "but not HHT's algorithmic loss. Wall times are the program's own (`run_statistics.json`), "
        "one thread, two cases at a time (one on each core): indicative to some ten "
        "percent; errors below 1e-6 are drawn at 1e-6 in the figures.\n")

    for key, experiment in EXPERIMENTS.items():
        cases = [r for r in results if experiment_of(r["name"]) == key]
        if not cases:
            continue
        reference_name = REFERENCES[key]
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
        lines.append("**Which model is within the tolerances fastest:** "
                     + fastest_within(cases, errors, reference_name, "the reference") + "\n")
        lines.append(f"![{experiment['title']}](figures/error_vs_runtime/"
                     f"{experiment['figure']})\n")

    write_with_discussion_link(path, lines, "error-vs-runtime_discussion.md")


def main():
    by_name = {case[0]: case for case in CASES}
    study_main(__doc__, "doc/error_vs_runtime/run_error_vs_runtime.py", "output/error_vs_runtime", "doc/error-vs-runtime.md", CASE_NAMES,
               lambda build, output_root, name, timeout, threads: run_case(
                   build, output_root, by_name[name], timeout, threads),
               load_case, write_report)


if __name__ == "__main__":
    main()
