#!/usr/bin/python3
# SPDX-License-Identifier: LGPL-2.1-or-later
"""Pneumatic actuation of the bellows (Dragon Skin 20, quarter model,
baseline parameter set): experiment 1 released from a soft vacuum at three
levels against the half-weight hold (and for Dragon Skin 30 and Ecoflex
00-50 at the level of their scenes), and the inflation of the hanging
actuator, its static elongation-pressure curve and the dynamic response
to a ramp, hold and vent. Writes doc/pneumatics.md and
doc/figures/pneumatics_elongation.png.

    /usr/bin/python3 doc/pneumatics/run_pneumatics.py build-release
        [--cases a,b] [--timeout 1800] [--threads 1] [--report-only]

Cases:
- vacuum_<level>: parameters/bellows/vacuum_release_ds20_3d.prm with the
  vacuum level (kPa) 1.5, 2.74 (the scene's) and 4, 5.25 s;
- hold: parameters/bellows/vertical_ds20_3d.prm, the half-weight hold;
- vacuum_<silicone>, hold_<silicone>: the same for ds30 and ef50
  (vacuum_release_<silicone>_3d.prm at its own level, vertical_<silicone>_3d.prm);
- static_<p>: the static equilibrium of parameters/bellows/
  inflation_ds20_3d.prm at the constant gauge pressure p (0 to 12 kPa);
- inflation: the scene itself (ramp to 8 kPa in 1 s, hold 1 s, vent);
- static1d_<p>, static2d_<p>, inflation_1d, inflation_2d: the same on the
  reduced 1D column and 2D strip (parameters/bellows/inflation_ds20_1d.prm,
  inflation_ds20_2d.prm), whose end load p A_eq stands for the cavity;
- drive_<f>: parameters/bellows/oscillation_ds20_3d.prm, a sinusoidal
  pressure of 0.2 kPa amplitude at the drive frequency f (Hz), 10 s; the
  response amplitude is the amplitude of the tip displacement's component
  at f, fitted by least squares after 6 s (a resonance curve).

What is reported, from each run's tip_trajectory.csv and tip-spectrum (the
same build) on the vertical (axial) motion: the initial tip displacement,
the peak frequency and the damping ratio by the half-power bandwidth (the
study's method) and by the modal fit; for the static cases the tip
displacement and the cavity volume against the pressure, and from them the
equivalent area dV/d(delta) that the reduced models' end load needs; for
the inflation the tip displacement against the pressure beside the static
curve, and the largest overshoot after the vent.

Nothing here is a test: the numbers are reported, not checked. The
discussion is doc/pneumatics_discussion.md.
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
VACUUM_SCENE = "parameters/bellows/vacuum_release_ds20_3d.prm"
HOLD_SCENE = "parameters/bellows/vertical_ds20_3d.prm"
INFLATION_SCENE = "parameters/bellows/inflation_ds20_3d.prm"
REDUCED_INFLATION = {"1d": "parameters/bellows/inflation_ds20_1d.prm",
                     "2d": "parameters/bellows/inflation_ds20_2d.prm"}
OSCILLATION_SCENE = "parameters/bellows/oscillation_ds20_3d.prm"
# drive frequencies, Hz: around the natural frequency 3.53 Hz of the
# vertical mode (the releases below ring at it)
DRIVES = ("1.77", "3", "3.35", "3.53", "3.71", "4.06", "5.3")
STEADY = 6.0  # s: the response is fitted after this time
LEVELS = ("1.5", "2.74", "4")
PRESSURES = ("0", "2", "4", "6", "8", "10", "12")
# end forces, mN (whole body), pulling the tip block along the axis: the
# force-elongation curves that give the pressure's force-equivalent area
FORCES = ("500", "1000", "2000", "3000", "4000", "5000")
TIP_AREA = 841.  # mm^2, the bottom face of the tip block (whole body)
REDUCED_AREA = 328.  # mm^2, the Equivalent area of the reduced inflation scenes
WORK_AREA = 392.  # mm^2, the secant dV/d(delta) of the 3D static curve, 0 to 8 kPa

# name, scene, label, overrides, kind
CASES = [(f"vacuum_{level}", VACUUM_SCENE, f"vacuum release, {level} kPa",
          [f"Loads and constraints/Function constants=hold=1.1397, vacuum={level}"],
          "release") for level in LEVELS]
CASES.append(("hold", HOLD_SCENE, "half-weight hold (958.4 mN)", [], "release"))
# the other silicones: the vacuum release at the level of their scene
# (the one that holds the tip where the half-weight hold does) and the hold
OTHER_SILICONES = {"ds30": ("Dragon Skin 30", 5.57, 0.035), "ef50": ("Ecoflex 00-50", 2.05, 0.041)}
for key, (silicone, _, _) in OTHER_SILICONES.items():
    CASES.append((f"vacuum_{key}", f"parameters/bellows/vacuum_release_{key}_3d.prm",
                  f"{silicone}: vacuum release", [], "release"))
    CASES.append((f"hold_{key}", f"parameters/bellows/vertical_{key}_3d.prm",
                  f"{silicone}: half-weight hold", [], "release"))
CASES += [(f"static_{p}", INFLATION_SCENE, f"static, {p} kPa",
           [f"Pneumatics/Pressure={p}", "Time integration/End time=0.01",
            "Initial conditions/Load steps=8"], "static") for p in PRESSURES]
CASES.append(("inflation", INFLATION_SCENE, "ramp, hold, vent", [], "inflation"))
CASES += [(f"force_{f}", INFLATION_SCENE, f"static, end force {f} mN",
           ["Pneumatics/Pressure=0", "Loads and constraints/Traction boundary ids=5",
            f"Loads and constraints/Traction=(x > 99.2) ? {float(f) / TIP_AREA:.6g} : 0; 0; 0",
            "Time integration/End time=0.01", "Initial conditions/Load steps=8"],
           "static") for f in FORCES]
REDUCED_TRACTION = {"1d": "{f}/section", "2d": "{f}/end_area; 0"}
for reduced, scene in REDUCED_INFLATION.items():
    CASES += [(f"force{reduced}_{f}", scene, f"static, end force {f} mN, {reduced.upper()}",
               ["Pneumatics/Pressure=0", "Loads and constraints/Traction boundary ids=1",
                "Loads and constraints/Traction=" + REDUCED_TRACTION[reduced].format(f=f),
                "Time integration/End time=0.01", "Initial conditions/Load steps=8"],
               "static") for f in FORCES]
    CASES += [(f"static{reduced}_{p}", scene, f"static, {p} kPa, {reduced.upper()}",
               [f"Pneumatics/Pressure={p}", "Time integration/End time=0.01",
                "Initial conditions/Load steps=8"], "static") for p in PRESSURES]
    # the same with the work-equivalent area instead of the scene's
    CASES += [(f"work{reduced}_{p}", scene,
               f"static, {p} kPa, {reduced.upper()}, A = {WORK_AREA:g} mm²",
               [f"Pneumatics/Pressure={p}", f"Pneumatics/Equivalent area={WORK_AREA:g}",
                "Time integration/End time=0.01", "Initial conditions/Load steps=8"],
               "static") for p in PRESSURES]
    CASES.append((f"inflation_{reduced}", scene, f"ramp, hold, vent, {reduced.upper()}",
                  [], "inflation"))
CASES += [(f"drive_{f}", OSCILLATION_SCENE, f"drive at {f} Hz",
           [f"Loads and constraints/Function constants=hold=1.1397, p_amp=0.2, f_drive={f}"],
           "drive") for f in DRIVES]
CASE_NAMES = [c[0] for c in CASES]


def run_case(build, output_root, name, timeout, threads):
    _, scene, label, overrides, kind = next(c for c in CASES if c[0] == name)
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
    result.update(analyse(build, output, kind))
    result.update({"name": name, "label": label, "scene": scene, "kind": kind})
    (output / "result.json").write_text(json.dumps(result, indent=1) + "\n")
    print(f"{name}: {result.get('status')} in {result['measured_seconds']:.0f} s")


def spectrum(build, trajectory, output):
    """tip-spectrum's dominant vertical peak: half-power and modal fit."""
    table = output / "spectrum.csv"
    subprocess.run([str(build / "tip-spectrum"), str(trajectory), "--csv", str(table)],
                   cwd=REPOSITORY, capture_output=True, check=False)
    if not table.exists():
        return {}
    with open(table) as file:
        for row in csv.DictReader(file):
            if row["direction"] == "vertical" and row["peak"] == "dominant":
                value = lambda key: float(row[key]) if row.get(key) else None
                return {"f_peak": value("f_peak_Hz"), "xi_half_power": value("xi_half_power"),
                        "f_fit": value("f_natural_fit_Hz"), "xi_fit": value("xi_fit")}
    return {}


def analyse(build, output, kind):
    trajectory = output / "tip_trajectory.csv"
    if not trajectory.exists():
        return {}
    data, finite = read_trajectory(trajectory)
    result = {"finite": finite, "u0": float(data["u_x"][0]),
              "balance_end": float(data["energy_balance"][-1])}
    if len(data["t"]) > 2:
        result["dt"] = float(np.median(np.diff(data["t"])))
    if "cavity_volume" in data:
        result["volume0"] = float(data["cavity_volume"][0])
    if "pressure_work" in data:
        result["pressure_work_max"] = float(np.max(np.abs(data["pressure_work"])))
    if kind == "release":
        result.update(spectrum(build, trajectory, output))
        result["amplitude"] = float(np.max(data["u_x"]) - np.min(data["u_x"])) / 2.
    if kind == "drive":
        t, u = data["t"], data["u_x"]
        steady = t >= STEADY
        frequency = float(next(e.split("f_drive=")[1] for e in
                               next(c for c in CASES if c[0] == output.name)[3]))
        omega = 2. * np.pi * frequency
        basis = np.column_stack([np.sin(omega * t[steady]), np.cos(omega * t[steady]),
                                 np.ones(np.count_nonzero(steady))])
        coefficients = np.linalg.lstsq(basis, u[steady], rcond=None)[0]
        result["drive_frequency"] = frequency
        result["drive_amplitude"] = float(np.hypot(coefficients[0], coefficients[1]))
        last = t >= t[-1] - 2.
        result["half_range_last_2s"] = float(np.max(u[last]) - np.min(u[last])) / 2.
    if kind == "inflation":
        t, u, p = data["t"], data["u_x"], data["pressure"]
        result["curve"] = {"t": t[::2].tolist(), "u": u[::2].tolist(),
                           "p": p[::2].tolist()}
        held = (t > 1.) & (t <= 2.)
        vented = t > 2.02
        result["u_end_of_ramp"] = float(np.interp(1., t, u))
        result["u_held_max"] = float(np.max(u[held]))
        result["u_held_min"] = float(np.min(u[held]))
        result["u_vented_min"] = float(np.min(u[vented]))
        result["u_vented_max"] = float(np.max(u[vented]))
        result["energy_scale"] = float(np.max(data["kinetic"] + data["strain"]))
    return result


def load_case(output_root, name):
    path = output_root / name / "result.json"
    return json.loads(path.read_text()) if path.exists() else None


def fmt(value, digits=4):
    return "—" if value is None else f"{value:.{digits}g}"


def release_row(r):
    """A table row of a released run: the spectrum's numbers, B and the wall time."""
    return (f"| {r['label']} | {r.get('status')} | {fmt(r.get('u0'), 4)} | "
            f"{fmt(r.get('amplitude'), 4)} | {fmt(r.get('f_peak'), 4)} | "
            f"{fmt(r.get('xi_half_power'), 3)} | {fmt(r.get('f_fit'), 5)} | "
            f"{fmt(r.get('xi_fit'), 4)} | {fmt(r.get('balance_end'), 4)} | "
            f"{r['measured_seconds']:.0f} |")


def figure(path, by_name):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    statics = [by_name.get(f"static_{p}") for p in PRESSURES]
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    points = [(float(p), r["u0"]) for p, r in zip(PRESSURES, statics)
              if r is not None and "u0" in r]
    if points:
        ax.plot(*zip(*points), "o-", color="k", label="static equilibrium, 3D")
    for reduced, marker in (("1d", "s"), ("2d", "^")):
        runs = [(float(p), by_name.get(f"static{reduced}_{p}")) for p in PRESSURES]
        points = [(p, r["u0"]) for p, r in runs if r is not None and "u0" in r]
        if points:
            ax.plot(*zip(*points), marker, ls="none", mfc="none", color="tab:green",
                    label=f"static equilibrium, {reduced.upper()} (end load p A_eq)")
    inflation = by_name.get("inflation")
    if inflation and "curve" in inflation:
        curve = inflation["curve"]
        t, u, p = (np.array(curve[k]) for k in ("t", "u", "p"))
        ramp = t <= 2.
        ax.plot(p[ramp], u[ramp], color="tab:blue", lw=1,
                label="ramp to 8 kPa in 1 s and hold")
        ax.plot(p[~ramp], u[~ramp], color="tab:red", lw=1, label="after the vent")
    ax.set_xlabel("gauge pressure in the cavity (kPa)")
    ax.set_ylabel("tip displacement along the axis (mm)")
    ax.axhline(0.5 * 104.5, color="grey", lw=0.5, ls="--")
    ax.text(12, 0.5 * 104.5 - 3, "50 % of the unloaded length", fontsize=8,
            color="grey", ha="right")
    ax.legend(fontsize=8, loc="upper left")
    ax.set_title("Bellows (Dragon Skin 20, quarter model): elongation against pressure",
                 fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def resonance_figure(path, by_name):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    runs = [by_name.get(f"drive_{f}") for f in DRIVES]
    points = [(r["drive_frequency"], r["drive_amplitude"]) for r in runs
              if r is not None and "drive_amplitude" in r]
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    if points:
        ax.plot(*zip(*points), "o-", color="k")
    ax.set_xlabel("drive frequency (Hz)")
    ax.set_ylabel("tip amplitude at the drive frequency (mm)")
    ax.set_title("Bellows (Dragon Skin 20, quarter model) driven by 0.2 kPa", fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def write_report(path, results, session):
    by_name = {r["name"]: r for r in results}
    figure_path = REPOSITORY / "doc" / "figures" / "pneumatics_elongation.png"
    figure_path.parent.mkdir(exist_ok=True)
    figure(figure_path, by_name)
    lines = ["# Pneumatic actuation of the bellows", "",
             "Generated by `./soft-robot.sh pneumatics` "
             "(`doc/pneumatics/run_pneumatics.py`); what the numbers mean and "
             "what follows from them is in "
             "[pneumatics_discussion.md](pneumatics_discussion.md).", ""]
    lines += run_lines(session) + [""]
    steps = sorted({round(by_name[n]["dt"], 6) for n in
                    [f"vacuum_{level}" for level in LEVELS] + ["hold"]
                    if n in by_name and "dt" in by_name[n]})
    step_text = ", ".join(f"{dt:g}" for dt in steps) if steps else "—"
    lines += ["## Experiment 1: released from a soft vacuum, and from the hold", "",
              "Dragon Skin 20, baseline parameter set, quarter model, 5.25 s at "
              f"dt = {step_text} s (the scenes' step). u0 is the tip block's initial "
              "displacement along the "
              "axis (mm, from the unloaded shape); f and ξ of the vertical motion "
              "by the half-power bandwidth (the study's method) and by the modal "
              "fit of tip-spectrum; B the energy balance at the end (µJ, HHT's "
              "algorithmic dissipation). Measured (FACTS.md): 4.20 Hz, ξ = 0.021.",
              "", "| case | status | u0 (mm) | half amplitude (mm) | f peak (Hz) "
              "| ξ half-power | f fit (Hz) | ξ fit | B (µJ) | wall (s) |",
              "|---|---|---|---|---|---|---|---|---|---|"]
    for name in [f"vacuum_{level}" for level in LEVELS] + ["hold"]:
        r = by_name.get(name)
        if r is None:
            continue
        lines.append(release_row(r))
    others = [(key, by_name.get(f"vacuum_{key}"), by_name.get(f"hold_{key}"))
              for key in OTHER_SILICONES]
    others = [o for o in others if o[1] is not None or o[2] is not None]
    if others:
        lines += ["", "The other silicones, each released from the vacuum level of its scene "
                  "(`parameters/bellows/vacuum_release_<silicone>_3d.prm`) and from the "
                  "half-weight hold; the same quantities.", "",
                  "| case | status | u0 (mm) | half amplitude (mm) | f peak (Hz) "
                  "| ξ half-power | f fit (Hz) | ξ fit | B (µJ) | wall (s) | measured f (Hz), ξ |",
                  "|---|---|---|---|---|---|---|---|---|---|---|"]
        for key, *runs in others:
            _, frequency, ratio = OTHER_SILICONES[key]
            for r in runs:
                if r is None:
                    continue
                lines.append(release_row(r) + f" {frequency:g}, {ratio:g} |")
    lines += ["", "## Inflation: the static curve", "",
              "Static equilibria of `parameters/bellows/inflation_ds20_3d.prm` "
              "(hanging under gravity, the gauge pressure p on the cavity wall). "
              "A_work is the centred difference "
              "dV/dδ of the cavity volume (whole body) by the tip displacement "
              "between the neighbouring pressures: the area with which an end "
              "load p A_work would do the pressure's work along this path.", "",
              "| p (kPa) | tip displacement (mm) | cavity volume (mm³) | A_work = dV/dδ (mm²) |",
              "|---|---|---|---|"]
    statics = [(float(p), by_name.get(f"static_{p}")) for p in PRESSURES]
    statics = [(p, r) for p, r in statics if r is not None and "u0" in r]
    for k, (p, r) in enumerate(statics):
        area = None
        if 0 < k < len(statics) - 1:
            before, after = statics[k - 1][1], statics[k + 1][1]
            area = (after["volume0"] - before["volume0"]) / (after["u0"] - before["u0"])
        lines.append(f"| {p:g} | {fmt(r['u0'], 5)} | {fmt(r.get('volume0'), 6)} | "
                     f"{fmt(area, 4)} |")
    by_pressure = {p: r for p, r in statics}
    if 0. in by_pressure and 8. in by_pressure:
        zero, eight = by_pressure[0.], by_pressure[8.]
        secant = (eight["volume0"] - zero["volume0"]) / (eight["u0"] - zero["u0"])
        lines += ["", f"Secant over 0 to 8 kPa: dV/dδ = {secant:.1f} mm²."]
    def tip(name):
        r = by_name.get(name)
        return r["u0"] if r is not None and "u0" in r else None

    def excess(values, key, added):
        """The elongation a reduced model adds from its hanging state, against
        the 3D model's `added`, in per cent."""
        if values.get(key) is None or values.get(0.) is None or not added:
            return "—"
        return f"{100. * ((values[key] - values[0.]) / added - 1.):+.1f} %"

    # the force-elongation curves, the hanging state (no force) first
    force_curves = {d: {0.: tip("static_0" if d == "3d" else f"static{d}_0")}
                    | {float(f): tip(prefix + f) for f in FORCES}
                    for d, prefix in (("3d", "force_"), ("1d", "force1d_"), ("2d", "force2d_"))}
    curve = sorted((f, u) for f, u in force_curves["3d"].items() if u is not None)
    volumes = [by_name.get("static_0")] + [by_name.get(f"force_{f}") for f in FORCES]
    volumes = [r["volume0"] for r in volumes if r is not None and "volume0" in r]
    lines += ["", "## The reduced models' end load against the 3D cavity", "",
              "The end force F on the tip block (whole body, pulling along the axis, "
              "no pressure) against the tip displacement δ of the 3D model and of the "
              "reduced 1D column and 2D strip, from their hanging equilibria; the "
              "differences are those of the elongation the force adds, δ − δ(0), from "
              "the 3D model's.", "",
              "| F (mN) | δ 3D (mm) | δ 1D (mm) | δ 2D (mm) | 1D against 3D | 2D against 3D |",
              "|---|---|---|---|---|---|"]
    for f, u in curve:
        added = u - force_curves["3d"][0.]
        lines.append(f"| {f:g} | {fmt(u, 5)} | "
                     + " | ".join(fmt(force_curves[d].get(f), 5) for d in ("1d", "2d"))
                     + " | " + " | ".join(excess(force_curves[d], f, added) if f else "—"
                                          for d in ("1d", "2d")) + " |")
    lines += ["", "The 3D model's response to the pressure and to the end force, side by "
              "side: F_eq is the end force that gives the 3D model the elongation the "
              "pressure p gives it (interpolated linearly on the force curve above), "
              "A_force = F_eq / p the force-equivalent area; ΔV is the cavity volume "
              "under the pressure less that of the 3D model pulled to the same δ by an "
              "end force (interpolated on the force curve). The last four columns are "
              "the reduced scenes' (`parameters/bellows/inflation_ds20_1d.prm`, "
              f"`inflation_ds20_2d.prm`), with their Equivalent area {REDUCED_AREA:g} mm² "
              f"and with the work-equivalent {WORK_AREA:g} mm² (the secant dV/dδ above), "
              "their elongation against the 3D model's as above.", "",
              "| p (kPa) | δ 3D (mm) | F_eq (mN) | A_force (mm²) | ΔV (mm³) "
              f"| 1D, {REDUCED_AREA:g} mm² | 2D, {REDUCED_AREA:g} mm² "
              f"| 1D, {WORK_AREA:g} mm² | 2D, {WORK_AREA:g} mm² |",
              "|---|---|---|---|---|---|---|---|---|"]
    reduced = {(d, prefix): {float(p): tip(f"{prefix}{d}_{p}") for p in PRESSURES}
               for d in REDUCED_INFLATION for prefix in ("static", "work")}
    forces, elongations = (np.array(v) for v in zip(*curve))
    on_force_path = len(volumes) == len(curve)
    for p, r in statics:
        f_eq = area = extra = None
        if p > 0 and elongations[0] <= r["u0"] <= elongations[-1]:
            f_eq = float(np.interp(r["u0"], elongations, forces))
            area = f_eq / p
            if on_force_path:
                extra = r["volume0"] - float(np.interp(r["u0"], elongations, volumes))
        added = r["u0"] - by_pressure[0.]["u0"]
        cells = [fmt(r["u0"], 5), fmt(f_eq, 4), fmt(area, 4), fmt(extra, 4)]
        cells += [excess(reduced[(d, prefix)], p, added) if p else "—"
                  for prefix in ("static", "work") for d in REDUCED_INFLATION]
        lines.append(f"| {p:g} | " + " | ".join(cells) + " |")
    runs = [(d, by_name.get("inflation" if d == "3d" else f"inflation_{d}"))
            for d in ("3d", "1d", "2d")]
    runs = [(d, r) for d, r in runs if r is not None and "u_end_of_ramp" in r]
    if runs:
        lines += ["", "## Inflation: ramp, hold, vent", "",
                  "`parameters/bellows/inflation_ds20_3d.prm` and its reduced 1D and 2D "
                  "scenes: 0 to 8 kPa in 1 s, held 1 s, vented in 20 ms, 1 s more.", "",
                  "| quantity | " + " | ".join(d.upper() for d, _ in runs) + " |",
                  "|---|" + "---|" * len(runs)]
        rows = [("status, wall time (s)",
                 lambda r: f"{r.get('status')}, {r['measured_seconds']:.0f}"),
                ("tip displacement at the start (hanging), mm", lambda r: fmt(r["u0"], 5)),
                ("at the end of the ramp, mm", lambda r: fmt(r["u_end_of_ramp"], 5)),
                ("during the hold, min / max, mm",
                 lambda r: f"{fmt(r['u_held_min'], 5)} / {fmt(r['u_held_max'], 5)}"),
                ("after the vent, min / max, mm",
                 lambda r: f"{fmt(r['u_vented_min'], 5)} / {fmt(r['u_vented_max'], 5)}"),
                ("largest pressure work, µJ", lambda r: fmt(r.get("pressure_work_max"), 5)),
                ("energy balance at the end, µJ", lambda r: fmt(r["balance_end"], 4))]
        for label, cell in rows:
            lines.append(f"| {label} | " + " | ".join(cell(r) for _, r in runs) + " |")
    lines += ["", "![elongation against pressure](figures/pneumatics_elongation.png)", "",
              "Elongation against pressure: the static curve (dots) and the tip of the "
              "inflation scene (lines), written by this script from the runs listed "
              "above" + (f" (commit `{session['runs'][-1]['commit']}`)."
                         if session.get("runs") else ".")]
    drives = [by_name.get(f"drive_{f}") for f in DRIVES]
    drives = [r for r in drives if r is not None and "drive_amplitude" in r]
    if drives:
        resonance_figure(REPOSITORY / "doc" / "figures" / "pneumatics_resonance.png", by_name)
        lines += ["", "## A sinusoidal pressure: the resonance curve", "",
                  "`parameters/bellows/oscillation_ds20_3d.prm`: the hanging actuator "
                  "under p = 0.2 kPa sin(2π f t) for 10 s. The amplitude is that of the "
                  f"tip displacement's component at f, fitted after {STEADY:g} s; the "
                  "half range of the last 2 s includes what is left of the free "
                  "vibration.", "",
                  "| f (Hz) | amplitude at f (mm) | half range, last 2 s (mm) | status | wall (s) |",
                  "|---|---|---|---|---|"]
        for r in drives:
            lines.append(f"| {r['drive_frequency']:g} | {fmt(r['drive_amplitude'], 4)} | "
                         f"{fmt(r['half_range_last_2s'], 4)} | {r.get('status')} | "
                         f"{r['measured_seconds']:.0f} |")
        lines += ["", "![resonance curve](figures/pneumatics_resonance.png)", "",
                  "The tip's amplitude at the drive frequency against that frequency, "
                  "written by this script from the runs listed above."]
    path.write_text("\n".join(lines) + "\n")
    print(f"wrote {path}")


if __name__ == "__main__":
    study_main(__doc__, "doc/pneumatics/run_pneumatics.py", "output/pneumatics",
               "doc/pneumatics.md", CASE_NAMES, run_case, load_case, write_report)
