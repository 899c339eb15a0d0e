#!/usr/bin/python3
# SPDX-License-Identifier: LGPL-2.1-or-later
"""The protocol study of the validation (issue 25): how the predictions of
experiments 2 and 3 depend on what the study does not give, the size and
direction of the push and the out-of-plane start. Model A of Dragon Skin
20 (the calibrated scenes planar_ds20_3d_calibrated.prm and
spherical_ds20_3d_calibrated.prm, run as they are) under

- experiment 2: half, once and twice the scenes' push of 958.4 mN per
  direction, sideways and down, and the scenes' sideways part alone;
- experiment 3: the scenes' start (a shear field, 200 mm/s at the tip
  block) and a rigid rotation about the base at 100 and 200 mm/s at
  x = 94.25 (the block's centre in the unloaded body).

    /usr/bin/python3 doc/protocol/run_protocol.py build-release
        [--cases a,b] [--timeout 7200] [--threads 1] [--report-only]

It writes doc/protocol.md and its figures, doc/figures/protocol/; the
discussion is the section "Protocol study" of
doc/validation_discussion.md. Nothing here is a test: the numbers are
reported, not checked.
"""

import json
import os
import shutil
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent))
sys.path.insert(0, str(HERE.parent / "reference"))
sys.path.insert(0, str(HERE.parent / "stability"))
from run_reference import read_statistics  # noqa: E402
from run_stability import run_program  # noqa: E402
from study_session import REPOSITORY, run_lines, study_main  # noqa: E402
from validation_report import (AXIAL_WINDOW, BOBBING_WINDOW,  # noqa: E402
                               DIRECTIONS, MEASURED, plt, read_magnitudes,
                               read_spectrum_table, save_small_png,
                               vertical_candidates)

PUSH = 1.08824  # kPa on the cylindrical block's face: the scenes' 958.4 mN
ROTATION = ("-v_tip * z / 109.5; 0; v_tip * (x + 15.25) / 109.5")

# name, experiment, scene, protocol, --set entries
PLANAR = "parameters/bellows/planar_ds20_3d_calibrated.prm"
SPHERICAL = "parameters/bellows/spherical_ds20_3d_calibrated.prm"
CASES = [
    ("planar_push_half", 2, PLANAR, "half the push, sideways and down",
     [f"Loads and constraints/Function constants=push={PUSH / 2:g}"]),
    ("planar_push_scene", 2, PLANAR, "the scenes' push, sideways and down", []),
    ("planar_push_double", 2, PLANAR, "twice the push, sideways and down",
     [f"Loads and constraints/Function constants=push={2 * PUSH:g}"]),
    ("planar_push_sideways", 2, PLANAR, "the scenes' sideways part only",
     ["Loads and constraints/Traction=0; (t <= 0 && x > 99.2) ? push : 0; 0"]),
    ("spherical_shear_200", 3, SPHERICAL,
     "the scenes' start: a shear field, 200 mm/s at the block", []),
    ("spherical_rotation_100", 3, SPHERICAL,
     "a rigid rotation about the base, 100 mm/s at x = 94.25",
     [f"Loads and constraints/Function constants=push={PUSH:g}, v_tip=100",
      f"Initial conditions/Velocity={ROTATION}",
      "Initial conditions/Velocity coordinates=initial state"]),
    ("spherical_rotation_200", 3, SPHERICAL,
     "a rigid rotation about the base, 200 mm/s at x = 94.25",
     [f"Loads and constraints/Function constants=push={PUSH:g}, v_tip=200",
      f"Initial conditions/Velocity={ROTATION}",
      "Initial conditions/Velocity coordinates=initial state"]),
]
CASE_NAMES = [c[0] for c in CASES]
SCENE_CASE = {2: "planar_push_scene", 3: "spherical_shear_200"}
TITLES = {2: "Experiment 2, the planar pendulum (half model)",
          3: "Experiment 3, the spherical pendulum (full model)"}
AXIAL = MEASURED["ds20"][0]  # model A rings at the measured frequency


def run_case(build, output_root, name, timeout, threads):
    _, _, scene, _, entries = next(c for c in CASES if c[0] == name)
    output = output_root / name
    if output.exists():
        shutil.rmtree(output)
    output.mkdir(parents=True)
    command = [str(build / "soft-robot"), scene,
               "--set", f"Problem/Output directory={output}",
               "--set", "Output/Write VTU=false"]
    for entry in entries:
        command += ["--set", entry]
    environment = {"OMP_NUM_THREADS": "1", "DEAL_II_NUM_THREADS": str(threads)}
    print(f"[{name}]", flush=True)
    _, result = run_program(command, dict(os.environ, **environment), output,
                            timeout)
    (output / "result.json").write_text(json.dumps(result))
    print(f"    {result['status']}", flush=True)


def load_case(output_root, name):
    output = output_root / name
    path = output / "result.json"
    if not path.exists():
        return None
    result = json.loads(path.read_text())
    result.update(read_statistics(output))
    result["name"] = name
    if result["status"] == "finished":
        result["spectrum"] = read_spectrum_table(output / "tip_spectrum.csv")
        result["frequencies"], result["magnitudes"] = read_magnitudes(
            output / "tip_spectrum_magnitudes.csv")
    return result


# @sect{The report}
#
# Per direction the dominant peak and the damping ratio of its modal fit
# (as the validation report); in the vertical direction also the two candidates of
# doc/validation_report.py: the bobbing near twice the swing frequency and
# the axial mode near the frequency of experiment 1.

def modal(entry):
    if entry is None or entry["peak"] != "dominant":
        return "no peak"
    return f"{entry['f_peak_Hz']:.3f} Hz, ξ {entry['xi_fit']:.5f}"


def peak(candidate):
    return "no maximum" if candidate is None else \
        f"{candidate[0]:.3f} Hz ({candidate[1]:.3f} mm)"


def experiment_table(experiment, results):
    directions = DIRECTIONS[3 if experiment == 3 else 2]
    header = (["case", "protocol"] + [f"{d}: f, ξ" for d in directions] +
              ["vertical: bobbing", "vertical: axial mode", "larger",
               "cutbacks", "wall s"])
    lines = ["| " + " | ".join(header) + " |",
             "|---|---|" + "---|" * len(directions) + "---|---|---|---:|---:|"]
    for name, e, _, protocol, _ in CASES:
        result = results.get(name)
        if e != experiment or result is None:
            continue
        if result["status"] != "finished":
            lines.append(f"| {name} | {protocol} | {result['status']}: "
                         f"{result.get('message', '')} |")
            continue
        bobbing, axial = vertical_candidates(result, AXIAL)
        larger = "—"
        if bobbing and axial:
            larger = "bobbing" if bobbing[1] > axial[1] else "axial"
        lines.append("| " + " | ".join(
            [name, protocol] + [modal(result["spectrum"].get(d)) for d in directions] +
            [peak(bobbing), peak(axial), larger, str(result.get("cutbacks", "—")),
             f"{result.get('wall_seconds', float('nan')):.0f}"]) + " |")
    return lines


def range_lines(experiment, results):
    """Each direction's dominant frequency over the finished protocols,
    relative to the scenes' protocol."""
    base = results.get(SCENE_CASE[experiment])
    finished = [r for name, e, *_ in CASES if e == experiment
                for r in [results.get(name)] if r and r["status"] == "finished"]
    if base is None or base["status"] != "finished" or len(finished) < 2:
        return []
    lines = ["", f"Over the {len(finished)} protocols run, relative to the scenes' "
             "protocol:", ""]
    for direction in DIRECTIONS[3 if experiment == 3 else 2]:
        values = [r["spectrum"][direction]["f_peak_Hz"] for r in finished
                  if r["spectrum"][direction]["peak"] == "dominant"]
        reference = base["spectrum"][direction]
        if reference["peak"] != "dominant" or not values:
            continue
        f0 = reference["f_peak_Hz"]
        lines.append(f"- {direction}: {min(values):.3f} to {max(values):.3f} Hz, "
                     f"{100 * (min(values) / f0 - 1):+.1f} % to "
                     f"{100 * (max(values) / f0 - 1):+.1f} % about {f0:.3f} Hz "
                     f"({len(values)} of {len(finished)} with a peak)")
    return lines


def plot_experiment(experiment, results, path):
    directions = DIRECTIONS[3 if experiment == 3 else 2]
    figure, axes = plt.subplots(len(directions), 1, figsize=(8, 2.4 * len(directions)),
                                sharex=True)
    styles = ["--", "-.", ":"]
    colours = ["#1f4fd8", "#d62020", "#109030", "#9040c0"]
    shown = [(name, protocol) for name, e, _, protocol, _ in CASES
             if e == experiment and results.get(name)
             and results[name]["status"] == "finished"]
    for axis, direction in zip(axes, directions):
        for k, (name, protocol) in enumerate(shown):
            r = results[name]
            f = r["frequencies"]
            window = (f >= 0.3) & (f <= 8.)
            scene = name == SCENE_CASE[experiment]
            axis.semilogy(f[window], np.maximum(r["magnitudes"][direction][window], 1e-6),
                          "-" if scene else styles[k % 3], lw=1.4 if scene else 1.2,
                          color="k" if scene else colours[k % len(colours)],
                          label=protocol)
        if direction == "vertical":
            axis.axvline(AXIAL, color="k", ls=":", lw=0.8,
                         label=f"experiment 1, {AXIAL:.2f} Hz")
        axis.set_ylabel(f"{direction} [mm]")
        axis.grid(True, alpha=0.3)
    axes[0].legend(fontsize=7, loc="upper right")
    axes[-1].set_xlabel("frequency [Hz]")
    figure.suptitle(f"{TITLES[experiment]}, model A of Dragon Skin 20:\namplitude "
                    "spectra of the tip motion under the protocols", fontsize=9)
    figure.tight_layout()
    path.parent.mkdir(parents=True, exist_ok=True)
    save_small_png(figure, path)
    plt.close(figure)


def write_report(path, results, session):
    by_name = {r["name"]: r for r in results}
    lines = ["<!-- Written by doc/protocol/run_protocol.py; the discussion is "
             "in doc/validation_discussion.md, \"Protocol study\". -->",
             "# The protocols of experiments 2 and 3", "",
             "The discussion of these results is in "
             "[validation_discussion.md](validation_discussion.md#protocol-study).", ""]
    lines += run_lines(session)
    lines += ["", "Model A of Dragon Skin 20 (the calibrated scenes, as they are: "
              "quadratic hexahedra with the linear dilatation, mu = 731.6 kPa, "
              "dt = 0.01 s, 6 s). Per direction the frequency of the dominant "
              "peak of the tip motion after the first second and the damping "
              "ratio of its modal fit; in the vertical direction also the largest local maxima of the amplitude "
              "spectrum within "
              f"{round(100 * BOBBING_WINDOW)} % of twice the horizontal "
              f"frequency (the bobbing) and within {round(100 * AXIAL_WINDOW)} % "
              f"of the measured experiment-1 frequency, {AXIAL:.2f} Hz, which "
              "model A reproduces (the axial mode), with their amplitudes."]
    for experiment in (2, 3):
        lines += ["", f"## {TITLES[experiment]}", ""]
        lines += experiment_table(experiment, by_name)
        lines += range_lines(experiment, by_name)
        figure = REPOSITORY / "doc" / "figures" / "protocol" / f"experiment_{experiment}.png"
        if any(by_name.get(name, {}).get("status") == "finished"
               for name, e, *_ in CASES if e == experiment):
            plot_experiment(experiment, by_name, figure)
            lines += ["", f"![Spectra, experiment {experiment}]"
                      f"(figures/protocol/experiment_{experiment}.png)"]
    path.write_text("\n".join(lines) + "\n")
    print(f"wrote {path}")


if __name__ == "__main__":
    study_main(__doc__, "doc/protocol/run_protocol.py", "output/protocol",
               "doc/protocol.md", CASE_NAMES, run_case, load_case, write_report)
