#!/usr/bin/python3
# SPDX-License-Identifier: LGPL-2.1-or-later
"""The twisting column (issue 6: a standard large-deformation elastodynamics
benchmark besides the actuator): parameters/benchmarks/twisting_column.prm
with Poisson's ratio 0.45 and 0.499, with and without the mean-dilatation
formulation, with quadratic hexahedra and with linear tetrahedra, and two
time-integration variants. Runs the cases with the Release build, one at a
time, and writes doc/twisting_column.md with figures in
doc/figures/twisting_column/.

    /usr/bin/python3 doc/twisting_column/run_twisting_column.py build-release
        [--cases a,b] [--timeout 1800] [--threads 1] [--report-only]

What is reported, from each run's tip_trajectory.csv (every step):
- the energy: kinetic K, strain S and their sum; with no damping, no
  gravity and no loads the balance column B = K + S - (K + S)(0) is the
  energy the time integration created (B > 0) or removed (B < 0);
- the angular momentum about the column's axis, L_y (through the origin,
  which lies on the axis): the clamped base takes a moment, so L_y is not
  conserved; it falls from its initial value to zero when the column has
  stopped twisting, and turns negative as it twists back. The time of its
  first zero is a quarter of the torsional period, a measure of the
  column's torsional stiffness: a locking discretisation is too stiff and
  turns back early. L_x and L_z stay near zero by symmetry.

Nothing here is a test: the numbers are reported, not checked.
"""

import json
import os
import shutil
import sys
from pathlib import Path

import numpy as np
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

REPOSITORY = Path(__file__).resolve().parents[2]
FIGURES = "doc/figures/twisting_column"
sys.path.insert(0, str(REPOSITORY / "doc" / "performance"))
sys.path.insert(0, str(REPOSITORY / "doc" / "stability"))
sys.path.insert(0, str(REPOSITORY / "doc"))
from run_benchmarks import write_with_discussion_link  # noqa: E402
from study_session import run_lines, study_main  # noqa: E402
from run_stability import read_trajectory, run_program  # noqa: E402

SCENE = "parameters/benchmarks/twisting_column.prm"
QUIET = ["Output/Progress interval=0", "Output/Write VTU=false"]
# Poisson's ratio 0.499: kappa = E / (3 (1 - 2 nu)) with E = 17,000 kPa.
NU499 = ["Material 1/Bulk modulus=2833333.3",
         "Material 1/Name=neo-Hookean solid, E = 17 MPa, nu = 0.499"]
DISPLACEMENT = ["Finite element/Volumetric formulation=displacement"]
# Linear tetrahedra: each hexahedron of the mesh cut into tetrahedra.
TETS = ["Finite element/Polynomial degree=1", "Geometry/Convert to simplices=true",
        "Finite element/Volumetric formulation=displacement"]

# name, label, overrides
CASES = [
    ("q2md_nu045", "Q2 mean dilatation, ν = 0.45", []),
    ("q2_nu045", "Q2 displacement, ν = 0.45", DISPLACEMENT),
    ("p1_nu045", "P1 tetrahedra, ν = 0.45", TETS),
    ("q2md_nu0499", "Q2 mean dilatation, ν = 0.499", NU499),
    ("q2_nu0499", "Q2 displacement, ν = 0.499", DISPLACEMENT + NU499),
    ("p1_nu0499", "P1 tetrahedra, ν = 0.499", TETS + NU499),
    ("q2md_nu045_dt1ms", "Q2 mean dilatation, ν = 0.45, dt = 1 ms",
     ["Time integration/Time step=0.001"]),
    ("q2md_nu045_hht", "Q2 mean dilatation, ν = 0.45, HHT α = −0.1",
     ["Time integration/Alpha=-0.1"]),
]
CASE_NAMES = [c[0] for c in CASES]


def run_case(build, output_root, case, timeout, threads):
    name, label, overrides = case
    output = output_root / name
    if output.exists():
        shutil.rmtree(output)
    output.mkdir(parents=True)
    command = [str(build / "soft-robot"), SCENE,
               "--set", f"Problem/Output directory={output}"]
    for entry in QUIET + overrides:
        command += ["--set", entry]
    environment = dict(os.environ, OMP_NUM_THREADS="1", DEAL_II_NUM_THREADS=str(threads))
    print(f"[{name}] {label}", flush=True)
    _, result = run_program(command, environment, output, timeout)
    result.update({"name": name, "label": label, "overrides": overrides})
    statistics = output / "run_statistics.json"
    if statistics.exists():
        result["statistics"] = json.loads(statistics.read_text())
    trajectory = output / "tip_trajectory.csv"
    if trajectory.exists():
        d, finite = read_trajectory(trajectory)
        result["finite"] = finite
        result["series"] = {k: d[k].tolist() for k in
                            ("t", "kinetic", "strain", "energy_balance",
                             "newton_iterations", "L_x", "L_y", "L_z") if k in d}
    (output / "result.json").write_text(json.dumps(result))
    print(f"    {result['status']} in {result['measured_seconds']:.1f} s", flush=True)
    return result


def load_case(output_root, name):
    path = output_root / name / "result.json"
    return json.loads(path.read_text()) if path.exists() else None


def measures(r):
    s = r.get("series")
    if not s:
        return None
    t = np.array(s["t"])
    E0 = s["kinetic"][0] + s["strain"][0]
    balance = np.array(s["energy_balance"]) / E0
    L = np.array(s["L_y"])
    crossing = None
    for k in range(1, len(L)):
        if L[k - 1] > 0 >= L[k]:
            crossing = t[k - 1] + (t[k] - t[k - 1]) * L[k - 1] / (L[k - 1] - L[k])
            break
    other = max(np.max(np.abs(s["L_x"])), np.max(np.abs(s["L_z"])))
    statistics = r.get("statistics") or {}
    steps = statistics.get("steps") or max(len(t) - 1, 1)
    return {"E0": E0, "max_balance": float(np.max(np.abs(balance))),
            "final_balance": float(balance[-1]), "L0": float(L[0]),
            "L_min": float(L.min() / L[0]), "crossing": crossing,
            "L_other": float(other / L[0]), "end": float(t[-1]),
            "dofs": statistics.get("dofs"), "cells": statistics.get("cells"),
            "wall": statistics.get("wall_seconds", r["measured_seconds"]),
            "newton": statistics.get("newton_iterations", 0) / steps,
            "cutbacks": statistics.get("cutbacks")}


def plot(results, path):
    figure, axes = plt.subplots(1, 3, figsize=(16, 4.8))
    for k, r in enumerate(results):
        s = r.get("series")
        if not s:
            continue
        color = plt.cm.tab10(k % 10)
        t = np.array(s["t"])
        E0 = s["kinetic"][0] + s["strain"][0]
        if k == 0:
            axes[0].plot(t, np.array(s["kinetic"]) / E0, "--", color=color, lw=1,
                         label=f"{r['label']}: kinetic")
            axes[0].plot(t, np.array(s["strain"]) / E0, ":", color=color, lw=1,
                         label=f"{r['label']}: strain")
        axes[0].plot(t, (np.array(s["kinetic"]) + np.array(s["strain"])) / E0, "-",
                     color=color, lw=1.2, label=f"{r['label']}: K + S")
        axes[1].plot(t, np.array(s["energy_balance"]) / E0, color=color, lw=1.2,
                     label=r["label"])
        axes[2].plot(t, np.array(s["L_y"]) / s["L_y"][0], color=color, lw=1.2,
                     label=r["label"])
    axes[0].set_ylabel("energy / initial energy")
    axes[1].set_ylabel("energy balance B / initial energy")
    axes[2].set_ylabel("angular momentum about the axis, L_y / L_y(0)")
    for ax in axes:
        ax.set_xlabel("t (s)")
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize=6)
    axes[2].legend(fontsize=7)
    figure.suptitle("Twisting column (1 m × 6 m × 1 m, E = 17 MPa, Ω = 105 rad/s): "
                    "energy and angular momentum", fontsize=10)
    figure.tight_layout()
    figure.savefig(path, dpi=110)
    plt.close(figure)


def write_report(path, results, session):
    figures = REPOSITORY / FIGURES
    figures.mkdir(parents=True, exist_ok=True)
    plot(results, figures / "energy_and_angular_momentum.png")
    lines = ["<!-- Written by doc/twisting_column/run_twisting_column.py; the "
             "discussion is in doc/twisting_column_discussion.md. -->",
             "# The twisting column\n"]
    lines += run_lines(session)
    lines.append("")
    lines.append(
        f"Scene: `{SCENE}` (see its comments for the data): a 1 m × 6 m × 1 m "
        "neo-Hookean column (E = 17 MPa, ρ = 1100 kg/m³), clamped at the base, "
        "released with the twisting velocity Ω sin(πY/2H) e_y × X, Ω = 105 rad/s; "
        "no damping, no gravity; 2 × 12 × 2 hexahedra (or each cut into "
        "tetrahedra), dt = 2 ms, trapezoidal rule (α = 0) unless stated, 0.5 s. "
        "E0 is the initial (kinetic) energy; B the energy balance; L_y the "
        "angular momentum about the axis, whose first zero (\"L_y = 0 at\") is "
        "the end of the first twist, a quarter of the torsional period. "
        "|L_x|, |L_z| is the largest value of either over the run, relative "
        "to L_y(0).\n")
    lines.append("| case | cells | dofs | Newton/step | cutbacks | wall s | max \\|B\\|/E0 "
                 "| B/E0 at end | L_y = 0 at (s) | min L_y / L_y(0) | max \\|L_x\\|, \\|L_z\\| "
                 "| finished |")
    lines.append("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|")
    for r in results:
        m = measures(r)
        status = "yes" if r["status"] == "finished" else f"**{r['status']}**"
        if m is None:
            lines.append(f"| {r['label']} |" + " – |" * 10 + f" {status} |")
            continue
        crossing = f"{m['crossing']:.4f}" if m["crossing"] else "–"
        lines.append(f"| {r['label']} | {m['cells']} | {m['dofs']} | {m['newton']:.2f} "
                     f"| {m['cutbacks']} | {m['wall']:.1f} | {m['max_balance']:.2e} "
                     f"| {m['final_balance']:+.2e} | {crossing} | {m['L_min']:+.3f} "
                     f"| {m['L_other']:.1e} | {status} |")
    lines.append("")
    lines.append("![energy and angular momentum](figures/twisting_column/"
                 "energy_and_angular_momentum.png)\n")
    write_with_discussion_link(path, lines, "twisting_column_discussion.md")


def main():
    by_name = {case[0]: case for case in CASES}
    study_main(__doc__, "doc/twisting_column/run_twisting_column.py", "output/twisting_column", "doc/twisting_column.md", CASE_NAMES,
               lambda build, output_root, name, timeout, threads: run_case(
                   build, output_root, by_name[name], timeout, threads),
               load_case, write_report)


if __name__ == "__main__":
    main()
