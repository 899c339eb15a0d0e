#!/usr/bin/python3
# SPDX-License-Identifier: LGPL-2.1-or-later
"""The stability study (issue 6, "stability on stiff and extreme cases"):
runs stiff and extreme variants of the bellows scenes with the Release
build of soft-robot, one at a time, and writes doc/stability.md with its
figures in doc/figures/stability/.

    /usr/bin/python3 doc/stability/run_stability.py build-release
        [--cases a,b] [--timeout 900] [--keep-vtu] [--report-only]

Every case is a scene of parameters/bellows/ with command-line overrides
(`--set`). For each case the script records whether the run finished, its
exit code and, if it did not finish, the last lines of its message; whether
anything that is not finite appears in the tip trajectory; the number of
steps, time-step cutbacks (and their reasons, from the log), Newton
iterations per step (mean and max, from the trajectory), the wall time it
measured itself, and the energy balance residual.

A case that runs longer than --timeout seconds is killed (its whole process
group) and reported as a hang.

The energy balance. The trajectory's column `energy_balance` is

    B(t) = K + S + G - W_traction + D_damping - (K + S + G)(0)

(kinetic, strain and gravitational energy, the work of the tractions and the
energy taken by the damping, the last two accumulated with the forces of
HHT's equations of motion; see SoftRobotDynamics::update_energies). B is
then the algorithmic dissipation of the scheme: B < 0 is energy the time
integrator removed (HHT with alpha < 0), B > 0 energy it created. The report
normalises B by the energy scale of the run,

    E_ref = max over t of ( K(t) + S(t) + |G(t) - G(0)| ),

the largest energy stored in the body at any time (strain energy has its
natural zero in the unloaded body; the gravitational potential has none,
so its change is taken). It also gives B against the largest kinetic
energy, the stricter measure for an oscillation about a prestressed state.

The 3D cases that matter for it write VTU files (all others run with
`Output/Write VTU=false`): the stiff cases only the initial state, from
which the script reads the volume ratio J (that the bulk-modulus override
took effect: 1 - J scales like 1/kappa), the large-deformation cases a
series, from which it computes the principal stretches of every silicone
cell (F from the displacements of the four vertices of each linear
tetrahedron). The VTU files are deleted after they have been read unless
--keep-vtu is given.

Nothing here is a test: the numbers are reported, not checked.
"""

import argparse
import base64
import json
import math
import os
import re
import shutil
import signal
import struct
import subprocess
import sys
import time
import zlib
from pathlib import Path

import numpy as np
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

plt.rcParams["axes.prop_cycle"] = plt.cycler(color=plt.get_cmap("tab20").colors)

REPOSITORY = Path(__file__).resolve().parents[2]
FIGURES = "doc/figures/stability"

VERTICAL_DS20 = "parameters/bellows/vertical_ds20_3d.prm"
VERTICAL_DS30 = "parameters/bellows/vertical_ds30_3d.prm"
VERTICAL_EF50 = "parameters/bellows/vertical_ef50_3d.prm"
PLANAR_DS20_2D = "parameters/bellows/planar_ds20_2d.prm"
COLUMN_DS20_1D = "parameters/bellows/column_ds20_1d.prm"

# The silicones' entries in parameters/silicones.prm.
EF50 = "Silicone library/Silicone 1"
DS20 = "Silicone library/Silicone 2"

QUIET = ["Output/Progress interval=0"]
SHORT = ["Time integration/End time=2"]
UNDAMPED_DS20 = ["Time integration/Alpha=0", f"{DS20}/Experiment-1 damping ratio=0"]
# Ecoflex 00-50 from the unloaded, undeformed state: no hold (the protocol's
# traction acts at t <= 0 only and would enter the initial acceleration).
UNLOADED = ["Initial conditions/Type=expressions", "Loads and constraints/Traction=0; 0; 0"]
TIP_2MPS = ["Initial conditions/Velocity=x > 89 ? 2000 : 0; 0; 0"]

# name, group, scene, overrides, what was changed, VTU output, spectral analysis
#   VTU output: None (off), "initial" (the state at t = 0 only), or the
#   interval of a series in seconds.
CASES = [
    ("ds20_baseline", "stiff", VERTICAL_DS20, [], "none: the scene with its linear "
     "tetrahedra, restored by `tetrahedral_defaults` "
     "(Dragon Skin 20, kappa/mu = 100, dt = 0.01 s, alpha = -0.25), 5.25 s",
     "initial", True),
    ("ds20_kappa1e3", "stiff", VERTICAL_DS20, [f"{DS20}/Bulk-to-shear ratio=1000"],
     "kappa/mu = 1e3 (`Bulk-to-shear ratio` of the library entry), 5.25 s", "initial", True),
    ("ds20_kappa1e4", "stiff", VERTICAL_DS20, [f"{DS20}/Bulk-to-shear ratio=1e4"],
     "kappa/mu = 1e4, 5.25 s", "initial", True),
    ("ds30_dt0.05", "stiff", VERTICAL_DS30, ["Time integration/Time step=0.05"],
     "Dragon Skin 30 (`vertical_ds30_3d.prm`), dt = 0.05 s, 5.25 s", None, True),
    ("ds20_block_x100", "stiff", VERTICAL_DS20,
     ["Material 2/Shear modulus=1e6", "Material 2/Bulk modulus=2e6"],
     "tip block 100x stiffer (mu = 1e6 kPa, kappa = 2e6 kPa), 5.25 s", "initial", True),
    ("ef50_release", "extreme", VERTICAL_EF50, UNLOADED + SHORT,
     "Ecoflex 00-50 released from the unloaded state (no hold), 2 s", 0.02, False),
    ("ef50_pull3", "extreme", VERTICAL_EF50,
     ["Initial conditions/Type=expressions",
      "Loads and constraints/Traction=x > 99.2 ? 3*hold : 0; 0; 0"] + SHORT,
     "Ecoflex 00-50 from the unloaded state, suddenly pulled down by a dead "
     "load of 3 x hold = 3.42 kPa on the block's end face (2.9 N on the whole "
     "body) from t = 0 on, 2 s", 0.02, False),
    ("ef50_pull10", "extreme", VERTICAL_EF50,
     ["Initial conditions/Type=expressions",
      "Loads and constraints/Traction=x > 99.2 ? 10*hold : 0; 0; 0"] + SHORT,
     "as ef50_pull3 with 10 x hold = 11.4 kPa (9.6 N), 2 s", 0.02, False),
    ("ds20_tip_2mps", "extreme", VERTICAL_DS20, TIP_2MPS + SHORT,
     "initial velocity 2000 mm/s along +x (down) on the nodes with x > 89 mm "
     "(the tip block and its glued face), 0 elsewhere, from the held "
     "equilibrium, 2 s", 0.02, False),
    ("ds20_tip_2mps_undamped", "extreme", VERTICAL_DS20,
     TIP_2MPS + SHORT + [f"{DS20}/Experiment-1 damping ratio=0"],
     "ds20_tip_2mps with zeta = 0 (alpha = -0.25), 2 s", 0.02, False),
    ("ds20_tip_2mps_alpha0_undamped", "extreme", VERTICAL_DS20,
     TIP_2MPS + SHORT + UNDAMPED_DS20,
     "ds20_tip_2mps with alpha = 0 and zeta = 0, 2 s", 0.02, False),
    ("ds20_dt0.05", "extreme", VERTICAL_DS20, ["Time integration/Time step=0.05"],
     "dt = 0.05 s, 5.25 s", None, True),
    ("ds20_alpha0_undamped", "extreme", VERTICAL_DS20, UNDAMPED_DS20,
     "alpha = 0 (trapezoidal rule), damping ratio 0 (zeta = 0), 5.25 s", None, True),
    ("ef50_release_alpha0_undamped", "extreme", VERTICAL_EF50,
     UNLOADED + SHORT + ["Time integration/Alpha=0", f"{EF50}/Experiment-1 damping ratio=0"],
     "ef50_release with alpha = 0 and zeta = 0, 2 s", 0.02, False),
    ("planar_2d_baseline", "conservation", PLANAR_DS20_2D, [],
     "reduced 2D strip (`planar_ds20_2d.prm`) as it is (alpha = -0.25, damped), 6 s",
     None, True),
    ("planar_2d_alpha0_undamped", "conservation", PLANAR_DS20_2D, UNDAMPED_DS20,
     "reduced 2D strip (`planar_ds20_2d.prm`), alpha = 0, zeta = 0, 6 s", None, True),
    ("column_1d_baseline", "conservation", COLUMN_DS20_1D, [],
     "reduced 1D column (`column_ds20_1d.prm`) as it is (alpha = -0.25, damped), 5.25 s",
     None, True),
    ("column_1d_alpha0_undamped", "conservation", COLUMN_DS20_1D, UNDAMPED_DS20,
     "reduced 1D column (`column_ds20_1d.prm`), alpha = 0, zeta = 0, 5.25 s", None, True),
    ("abort_check", "check", VERTICAL_DS20,
     TIP_2MPS + SHORT + ["Time integration/Minimum time step=0.004"],
     "deliberate: ds20_tip_2mps with `Minimum time step` = 0.004 s, to see "
     "the run stop", 0.02, False),
]

CASE_NAMES = [case[0] for case in CASES]
ALPHA0 = [name for name in CASE_NAMES if "alpha0" in name]


def directory_name(name):
    return name.replace("/", "_per_")


# @sect{Reading the program's output}

def read_trajectory(path):
    """The columns of a tip trajectory as numpy arrays, and whether every
    number in it is finite (a value that does not parse counts as not
    finite)."""
    names, rows, finite = None, [], True
    with open(path) as file:
        for line in file:
            if line.startswith("#") or not line.strip():
                continue
            fields = line.strip().split(",")
            if names is None:
                names = fields
                continue
            row = []
            for field in fields:
                try:
                    value = float(field)
                except ValueError:
                    value = math.nan
                if not math.isfinite(value):
                    finite = False
                row.append(value)
            rows.append(row)
    data = np.array(rows, dtype=float).reshape(-1, len(names))
    return {name: data[:, i] for i, name in enumerate(names)}, finite


def read_vtu(path):
    """The binary (zlib-compressed, base64) data arrays of a deal.II VTU
    file, and its TIME."""
    text = Path(path).read_text()
    arrays = {}
    for match in re.finditer(r"<DataArray([^>]*)>(.*?)</DataArray>", text, re.S):
        attributes = dict(re.findall(r'(\w+)="([^"]*)"', match.group(1)))
        body = match.group(2).strip()
        name = attributes.get("Name", "Points")
        if attributes.get("format") == "ascii":
            arrays[name] = np.array(body.split(), dtype=float)
            continue
        blocks, _, _, _ = struct.unpack("<4I", base64.b64decode(body[:24]))
        if blocks != 1:
            raise ValueError(f"{path}: {blocks} compressed blocks; one expected")
        data = zlib.decompress(base64.b64decode(body[24:]))
        dtype = {"Float32": "<f4", "Float64": "<f8", "Int32": "<i4",
                 "Int64": "<i8", "UInt8": "<u1"}[attributes["type"]]
        values = np.frombuffer(data, dtype=dtype)
        components = int(attributes.get("NumberOfComponents", 1))
        arrays[name] = values.reshape(-1, components) if components > 1 else values
    return arrays


def deformation_of_cells(arrays):
    """Per linear tetrahedron: principal stretches, J, material id and
    reference volume. deal.II writes every cell with its own vertices, cell
    data repeated at each of them."""
    cells = arrays["connectivity"].reshape(-1, 4)
    X = arrays["Points"][cells].astype(float)
    x = X + arrays["displacement"][cells].astype(float)
    dX = np.stack([X[:, i] - X[:, 0] for i in (1, 2, 3)], axis=2)
    dx = np.stack([x[:, i] - x[:, 0] for i in (1, 2, 3)], axis=2)
    F = dx @ np.linalg.inv(dX)
    C = np.transpose(F, (0, 2, 1)) @ F
    stretches = np.sqrt(np.clip(np.linalg.eigvalsh(C), 0., None))
    return (stretches, np.linalg.det(F), arrays["material_id"][cells[:, 0]],
            np.abs(np.linalg.det(dX)) / 6.)


def analyse_vtu_series(output, keep):
    """Per VTU file: the time, the largest and smallest principal stretch
    and the smallest J in the silicone (material 1), the smallest J
    anywhere, and the volume-weighted mean |1 - J| of each material."""
    rows = []
    for path in sorted(output.glob("solution_*.vtu")):
        arrays = read_vtu(path)
        stretches, J, material, volume = deformation_of_cells(arrays)
        silicone = material == 1
        block = material == 2
        mean_deviation = {
            id: float(np.sum(volume[m] * np.abs(1. - J[m])) / np.sum(volume[m]))
            for id, m in ((1, silicone), (2, block)) if m.any()}
        rows.append({
            "t": float(arrays["TIME"][0]),
            "max_stretch": float(stretches[silicone].max()),
            "min_stretch": float(stretches[silicone].min()),
            "min_J_silicone": float(J[silicone].min()),
            "min_J": float(J.min()),
            "mean_abs_1_minus_J_silicone": mean_deviation.get(1, math.nan),
            "mean_abs_1_minus_J_block": mean_deviation.get(2, math.nan),
        })
    if not keep:
        for pattern in ("solution_*.vtu", "solution_*.pvtu", "solution.pvd"):
            for path in output.glob(pattern):
                path.unlink()
    rows.sort(key=lambda row: row["t"])
    return rows


def tip_frequency(output):
    """The dominant peak of the direction with the largest magnitude."""
    path = output / "tip_spectrum.csv"
    if not path.exists():
        return None
    import csv
    best = None
    with open(path) as file:
        for row in csv.DictReader(file):
            if row["peak"] != "dominant" or not row["f_peak_Hz"]:
                continue
            magnitude = float(row["magnitude"])
            if best is None or magnitude > best[0]:
                best = (magnitude, float(row["f_peak_Hz"]), row["direction"])
    return ["no peak", ""] if best is None else [best[1], best[2]]


CUTBACK = re.compile(r"step at t = (\S+) failed \((.*)\); time step cut back to (\S+) s")


def cutbacks_from_log(log):
    """The cutbacks the log reports, with their reasons grouped (numbers in
    the reasons are dropped)."""
    events, reasons = [], {}
    for line in log.splitlines():
        match = CUTBACK.search(line)
        if match:
            events.append((float(match.group(1)), float(match.group(3))))
            reason = re.sub(r"\s*\([^()]*[0-9][^()]*\)", "", match.group(2))
            reason = re.sub(r"[-+]?\d[\d.e+-]*", "#", reason).strip()
            reasons[reason] = reasons.get(reason, 0) + 1
    return events, reasons


def printed_materials(log):
    return [line.strip() for line in log.splitlines() if line.startswith("Material ")]


def relative(text):
    """Text without this machine's paths."""
    return text.replace(str(REPOSITORY) + "/", "").replace(str(REPOSITORY), ".")


# @sect{Running a case}

def run_program(command, environment, output, timeout):
    """Runs soft-robot with its output in output/run.log, killing it after
    `timeout` seconds. Returns the log and what the studies record of the
    run: exit code, timeout, wall time, the printed material data, and its
    status (finished, stopped cleanly with exit code 2, hang, or crashed)
    with the last lines of the log and the stop message if it did not
    finish."""
    start = time.perf_counter()
    with open(output / "run.log", "w") as log:
        process = subprocess.Popen(command, cwd=REPOSITORY, env=environment,
                                   stdout=log, stderr=subprocess.STDOUT,
                                   start_new_session=True)
        timed_out = False
        try:
            exit_code = process.wait(timeout=timeout)
        except subprocess.TimeoutExpired:
            timed_out = True
            os.killpg(process.pid, signal.SIGKILL)
            exit_code = process.wait()
    seconds = time.perf_counter() - start
    log = (output / "run.log").read_text(errors="replace")
    result = {"exit_code": exit_code, "timed_out": timed_out,
              "measured_seconds": seconds, "materials": printed_materials(log)}
    if timed_out:
        result["status"] = "hang"
    elif exit_code == 0:
        result["status"] = "finished"
    elif exit_code == 2 and "The simulation stopped:" in log:
        result["status"] = "stopped"
    else:
        result["status"] = "crashed"
    if result["status"] != "finished":
        tail = [line for line in log.strip().splitlines() if line.strip()][-10:]
        result["log_tail"] = [relative(line) for line in tail]
        stop = re.search(r"The simulation stopped: (.*)", log)
        result["message"] = relative(stop.group(1)) if stop else relative(tail[-1] if tail else "")
    return log, result


def run_case(build, output_root, case, timeout, keep_vtu):
    name, group, scene, overrides, description, vtu, spectral = case
    output = output_root / directory_name(name)
    if output.exists():
        shutil.rmtree(output)
    output.mkdir(parents=True)
    entries = tetrahedral_defaults(scene) + QUIET + [
        f"Output/Spectral analysis={'true' if spectral else 'false'}"]
    if vtu is None:
        entries.append("Output/Write VTU=false")
    elif vtu == "initial":
        entries += ["Output/Write VTU=true", "Output/Output interval=1e9"]
    else:
        entries += ["Output/Write VTU=true", f"Output/Output interval={vtu}"]
    entries += overrides
    command = [str(build / "soft-robot"), scene,
               "--set", f"Problem/Output directory={output}"]
    for entry in entries:
        command += ["--set", entry]
    environment = dict(os.environ, OMP_NUM_THREADS="1")
    print(f"[{name}] {description}", flush=True)

    log, outcome = run_program(command, environment, output, timeout)
    result = {"name": name, "group": group, "scene": scene, "description": description,
              "overrides": overrides, **outcome}

    events, reasons = cutbacks_from_log(log)
    result["cutbacks_in_log"] = len(events)
    result["cutback_reasons"] = reasons
    result["smallest_step_in_log"] = min((dt for _, dt in events), default=None)

    statistics_path = output / "run_statistics.json"
    if statistics_path.exists():
        result["statistics"] = json.loads(statistics_path.read_text())
    trajectory_path = output / "tip_trajectory.csv"
    if trajectory_path.exists():
        _, finite = read_trajectory(trajectory_path)
        result["trajectory_finite"] = finite
    result["tip_frequency"] = tip_frequency(output)
    if vtu is not None:
        result["vtu"] = analyse_vtu_series(output, keep_vtu)
    (output / "result.json").write_text(json.dumps(result, indent=1))
    print(f"    {result['status']} (exit {result['exit_code']}) "
          f"in {result['measured_seconds']:.1f} s, "
          f"{len(events)} cutback(s)", flush=True)
    return result


def load_case(output_root, name):
    output = output_root / directory_name(name)
    path = output / "result.json"
    if not path.exists():
        sys.exit(f"{path} does not exist: run the case first (without --report-only)")
    return json.loads(path.read_text())


# @sect{What the report shows}

def measures(result, output_root):
    """Steps, Newton iterations per step and the energy balance from the
    trajectory of a case."""
    output = output_root / directory_name(result["name"])
    path = output / "tip_trajectory.csv"
    if not path.exists():
        return None
    d, finite = read_trajectory(path)
    t = d["t"]
    steps = t > 0
    newton = d["newton_iterations"][steps]
    K, S, G = d["kinetic"], d["strain"], d["gravity_potential"]
    B = d["energy_balance"]
    scale = float(np.nanmax(K + S + np.abs(G - G[0])))
    return {
        "d": d, "finite": finite, "steps": int(steps.sum()), "end_time": float(t[-1]),
        "newton_mean": float(newton.mean()) if newton.size else None,
        "newton_max": int(newton.max()) if newton.size else 0,
        "E_ref": scale, "K_max": float(np.nanmax(K)),
        "B_maxabs": float(np.nanmax(np.abs(B))), "B_end": float(B[-1]),
        "B_maxgain": float(max(np.nanmax(B), 0.)),
        "t_maxgain": float(t[int(np.nanargmax(B))]),
        "B_step1": float(B[1]) if len(B) > 1 else None,
        "dt_min": float(d["dt"][steps].min()) if steps.any() else math.nan,
    }


def plot_energy_balance(results, m, path):
    hht = [r for r in results if r["name"] not in ALPHA0 and m[r["name"]]]
    trapezoidal = [r for r in results if r["name"] in ALPHA0 and m[r["name"]]]
    figure, axes = plt.subplots(2, 1, figsize=(10, 8.5), sharex=True)
    for ax, group, title in ((axes[0], hht, "HHT alpha = -0.25 (and damping, if the scene has it)"),
                             (axes[1], trapezoidal, "alpha = 0, no damping")):
        for r in group:
            d = m[r["name"]]["d"]
            ax.plot(d["t"], d["energy_balance"] / m[r["name"]]["E_ref"], label=r["name"], lw=1.2)
        ax.axhline(0., color="k", lw=0.5)
        ax.set_ylabel("energy balance B / E_ref")
        ax.set_title(title, fontsize=10)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7, ncol=2)
    axes[1].set_xlabel("t (s)")
    figure.suptitle("Energy balance residual B = K + S + G - W + D - E(0), normalised by "
                    "E_ref = max(K + S + |G - G(0)|)", fontsize=10)
    figure.tight_layout()
    figure.savefig(path, dpi=110)
    plt.close(figure)


def plot_newton(results, m, path):
    shown = [r for r in results if m[r["name"]]]
    columns = 3
    rows = math.ceil(len(shown) / columns)
    figure, axes = plt.subplots(rows, columns, figsize=(13, 2.4 * rows), squeeze=False)
    for ax, r in zip(axes.flat, shown):
        d = m[r["name"]]["d"]
        steps = d["t"] > 0
        ax.plot(d["t"][steps], d["newton_iterations"][steps], ".", ms=2.5, color="C0")
        ax.set_ylim(0, max(13, d["newton_iterations"].max() + 1))
        ax.set_title(r["name"] + ("" if r["status"] == "finished" else f" ({r['status']})"),
                     fontsize=9)
        ax.set_ylabel("Newton it.", fontsize=8, color="C0")
        ax.tick_params(labelsize=7)
        twin = ax.twinx()
        twin.semilogy(d["t"][steps], d["dt"][steps], color="C3", lw=0.8)
        twin.set_ylabel("dt (s)", fontsize=8, color="C3")
        twin.tick_params(labelsize=7)
    for ax in list(axes.flat)[len(shown):]:
        ax.axis("off")
    figure.suptitle("Newton iterations per step (dots, left) and time step (line, right)",
                    fontsize=10)
    figure.tight_layout()
    figure.savefig(path, dpi=110)
    plt.close(figure)


def plot_energy_components(results, m, path):
    shown = [r for r in results if r["name"] in ALPHA0 and m[r["name"]]]
    if not shown:
        return False
    figure, axes = plt.subplots(len(shown), 1, figsize=(10, 3.0 * len(shown)), squeeze=False)
    for ax, r in zip(axes[:, 0], shown):
        d = m[r["name"]]["d"]
        t = d["t"]
        ax.plot(t, d["kinetic"], label="kinetic K")
        ax.plot(t, d["strain"] - d["strain"][0], label="strain S - S(0)")
        ax.plot(t, d["gravity_potential"] - d["gravity_potential"][0], label="gravity G - G(0)")
        ax.plot(t, -d["traction_work"], label="- traction work W")
        ax.set_ylabel("energy (µJ)")
        ax.set_title(r["name"], fontsize=9)
        ax.grid(alpha=0.3)
        twin = ax.twinx()
        twin.plot(t, d["energy_balance"], color="k", lw=1.0, label="balance B (right)")
        twin.set_ylabel("balance B (µJ)")
        lines = ax.get_legend_handles_labels()
        more = twin.get_legend_handles_labels()
        ax.legend(lines[0] + more[0], lines[1] + more[1], fontsize=7, ncol=5, loc="upper right")
    axes[-1, 0].set_xlabel("t (s)")
    figure.suptitle("Energy components with alpha = 0 and no damping "
                    "(kg mm²/s² = µJ; the balance on its own axis)", fontsize=10)
    figure.tight_layout()
    figure.savefig(path, dpi=110)
    plt.close(figure)
    return True


def plot_stretch(results, m, path):
    shown = [r for r in results if r.get("vtu") and max(row["t"] for row in r["vtu"]) > 0]
    if not shown:
        return False
    figure, axes = plt.subplots(1, 2, figsize=(12, 4.2))
    for i, r in enumerate(shown):
        rows = r["vtu"]
        axes[0].plot([row["t"] for row in rows], [row["max_stretch"] for row in rows],
                     "-o", ms=2, color=f"C{i}", label=r["name"])
        if m[r["name"]]:
            d = m[r["name"]]["d"]
            axes[1].plot(d["t"], d["u_x"], color=f"C{i}", label=r["name"])
    axes[0].axhline(2., color="k", lw=0.6, ls="--")
    axes[0].set_yscale("log")
    axes[0].set_ylabel("largest principal stretch in the silicone")
    axes[1].set_ylabel("tip displacement u_x (mm)")
    for ax in axes:
        ax.set_xlabel("t (s)")
        ax.grid(alpha=0.3, which="both")
        ax.legend(fontsize=7)
    figure.suptitle("Large deformations: the largest principal stretch of any silicone cell "
                    "(from the VTU series) and the tip motion", fontsize=10)
    figure.tight_layout()
    figure.savefig(path, dpi=110)
    plt.close(figure)
    return True


# @sect{The report}

# The machine and the commit are described as in the speed benchmark; the
# scenes' linear tetrahedra are restored for every case (run_case()).
sys.path.insert(0, str(REPOSITORY / "doc" / "performance"))
sys.path.insert(0, str(REPOSITORY / "doc"))
from run_benchmarks import (commit, machine_description,  # noqa: E402
                            write_with_discussion_link)
from study_session import tetrahedral_defaults  # noqa: E402


def fmt(value, digits=2):
    if value is None or (isinstance(value, float) and not math.isfinite(value)):
        return "–"
    return f"{value:.{digits}e}" if value != 0 and (abs(value) < 1e-2 or abs(value) >= 1e4) \
        else f"{value:.{digits}f}"


def status_text(r, x):
    if r["status"] == "finished":
        return "yes"
    if r["status"] == "stopped":
        return f"clean stop (exit 2): {r['message']}"
    if r["status"] == "hang":
        reached = f" at t = {x['end_time']:.4g} s" if x else ""
        return (f"**no: killed at the {r['measured_seconds']:.0f} s timeout**, its "
                f"trajectory ends{reached} (log tail below)")
    return f"**no: crashed (exit {r['exit_code']})** (see its log tail below)"


def write_report(path, results, m, session):
    figures = REPOSITORY / FIGURES
    figures.mkdir(parents=True, exist_ok=True)
    plot_energy_balance(results, m, figures / "energy_balance.png")
    plot_newton(results, m, figures / "newton_iterations.png")
    has_components = plot_energy_components(results, m, figures / "energy_components_alpha0.png")
    has_stretch = plot_stretch(results, m, figures / "stretch.png")

    lines = []
    lines.append("<!-- Written by doc/stability/run_stability.py; "
                 "the discussion is in doc/stability_discussion.md. -->")
    lines.append("# Stability on stiff and extreme cases\n")
    lines.append(f"Command: `{session['command']}`  ")
    lines.append(f"Commit: `{session.get('commit') or commit()}` (HEAD when the study "
                 "started), Release build  ")
    lines.append(f"Machine: {session['machine']}; load average at the start "
                 f"{session['load']}  ")
    lines.append(f"Date: {session['date']}; the whole study took "
                 f"{session['total_seconds']:.0f} s\n")
    lines.append(
        "Base scene: experiment 1 (vertical oscillation) on the coarse quarter model "
        "(1,801 linear tetrahedra), `parameters/bellows/vertical_<silicone>_3d.prm`; the "
        "reduced 2D and 1D scenes for the conservation check in every dimension. Every "
        "case is the scene with `--set` overrides (listed below the table). The cases "
        "run one at a time with a timeout of "
        f"{session['timeout']:.0f} s each; a case that exceeds it is killed and reported "
        "as a hang. Wall times are measured by this script around the whole run; the "
        "machine was shared with other work, so they are indicative only.\n")
    lines.append(
        "**Energy balance.** The trajectory's `energy_balance` is B = K + S + G − W + D − "
        "(K + S + G)(0): kinetic, strain and gravitational energy, minus the work of the "
        "tractions, plus the energy taken by the damping (both accumulated with the "
        "forces of HHT's equations of motion, the mean of the two at the ends of each "
        "step, so that B is the scheme's algorithmic dissipation and nothing else; "
        "`doc/introduction.md`). B < 0 is energy that the time integrator removed (HHT "
        "with α < 0), B > 0 energy it created. It is "
        "normalised by E_ref = max over t of (K + S + |G − G(0)|), the largest energy "
        "stored in the body during the run. \"max |B|/E_ref\" is the drift, \"B end\" the "
        "signed value at the last step. Newton/step counts the iterations of the "
        "converged attempt of each step (not those of attempts that were cut back); "
        "\"tangents\" is the number of matrix assemblies and factorizations of the run "
        "(`run_statistics.json`, written only by a run that finishes).\n")

    lines.append("| case | what was changed | finished | steps | cutbacks | Newton/step "
                 "mean / max | tangents | max \\|B\\|/E_ref | B end / E_ref | NaN/inf "
                 "| wall s |")
    lines.append("|---|---|---|---:|---:|---:|---:|---:|---:|---|---:|")
    for r in results:
        x = m[r["name"]]
        steps = x["steps"] if x else "–"
        newton = f"{x['newton_mean']:.2f} / {x['newton_max']}" \
            if x and x["newton_mean"] is not None else "–"
        valid = x and x["E_ref"] > 0 and x["steps"] > 0
        drift = fmt(x["B_maxabs"] / x["E_ref"]) if valid else "–"
        end = fmt(x["B_end"] / x["E_ref"]) if valid else "–"
        finite = "–" if not x else ("none" if x["finite"] else "**yes**")
        tangents = r["statistics"]["factorizations_or_amg_setups"] \
            if "statistics" in r else "–"
        lines.append(f"| {r['name']} | {r['description']} | {status_text(r, x)} | {steps} "
                     f"| {r['cutbacks_in_log']} | {newton} | {tangents} | {drift} | {end} "
                     f"| {finite} "
                     f"| {r['measured_seconds']:.1f} |")
    lines.append("")

    lines.append("## Energies, time steps and deformation\n")
    lines.append("Energies in kg mm²/s² = µJ (of the modelled part of the body: a quarter "
                 "of it in 3D). \"largest gain\" is the largest positive B; \"B after step 1\" is the "
                 "balance after the first step, in which a load released at t = 0 still "
                 "acts with the weight −α (see the discussion). dt min is the "
                 "smallest step that converged; the stretch columns come from the VTU "
                 "series (largest and smallest principal stretch of any silicone cell at "
                 "any output time, smallest J of any cell), where one was written. The tip "
                 "frequency is the program's spectral analysis of the whole record, where "
                 "it was switched on.\n")
    lines.append("| case | t reached s | E_ref | max K | B after step 1 | max \\|B\\| "
                 "| largest gain | max \\|B\\| / max K | dt min s | cutback reasons (count) "
                 "| max stretch | min stretch | min J | tip f Hz |")
    lines.append("|---|---:|---:|---:|---:|---:|---:|---:|---:|---|---:|---:|---:|---|")
    for r in results:
        x = m[r["name"]]
        if not x:
            lines.append(f"| {r['name']} |" + " – |" * 13)
            continue
        reasons = "; ".join(f"{k} ({v})" for k, v in r["cutback_reasons"].items()) or "–"
        series = r.get("vtu") or []
        if len(series) > 1:
            stretch = (fmt(max(row["max_stretch"] for row in series)),
                       fmt(min(row["min_stretch"] for row in series)),
                       fmt(min(row["min_J"] for row in series), 3))
        else:
            stretch = ("–", "–", "–")
        f = "–"
        if r.get("tip_frequency"):
            f, direction = r["tip_frequency"]
            f = f if isinstance(f, str) else f"{f:.4f} ({direction})"
        gain = fmt(x["B_maxgain"])
        if x["B_maxgain"] > 0:
            gain += f" (t = {x['t_maxgain']:.4g})"
        lines.append(
            f"| {r['name']} | {x['end_time']:.3f} | {fmt(x['E_ref'])} | {fmt(x['K_max'])} "
            f"| {fmt(x['B_step1'])} | {fmt(x['B_maxabs'])} | {gain} "
            f"| {fmt(x['B_maxabs'] / x['K_max']) if x['K_max'] > 0 else '–'} "
            f"| {fmt(x['dt_min'])} | {reasons} | {stretch[0]} | {stretch[1]} | {stretch[2]} "
            f"| {f} |")
    lines.append("")

    first = [r for r in results if m[r["name"]] and m[r["name"]]["steps"] >= 2
             and m[r["name"]]["E_ref"] > 0
             and abs(m[r["name"]]["B_step1"]) > 1e-3 * m[r["name"]]["E_ref"]]
    if first:
        lines.append("## The first steps\n")
        lines.append("The cases whose balance moves by more than 1e-3 E_ref in the first "
                     "step: the terms of B after each of the first three steps. E = K + S + "
                     "G is a state function, computed afresh at every step; W and D are "
                     "sums over the steps.\n")
        lines.append("| case | step | t s | dt s | E − E(0) | W | D | B |")
        lines.append("|---|---:|---:|---:|---:|---:|---:|---:|")
        for r in first:
            d = m[r["name"]]["d"]
            E = d["kinetic"] + d["strain"] + d["gravity_potential"]
            for i in range(1, min(4, len(E))):
                lines.append(f"| {r['name']} | {i} | {d['t'][i]:.3g} | {d['dt'][i]:.3g} "
                             f"| {fmt(E[i] - E[0])} | {fmt(d['traction_work'][i])} "
                             f"| {fmt(d['damping_dissipation'][i])} "
                             f"| {fmt(d['energy_balance'][i])} |")
        lines.append("")

    initial = [r for r in results if r.get("vtu") and len(r["vtu"]) >= 1
               and r["name"].startswith("ds20_") and r["vtu"][0]["t"] == 0.
               and (r["name"] == "ds20_baseline" or "kappa" in r["name"]
                    or "block" in r["name"])]
    if initial:
        lines.append("## Do the overrides take effect?\n")
        lines.append("The log prints each material's shear modulus, but not its bulk "
                     "modulus. So the initial (held, static) state of the stiff cases is "
                     "written as VTU and the volume change read from it: the "
                     "volume-weighted mean of |1 − J| per material, with J from the "
                     "displacements of each tetrahedron (it agrees with the program's "
                     "own J field). A larger κ must make 1 − J smaller; in proportion "
                     "to 1/κ only if the pressure stayed the same, which it need not, since "
                     "the linear tetrahedra lock and the deformed shape changes with κ.\n")
        lines.append("| case | mean \\|1 − J\\| silicone | ratio to baseline | mean "
                     "\\|1 − J\\| tip block | ratio to baseline | printed material data |")
        lines.append("|---|---:|---:|---:|---:|---|")
        base = next((r for r in initial if r["name"] == "ds20_baseline"), None)
        for r in initial:
            row = r["vtu"][0]
            s, b = row["mean_abs_1_minus_J_silicone"], row["mean_abs_1_minus_J_block"]
            rs = fmt(base["vtu"][0]["mean_abs_1_minus_J_silicone"] / s) if base else "–"
            rb = fmt(base["vtu"][0]["mean_abs_1_minus_J_block"] / b) if base else "–"
            printed = "<br>".join(r["materials"])
            lines.append(f"| {r['name']} | {fmt(s, 3)} | {rs} | {fmt(b, 3)} | {rb} | {printed} |")
        lines.append("")

    lines.append("## Figures\n")
    lines.append(f"![energy balance]({FIGURES.replace('doc/', '')}/energy_balance.png)\n")
    lines.append(f"![Newton iterations]({FIGURES.replace('doc/', '')}/newton_iterations.png)\n")
    if has_components:
        lines.append(f"![energy components]({FIGURES.replace('doc/', '')}/"
                     "energy_components_alpha0.png)\n")
    if has_stretch:
        lines.append(f"![stretch]({FIGURES.replace('doc/', '')}/stretch.png)\n")

    lines.append("## The cases in detail\n")
    lines.append("Every run also gets `Output/Progress interval=0`, "
                 "`Output/Spectral analysis=true` where the tip-frequency column has an entry (else `false`), and "
                 "`Output/Write VTU=false` except where a VTU output is listed.\n")
    by_name = {case[0]: case for case in CASES}
    for r in results:
        case = by_name.get(r["name"])
        vtu = case[5] if case else None
        output = {None: "no VTU", "initial": "VTU of the initial state only "
                  "(`Output/Output interval=1e9`)"}.get(vtu, f"VTU every {vtu} s")
        sets = " ".join(f"`--set '{entry}'`" for entry in r["overrides"]) or "no override"
        lines.append(f"- **{r['name']}** (`{r['scene']}`, {r['group']}): {sets}; {output}.")
        if r["status"] != "finished":
            lines.append("  Last lines of its output:\n")
            lines.append("  ```")
            lines += [f"  {line}" for line in r["log_tail"]]
            lines.append("  ```")
    lines.append("")

    write_with_discussion_link(path, lines, "stability_discussion.md")


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("build", help="the Release build directory (with soft-robot)")
    parser.add_argument("--cases", help="comma-separated case names (default: all)")
    parser.add_argument("--output", default="output/stability")
    parser.add_argument("--report", default="doc/stability.md")
    parser.add_argument("--timeout", type=float, default=900.,
                        help="seconds after which a case is killed (default 900)")
    parser.add_argument("--keep-vtu", action="store_true",
                        help="keep the VTU files after reading them")
    parser.add_argument("--report-only", action="store_true",
                        help="write the report from the output of the last run")
    arguments = parser.parse_args()

    build = Path(arguments.build).resolve()
    if not arguments.report_only and not (build / "soft-robot").exists():
        sys.exit(f"{build / 'soft-robot'} does not exist: build in Release first")
    selected = CASES
    if arguments.cases:
        names = arguments.cases.split(",")
        unknown = set(names) - set(CASE_NAMES)
        if unknown:
            sys.exit(f"unknown case(s): {', '.join(sorted(unknown))}; "
                     f"known: {', '.join(CASE_NAMES)}")
        selected = [case for case in CASES if case[0] in names]
    output_root = (REPOSITORY / arguments.output).resolve()
    output_root.mkdir(parents=True, exist_ok=True)

    try:
        build_shown = str(build.relative_to(REPOSITORY))
    except ValueError:
        build_shown = "<Release build directory>"
    command = f"/usr/bin/python3 doc/stability/run_stability.py {build_shown}" + (
        f" --cases {arguments.cases}" if arguments.cases else "")
    session_path = output_root / "session.json"
    if arguments.report_only:
        results = [load_case(output_root, case[0]) for case in selected]
        for result, case in zip(results, selected):
            result["description"] = case[4]
        session = json.loads(session_path.read_text())
    else:
        session = {"command": command, "commit": commit(), "machine": machine_description(),
                   "load": ", ".join(f"{x:.2f}" for x in os.getloadavg()),
                   "date": time.strftime("%Y-%m-%d"), "timeout": arguments.timeout}
        start = time.perf_counter()
        results = [run_case(build, output_root, case, arguments.timeout, arguments.keep_vtu)
                   for case in selected]
        session["total_seconds"] = time.perf_counter() - start
        session_path.write_text(json.dumps(session, indent=1))
    m = {r["name"]: measures(r, output_root) for r in results}
    write_report(REPOSITORY / arguments.report, results, m, session)


if __name__ == "__main__":
    main()
