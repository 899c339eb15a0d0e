#!/usr/bin/python3
# SPDX-License-Identifier: LGPL-2.1-or-later
"""The damping of the swinging actuator against the time step: does the
swing's frequency and damping converge as the step shrinks, and what does
the start-up of a release do? Runs the planar and the spherical pendulum of
Dragon Skin 20 (parameters/bellows/planar_ds20_3d.prm and
spherical_ds20_3d.prm, the baseline parameter set, 6 s) and the vertical
oscillation of experiment 1 (vertical_ds20_3d.prm, 5.25 s) with the
Kelvin-Voigt damping (the default) at dt = 0.01, 0.005 and 0.0025 s, the
planar one also with the lagged damping matrix (the old form) and with
other HHT parameters, and writes doc/damping.md.

    /usr/bin/python3 doc/damping/run_damping.py build-release
        [--cases a,b] [--timeout 3600] [--threads 1] [--report-only]

What is reported, from each run's tip_trajectory.csv:
- the swing's frequency and damping ratio from the modal fit of
  tip-spectrum (the same build) on the record after its first second, per
  direction (horizontal: the swing plane; depth: across it, in the
  spherical pendulum);
- the energy the damping forces took after the first second, D(6) - D(1)
  (the column damping_dissipation), and before it, D(1): the start-up
  transient, whose part beyond the steady rate of the swing,
  D(1) - (D(6) - D(1)) / 5, is the energy that the release put into stiff
  modes and the damping took out;
- the energy balance at the end (the algorithmic dissipation of HHT), and
  the time the damping needed to take 90 % of the start-up excess;
- the limit dt -> 0 of each quantity by Richardson extrapolation from the
  two smallest steps (second order), and each step's deviation from it.

Nothing here is a test: the numbers are reported, not checked. The
discussion is doc/damping_discussion.md.
"""

import csv
import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np

REPOSITORY = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(REPOSITORY / "doc"))
sys.path.insert(0, str(REPOSITORY / "doc" / "stability"))
from study_session import run_lines, study_main, tetrahedral_defaults  # noqa: E402
from run_stability import read_trajectory, run_program  # noqa: E402

QUIET = ["Output/Progress interval=0", "Output/Write VTU=false",
         "Output/Spectral analysis=false"]
SKIP = 1.0  # s: the start-up transient left out of the swing's analysis

# name, scene, label, overrides
CASES = []
for scene in ("planar", "spherical"):
    for dt in ("0.01", "0.005", "0.0025"):
        CASES.append((f"{scene}_kv_{dt}", f"parameters/bellows/{scene}_ds20_3d.prm",
                      f"{scene}, Kelvin-Voigt, dt = {dt} s",
                      [f"Time integration/Time step={dt}"]))
# Experiment 1, the axial mode of the hanging actuator: the scenes' time
# step must also resolve it.
for dt in ("0.01", "0.005", "0.0025"):
    CASES.append((f"vertical_kv_{dt}", "parameters/bellows/vertical_ds20_3d.prm",
                  f"vertical, Kelvin-Voigt, dt = {dt} s",
                  [f"Time integration/Time step={dt}"]))
for dt in ("0.01", "0.005"):
    CASES.append((f"planar_lagged_{dt}", "parameters/bellows/planar_ds20_3d.prm",
                  f"planar, lagged damping matrix, dt = {dt} s",
                  [f"Time integration/Time step={dt}",
                   "Damping/Stiffness-proportional damping=lagged matrix"]))
for alpha in ("-0.1", "0"):
    for dt in ("0.01", "0.005"):
        CASES.append((f"planar_alpha{alpha}_{dt}", "parameters/bellows/planar_ds20_3d.prm",
                      f"planar, Kelvin-Voigt, alpha = {alpha}, dt = {dt} s",
                      [f"Time integration/Time step={dt}",
                       f"Time integration/Alpha={alpha}"]))
CASES.append(("planar_undamped_0.01", "parameters/bellows/planar_ds20_3d.prm",
              "planar, no damping (HHT alone), dt = 0.01 s",
              # The silicone's damping coefficient comes from the Silicone
              # library (Dragon Skin 20 is its entry 2), which ignores the
              # material's own entry.
              ["Time integration/Time step=0.01",
               "Silicone library/Silicone 2/Experiment-1 damping ratio=0",
               "Material 2/Damping coefficient=0"]))
CASE_NAMES = [c[0] for c in CASES]


def run_case(build, output_root, name, timeout, threads):
    case = next(c for c in CASES if c[0] == name)
    _, scene, label, overrides = case
    output = output_root / name
    if output.exists():
        shutil.rmtree(output)
    output.mkdir(parents=True)
    command = [str(build / "soft-robot"), scene]
    for entry in (tetrahedral_defaults(scene) + QUIET + overrides
                  + [f"Problem/Output directory={output}"]):
        command += ["--set", entry]
    environment = dict(os.environ, DEAL_II_NUM_THREADS=str(threads))
    _, result = run_program(command, environment, output, timeout)
    result.update(analyse(build, output))
    result.update({"name": name, "label": label, "scene": scene})
    (output / "result.json").write_text(json.dumps(result, indent=1) + "\n")
    print(f"{name}: {result.get('status')} in {result['measured_seconds']:.0f} s")


def analyse(build, output):
    """The swing's modal fit after SKIP and the energies of the run."""
    trajectory = output / "tip_trajectory.csv"
    if not trajectory.exists():
        return {}
    table = output / "spectrum_after_skip.csv"
    subprocess.run([str(build / "tip-spectrum"), str(trajectory), "--skip", str(SKIP),
                    "--csv", str(table)], cwd=REPOSITORY, capture_output=True,
                   check=False)
    fits = {}
    if table.exists():
        with open(table) as file:
            for row in csv.DictReader(file):
                if row["peak"] != "dominant":
                    continue
                fits[row["direction"]] = {
                    "f": float(row["f_natural_fit_Hz"]) if row["f_natural_fit_Hz"] else None,
                    "xi": float(row["xi_fit"]) if row["xi_fit"] else None}
    data, finite = read_trajectory(trajectory)
    t, D = data["t"], data["damping_dissipation"]
    end = t[-1]
    D_skip = float(np.interp(SKIP, t, D))
    after = float(D[-1] - D_skip)
    steady_rate = after / (end - SKIP) if end > SKIP else 0.
    excess = D_skip - steady_rate * SKIP
    # the time by which 90 % of the start-up excess was taken
    excess_curve = D - steady_rate * t
    reached = np.nonzero(excess_curve[t <= SKIP] >= 0.9 * excess)[0]
    t90 = float(t[reached[0]]) if excess > 0 and len(reached) else None
    return {"fits": fits, "end_time": float(end), "finite": finite,
            "dissipation_after_skip": after, "dissipation_before_skip": D_skip,
            "startup_excess": excess, "startup_t90": t90,
            "balance_end": float(data["energy_balance"][-1]),
            "newton": float(np.sum(data["newton_iterations"]))}


def load_case(output_root, name):
    path = output_root / name / "result.json"
    return json.loads(path.read_text()) if path.exists() else None


def fmt(value, digits=4):
    return "—" if value is None else f"{value:.{digits}g}"


def richardson(coarse, fine):
    """The dt -> 0 limit of a second-order quantity from dt and dt/2."""
    if coarse is None or fine is None:
        return None
    return fine + (fine - coarse) / 3.


def write_report(path, results, session):
    by_name = {r["name"]: r for r in results}
    lines = ["# The damping of the swinging actuator against the time step", "",
             "Generated by `./soft-robot.sh damping` "
             "(`doc/damping/run_damping.py`); what the numbers mean and what "
             "follows from them is in [damping_discussion.md](damping_discussion.md).",
             ""] + run_lines(session) + [""]
    lines += ["## All runs", "",
              f"Modal fit of tip-spectrum after the first {SKIP:g} s (the swing: the "
              "horizontal direction; for the vertical scene the vertical one, the "
              "axial mode); D is the "
              "energy the damping forces took (µJ), B the energy balance at the "
              "end (the algorithmic dissipation of HHT, µJ).", "",
              "| case | status | f swing (Hz) | ξ swing | f depth (Hz) "
              "| ξ depth | D after 1 s | D before 1 s | start-up excess | "
              "t90 of the excess (s) | B | Newton iterations | wall (s) |",
              "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for name in CASE_NAMES:
        r = by_name.get(name)
        if r is None:
            continue
        h = r.get("fits", {}).get(
            "vertical" if name.startswith("vertical") else "horizontal", {})
        d = r.get("fits", {}).get("depth", {}) if name.startswith("spherical") else {}
        lines.append(
            f"| {r['label']} | {r.get('status')} | {fmt(h.get('f'), 5)} | "
            f"{fmt(h.get('xi'), 4)} | {fmt(d.get('f'), 5)} | {fmt(d.get('xi'), 4)} | "
            f"{fmt(r.get('dissipation_after_skip'), 5)} | "
            f"{fmt(r.get('dissipation_before_skip'), 5)} | "
            f"{fmt(r.get('startup_excess'), 4)} | {fmt(r.get('startup_t90'), 3)} | "
            f"{fmt(r.get('balance_end'), 4)} | {fmt(r.get('newton'), 5)} | "
            f"{r['measured_seconds']:.0f} |")
    lines += ["", "## Convergence in the time step (Kelvin-Voigt damping, alpha = −0.25)", "",
              "The limit is the Richardson extrapolation from dt = 0.005 and "
              "0.0025 s (second order); each column gives the deviation from it.", "",
              "| scene | quantity | limit dt → 0 | dt = 0.01 | dt = 0.005 | dt = 0.0025 |",
              "|---|---|---|---|---|---|"]
    for scene in ("vertical", "planar", "spherical"):
        runs = [by_name.get(f"{scene}_kv_{dt}") for dt in ("0.01", "0.005", "0.0025")]
        if any(r is None for r in runs):
            continue
        direction = "vertical" if scene == "vertical" else "horizontal"
        quantities = [(f"f {direction} (Hz)",
                       lambda r, d=direction: r["fits"].get(d, {}).get("f")),
                      (f"ξ {direction}",
                       lambda r, d=direction: r["fits"].get(d, {}).get("xi")),
                      ("D after 1 s (µJ)", lambda r: r["dissipation_after_skip"])]
        if scene == "spherical":
            quantities[2:2] = [
                ("f depth (Hz)", lambda r: r["fits"].get("depth", {}).get("f")),
                ("ξ depth", lambda r: r["fits"].get("depth", {}).get("xi"))]
        for label, get in quantities:
            values = [get(r) for r in runs]
            limit = richardson(values[1], values[2])
            deviations = ["—" if v is None or not limit else f"{100 * (v - limit) / limit:+.2f} %"
                          for v in values]
            lines.append(f"| {scene} | {label} | {fmt(limit, 5)} | "
                         + " | ".join(deviations) + " |")
    path.write_text("\n".join(lines) + "\n")
    print(f"wrote {path}")


if __name__ == "__main__":
    study_main(__doc__, "doc/damping/run_damping.py", "output/damping",
               "doc/damping.md", CASE_NAMES, run_case, load_case, write_report)
