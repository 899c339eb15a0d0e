#!/usr/bin/python3
# SPDX-License-Identifier: LGPL-2.1-or-later
"""Write the validation report of the 30 bellows scenes against the study.

Usage: /usr/bin/python3 doc/validation_report.py OUTPUT_DIR DOC_DIR

Reads OUTPUT_DIR/<scene>/{tip_trajectory.csv, tip_spectrum.csv,
tip_spectrum_magnitudes.csv, run.log, wall_seconds, run_info} for every
scene and
writes DOC_DIR/validation.md and DOC_DIR/figures/validation/<scene>.png.
Below its header the report links to the hand-written discussion of the
results, DOC_DIR/validation_discussion.md.

All scenes are read and checked before anything is written; a missing or
incomplete file stops the script with a message naming it. The markdown is
written to a temporary file and renamed at the end, so an existing report
is never left half-written.

Needs numpy and matplotlib (Debian's python3-numpy, python3-matplotlib),
and Pillow, which matplotlib itself depends on.
"""
import csv
import datetime
import io
import os
import re
import subprocess
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
from PIL import Image


# @sect{The scenes and the reference numbers}

SILICONES = {"ef50": "Ecoflex 00-50", "ds20": "Dragon Skin 20",
             "ds30": "Dragon Skin 30"}
PARAMETER_SETS = {"baseline": "", "calibrated": "_calibrated"}

# Scene kinds in report order: (name prefix, dimension suffix, experiment,
# model description). The dimension of the model is the number in the suffix.
KINDS = [("vertical", "3d", 1, "3D quarter model"),
         ("column", "1d", 1, "1D column"),
         ("planar", "3d", 2, "3D half model"),
         ("planar", "2d", 2, "2D strip"),
         ("spherical", "3d", 3, "3D full model")]

EXPERIMENTS = {1: "Experiment 1: vertical oscillation",
               2: "Experiment 2: planar pendulum (prediction)",
               3: "Experiment 3: spherical pendulum (prediction)"}

# The spectral directions the program analyses for a trajectory with one,
# two or three displacement components (vertical = x; for three components
# horizontal and depth are the axes of the best-fit plane of the (y,z)
# motion, not y and z themselves).
DIRECTIONS = {1: ["vertical"], 2: ["vertical", "horizontal"],
              3: ["vertical", "horizontal", "depth"]}

# The directions the tables of the pendulum experiments report (experiment
# 1 reports the vertical direction only).
PREDICTION_DIRECTIONS = {2: ["vertical", "horizontal"],
                         3: ["vertical", "horizontal", "depth"]}

# Experiment 1 of the study: measured and simulated (by the reference)
# frequency in Hz and damping ratio.
MEASURED = {"ef50": (2.05, 0.041), "ds20": (4.20, 0.021),
            "ds30": (5.57, 0.035)}
REFERENCE_SIMULATION = {"ef50": (2.06, 0.040), "ds20": (4.33, 0.023),
                        "ds30": (5.44, 0.035)}

# Cost of the reference simulations: (linear tetrahedra, wall time in s,
# threads) per experiment.
REFERENCE_COST = {1: (1743, 1800, 4), 2: (3670, 5000, 4),
                  3: (4178, 2200, 4)}
REFERENCE_MODEL = {1: "quarter model", 2: "half model", 3: "full model"}

# One colour per direction, used for the displacement component along the
# same axis as well.
COLOURS = {"vertical": "C0", "horizontal": "C1", "depth": "C2"}
COMPONENTS = [("u_x", "vertical"), ("u_y", "horizontal"), ("u_z", "depth")]

FILES = ["tip_trajectory.csv", "tip_spectrum.csv",
         "tip_spectrum_magnitudes.csv", "run.log", "wall_seconds", "run_info"]

# The entries of run_info, which ./soft-robot.sh validate writes for every
# scene: the commit and the inputs (a digest of the committed sources,
# parameters and meshes, or 'modified') it ran from, its threads, the
# scenes run at a time, and the start of the invocation of validate.
RUN_INFO = ["commit", "inputs", "threads", "jobs", "set"]


class ReportError(Exception):
    """A missing or incomplete input file; the message names it."""


def scene_list():
    """All scenes as dictionaries, in report order."""
    scenes = []
    for prefix, suffix, experiment, model in KINDS:
        for key, silicone in SILICONES.items():
            for set_name, set_suffix in PARAMETER_SETS.items():
                scenes.append({
                    "name": "%s_%s_%s%s" % (prefix, key, suffix, set_suffix),
                    "key": key, "silicone": silicone,
                    "parameter_set": set_name, "experiment": experiment,
                    "model": model, "dim": int(suffix[0])})
    return scenes


# @sect{Reading the output of one scene}

def read_trajectory(path):
    """Time and displacement columns of tip_trajectory.csv (mm, s)."""
    with open(path) as stream:
        lines = [line.strip() for line in stream
                 if line.strip() and not line.startswith("#")]
    if len(lines) < 2:
        raise ReportError("%s: no data rows after the header" % path)
    names = lines[0].split(",")
    rows = []
    for number, line in enumerate(lines[1:], start=2):
        fields = line.split(",")
        if len(fields) != len(names):
            raise ReportError("%s: data row %d has %d fields, the header %d "
                              "(truncated file?)"
                              % (path, number, len(fields), len(names)))
        try:
            rows.append([float(value) for value in fields])
        except ValueError:
            raise ReportError("%s: data row %d is not numeric"
                              % (path, number))
    data = np.array(rows)
    columns = {name: data[:, k] for k, name in enumerate(names)}
    if "t" not in columns or "u_x" not in columns:
        raise ReportError("%s: the header lacks t or u_x" % path)
    return {name: columns[name] for name in ["t", "u_x", "u_y", "u_z"]
            if name in columns}


def optional_float(text):
    """A number, or None for an empty field (not determined)."""
    return float(text) if text.strip() else None


def read_spectrum_table(path):
    """The dominant row (or the 'none' row) of each direction."""
    numeric = ["f_peak_Hz", "magnitude", "xi_half_power", "xi_fit", "cycles",
               "sample_rate_Hz"]
    with open(path, newline="") as stream:
        reader = csv.DictReader(stream)
        missing = [name for name in numeric + ["direction", "peak", "warnings"]
                   if name not in (reader.fieldnames or [])]
        if missing:
            raise ReportError("%s: the header lacks %s"
                              % (path, ", ".join(missing)))
        directions = {}
        for row in reader:
            if row["peak"] not in ("dominant", "none"):
                continue
            if None in row.values():
                raise ReportError("%s: the row of direction %s is too short"
                                  % (path, row["direction"]))
            entry = {"peak": row["peak"], "warnings": row["warnings"].strip()}
            try:
                entry.update({name: optional_float(row[name])
                              for name in numeric})
            except ValueError:
                raise ReportError("%s: a number in the row of direction %s "
                                  "does not parse" % (path, row["direction"]))
            if entry["peak"] == "dominant" and (entry["f_peak_Hz"] is None or
                                                entry["magnitude"] is None):
                raise ReportError("%s: the dominant peak of direction %s has "
                                  "no frequency or magnitude"
                                  % (path, row["direction"]))
            directions[row["direction"]] = entry
    return directions


def read_magnitudes(path):
    """Frequencies (Hz) and the amplitude spectrum per direction (mm)."""
    with open(path) as stream:
        lines = stream.read().splitlines()
    names = lines[0].split(",") if lines else []
    if not names or names[0] != "frequency_Hz" or len(lines) < 3:
        raise ReportError("%s: expected a header starting with frequency_Hz "
                          "and at least two frequencies" % path)
    try:
        data = np.loadtxt(lines[1:], delimiter=",", ndmin=2)
    except ValueError:
        raise ReportError("%s: ragged or non-numeric rows (truncated file?)"
                          % path)
    if data.shape[1] != len(names):
        raise ReportError("%s: %d columns in the header, %d in the rows"
                          % (path, len(names), data.shape[1]))
    spectra = {name[len("magnitude_"):]: data[:, k]
               for k, name in enumerate(names)
               if name.startswith("magnitude_")}
    return data[:, 0], spectra


def read_run_log(path):
    """Mesh, degrees of freedom and time-stepping statistics of run.log."""
    with open(path) as stream:
        text = stream.read()
    patterns = {
        "mesh": r"^Mesh: (\d+) (\w+) cells, (\d+) material\(s\)",
        "dofs": r"^Degrees of freedom: (\d+) \((.*), (\d+) MPI "
                r"process\(es\)\)",
        "finished": r"^Finished (\d+) steps in ([0-9.eE+-]+) s: (\d+) Newton "
                    r"iterations, (\d+) linear iterations, (?:\d+ matrix "
                    r"factorizations or multigrid set-ups, )?(\d+) time-step "
                    r"cutbacks\."}
    found = {}
    for key, pattern in patterns.items():
        matches = re.findall(pattern, text, re.MULTILINE)
        if not matches:
            raise ReportError("%s: no line matching '%s' (the run did not "
                              "finish?)" % (path, pattern))
        found[key] = matches[-1]
    cells, cell_type, _ = found["mesh"]
    dofs, element, processes = found["dofs"]
    steps, _, newton, _, cutbacks = found["finished"]
    return {"cells": int(cells), "cell_type": cell_type, "dofs": int(dofs),
            "element": element, "processes": int(processes),
            "steps": int(steps), "newton": int(newton),
            "cutbacks": int(cutbacks)}


def read_wall_seconds(path):
    """The total wall time of the run in seconds."""
    with open(path) as stream:
        text = stream.read().strip()
    try:
        return float(text)
    except ValueError:
        raise ReportError("%s: expected one number, found '%s'" % (path, text))


def read_wall_interval(path):
    """Start and end of the run (seconds since the epoch), if recorded."""
    if not path.is_file():
        return None
    values = path.read_text().split()
    try:
        start, end = (float(value) for value in values)
    except ValueError:
        raise ReportError("%s: expected two numbers, found '%s'"
                          % (path, " ".join(values)))
    return start, end


def read_run_info(path):
    """The entries of run_info as strings."""
    info = {}
    for line in path.read_text().splitlines():
        key, _, value = line.partition(" ")
        info[key] = value.strip()
    missing = [key for key in RUN_INFO if not info.get(key)]
    if missing:
        raise ReportError("%s: no entry %s" % (path, ", ".join(missing)))
    return info


def read_scene(output_dir, scene):
    """All outputs of one scene, checked for consistency with its model."""
    directory = Path(output_dir) / scene["name"]
    for name in FILES:
        if not (directory / name).is_file():
            raise ReportError("%s: missing" % (directory / name))
    trajectory = read_trajectory(directory / "tip_trajectory.csv")
    components = sum(name in trajectory for name in ["u_x", "u_y", "u_z"])
    if components != scene["dim"]:
        raise ReportError("%s: %d displacement components in a %dD scene"
                          % (directory / "tip_trajectory.csv", components,
                             scene["dim"]))
    expected = DIRECTIONS[scene["dim"]]
    spectrum = read_spectrum_table(directory / "tip_spectrum.csv")
    if sorted(spectrum) != sorted(expected):
        raise ReportError("%s: directions %s instead of %s"
                          % (directory / "tip_spectrum.csv",
                             ", ".join(sorted(spectrum)) or "none",
                             ", ".join(expected)))
    frequencies, magnitudes = read_magnitudes(
        directory / "tip_spectrum_magnitudes.csv")
    if sorted(magnitudes) != sorted(expected):
        raise ReportError("%s: magnitude columns for %s instead of %s"
                          % (directory / "tip_spectrum_magnitudes.csv",
                             ", ".join(sorted(magnitudes)) or "none",
                             ", ".join(expected)))
    # The spectrum runs up to the Nyquist frequency; a file that ends below
    # it was cut short.
    sample_rate = spectrum["vertical"]["sample_rate_Hz"]
    if sample_rate is None or abs(frequencies[-1] - sample_rate / 2.) \
            > 1e-6 * sample_rate:
        raise ReportError("%s: ends at %g Hz, not at the Nyquist frequency "
                          "(half the sample rate in tip_spectrum.csv; "
                          "truncated file?)"
                          % (directory / "tip_spectrum_magnitudes.csv",
                             frequencies[-1]))
    # The program writes one trajectory row for the initial state and one
    # per time step.
    log = read_run_log(directory / "run.log")
    rows = len(trajectory["t"])
    if rows != log["steps"] + 1:
        raise ReportError("%s: %d rows, but %s reports %d steps (truncated "
                          "file?)" % (directory / "tip_trajectory.csv", rows,
                                      directory / "run.log", log["steps"]))
    return dict(scene, trajectory=trajectory, spectrum=spectrum,
                frequencies=frequencies, magnitudes=magnitudes, log=log,
                wall=read_wall_seconds(directory / "wall_seconds"),
                interval=read_wall_interval(directory / "wall_interval"),
                info=read_run_info(directory / "run_info"))


def check_inputs(runs):
    """All scenes must have run from the same inputs, or the report would
    compare results of different programs."""
    inputs = sorted({run["info"]["inputs"] for run in runs})
    if len(inputs) > 1:
        raise ReportError(
            "the scenes ran from different inputs (%s; run_info of each "
            "scene); run ./soft-robot.sh validate again without --resume"
            % ", ".join(inputs))


# @sect{Number formatting}

DASH = "—"


def number(value, decimals):
    return DASH if value is None else "%.*f" % (decimals, value)


def frequency(value):
    return number(value, 3)


def damping(value):
    return number(value, 4)


def error_percent(value, measured):
    """Signed relative error in per cent (adding 0 turns -0.0 into 0.0)."""
    if value is None:
        return DASH
    return "%+.1f" % (round(100. * (value - measured) / measured, 1) + 0.)


def count(value):
    return "{:,}".format(value)


def escape(text):
    """Free text made safe for a markdown table cell."""
    for character in "\\|*_`":
        text = text.replace(character, "\\" + character)
    return text.replace("<", "&lt;")


def table(header, rows):
    """A markdown table as a list of lines."""
    lines = ["| " + " | ".join(header) + " |",
             "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(row) + " |" for row in rows]
    return lines


def scene_label(run):
    return "%s, %s, %s parameters" % (run["silicone"], run["model"],
                                      run["parameter_set"])


# @sect{The header}

def git_description(repository):
    """Short commit and whether tracked files differ from it."""
    try:
        commit = subprocess.run(
            ["git", "-C", str(repository), "rev-parse", "--short", "HEAD"],
            capture_output=True, text=True, check=True).stdout.strip()
        status = subprocess.run(
            ["git", "-C", str(repository), "status", "--porcelain"],
            capture_output=True, text=True, check=True).stdout
    except (OSError, subprocess.CalledProcessError):
        return "an unknown commit (git is unavailable)"
    # Untracked files ('??') do not change what was built.
    modified = [line for line in status.splitlines()
                if line and not line.startswith("??")]
    return "commit `%s`%s" % (commit, " (with uncommitted changes)"
                               if modified else "")


def cpu_model():
    try:
        with open("/proc/cpuinfo") as stream:
            for line in stream:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return "unknown CPU"


def joined(values, conjunction="or"):
    """'a', 'a or b', 'a, b or c'."""
    values = list(values)
    return (values[0] if len(values) == 1 else
            ", ".join(values[:-1]) + " %s " % conjunction + values[-1])


def header(runs, doc_dir):
    repository = Path(__file__).resolve().parent.parent
    processes = sorted({run["log"]["processes"] for run in runs})
    threads = sorted({run["info"]["threads"] for run in runs}, key=int)
    jobs = sorted({run["info"]["jobs"] for run in runs}, key=int)
    how = ("one MPI process each" if processes == [1] else
           "with %s MPI processes" % joined(map(str, processes)))
    how += " of %s thread(s) (DEAL_II_NUM_THREADS)" % joined(threads)
    commits = sorted({run["info"]["commit"] for run in runs})
    inputs = runs[0]["info"]["inputs"]
    source = ("commit `%s`" % commits[0] if len(commits) == 1 else
              "commits %s, which have the same sources, parameters and "
              "meshes" % joined(("`%s`" % commit for commit in commits), "and"))
    if inputs == "modified":
        source += " with uncommitted changes of the sources, parameters " \
                  "or meshes"
    date = datetime.datetime.now().astimezone().strftime("%Y-%m-%d %H:%M %Z")
    lines = [
        "# Validation against the reference study", "",
        "Generated by `./soft-robot.sh validate` (through "
        "`doc/validation_report.py`) at %s on %s, on a machine with %s cores "
        "(%s). The %d scenes ran from %s, %s at a time (SOFT_ROBOT_JOBS), "
        "%s; wall times are those of each scene, including set-up and the "
        "static initial state."
        % (git_description(repository), date, os.cpu_count(), cpu_model(),
           len(runs), source, joined(jobs), how), ""]
    lines += ["The discussion of these results is in "
              "[validation_discussion.md](validation_discussion.md).", ""]
    return lines


# @sect{The tables}

def dominant_columns(entry):
    """f_peak, xi half-power and xi fit of one direction, or 'no peak'."""
    if entry["peak"] == "none":
        return ["no peak", DASH, DASH]
    return [frequency(entry["f_peak_Hz"]), damping(entry["xi_half_power"]),
            damping(entry["xi_fit"])]


def cost_columns(run):
    return [count(run["log"]["cells"]), count(run["log"]["dofs"]),
            number(run["wall"], 1)]


def reference_cost_sentence(experiment):
    cells, seconds, threads = REFERENCE_COST[experiment]
    return ("Cost of the reference simulation: %s, %s linear tetrahedra, "
            "about %s s on %d threads."
            % (REFERENCE_MODEL[experiment], count(cells), count(seconds),
               threads))


def experiment_1(runs):
    header_row = ["silicone", "model", "parameter set", "f_peak (Hz)",
                  "error vs measured (%)", "ξ half-power",
                  "error vs measured (%)", "ξ modal fit", "cycles in record",
                  "cells", "dofs", "wall time (s)"]
    cells, seconds, threads = REFERENCE_COST[1]
    rows = []
    for key, silicone in SILICONES.items():
        f_measured, xi_measured = MEASURED[key]
        f_reference, xi_reference = REFERENCE_SIMULATION[key]
        rows.append([silicone, "measured", DASH, frequency(f_measured), DASH,
                     damping(xi_measured), DASH, DASH, DASH, DASH, DASH, DASH])
        rows.append([silicone, "reference simulation (quarter model)", DASH,
                     frequency(f_reference),
                     error_percent(f_reference, f_measured),
                     damping(xi_reference),
                     error_percent(xi_reference, xi_measured), DASH, DASH,
                     count(cells), DASH,
                     "≈ %s (%d threads)" % (count(seconds), threads)])
        for run in runs:
            if run["experiment"] != 1 or run["key"] != key:
                continue
            vertical = run["spectrum"]["vertical"]
            if vertical["peak"] == "none":
                results = ["no peak"] + [DASH] * 5
            else:
                results = [frequency(vertical["f_peak_Hz"]),
                           error_percent(vertical["f_peak_Hz"], f_measured),
                           damping(vertical["xi_half_power"]),
                           error_percent(vertical["xi_half_power"],
                                         xi_measured),
                           damping(vertical["xi_fit"]),
                           number(vertical["cycles"], 1)]
            rows.append([silicone, run["model"], run["parameter_set"]]
                        + results + cost_columns(run))
    return (["## " + EXPERIMENTS[1], "",
             "Frequency and damping ratio of the vertical tip motion "
             "(dominant spectral peak). The measured values and the reference "
             "simulation are those of the study; the errors are relative to "
             "the measured values. The half-power damping ratio is biased "
             "high when the record holds few cycles of a lightly damped "
             "oscillation; the warnings below estimate the bias.",
             ""]
            + table(header_row, rows)
            + ["", reference_cost_sentence(1), ""])


def prediction_table(runs, experiment):
    directions = PREDICTION_DIRECTIONS[experiment]
    header_row = ["silicone", "model", "parameter set"]
    for direction in directions:
        header_row += ["%s f_peak (Hz)" % direction,
                       "%s ξ half-power" % direction,
                       "%s ξ fit" % direction]
    header_row += ["cells", "dofs", "wall time (s)"]
    rows = []
    for key, silicone in SILICONES.items():
        for run in runs:
            if run["experiment"] != experiment or run["key"] != key:
                continue
            row = [silicone, run["model"], run["parameter_set"]]
            for direction in directions:
                row += dominant_columns(run["spectrum"][direction])
            rows.append(row + cost_columns(run))
    note = ("The study publishes no numbers for this experiment: these are "
            "predictions. Dominant spectral peak per direction of the tip "
            "motion; in the 3D models, horizontal and depth are the axes of "
            "the best-fit plane of the horizontal (y, z) motion.")
    return (["## " + EXPERIMENTS[experiment], "", note, ""]
            + table(header_row, rows)
            + ["", reference_cost_sentence(experiment), ""]
            + candidates_table(runs, experiment))


# @sect{The two candidates of the vertical motion of a pendulum}
#
# A pendulum that stretches bobs at twice its swing frequency, and its
# release also rings the axial mode of experiment 1. Either can dominate
# the vertical spectrum, depending on the protocol (the push's size and
# the out-of-plane speed; doc/validation_discussion.md, "Protocol
# study"). Each candidate is the largest local maximum of the vertical
# amplitude spectrum in a window around where it is expected: the bobbing
# within 10 % of twice the dominant horizontal frequency, the axial mode
# within 15 % of the frequency of experiment 1 on the same silicone and
# parameter set (3D quarter model), outside the bobbing's window.

BOBBING_WINDOW = 0.10
AXIAL_WINDOW = 0.15


def local_maximum(frequencies, magnitude, centre, half_width, excluded=None):
    """Frequency and amplitude of the largest local maximum of the spectrum
    within centre * (1 +- half_width), or None; a maximum inside the
    excluded (lower, upper) interval does not count."""
    lower, upper = centre * (1. - half_width), centre * (1. + half_width)
    best = None
    for k in range(1, len(frequencies) - 1):
        f = frequencies[k]
        if not lower <= f <= upper:
            continue
        if excluded and excluded[0] <= f <= excluded[1]:
            continue
        if magnitude[k] >= magnitude[k - 1] and magnitude[k] >= magnitude[k + 1]:
            if best is None or magnitude[k] > best[1]:
                best = (f, magnitude[k])
    return best


def companion(runs, run, experiment, model):
    """The run of `experiment` on `model` with run's silicone and parameter
    set."""
    return next(r for r in runs if r["experiment"] == experiment
                and r["model"] == model and r["key"] == run["key"]
                and r["parameter_set"] == run["parameter_set"])


def vertical_candidates(run, axial_frequency):
    """The bobbing and the axial candidate of a pendulum's vertical motion
    as ((f, amplitude) or None, (f, amplitude) or None); axial_frequency
    (Hz, or None) is where experiment 1 locates the axial mode."""
    horizontal = run["spectrum"]["horizontal"]
    frequencies = run["frequencies"]
    magnitude = run["magnitudes"]["vertical"]
    bobbing = None
    excluded = None
    if horizontal["peak"] == "dominant":
        twice = 2. * horizontal["f_peak_Hz"]
        bobbing = local_maximum(frequencies, magnitude, twice, BOBBING_WINDOW)
        excluded = (twice * (1. - BOBBING_WINDOW), twice * (1. + BOBBING_WINDOW))
    axial = None
    if axial_frequency is not None:
        axial = local_maximum(frequencies, magnitude, axial_frequency,
                              AXIAL_WINDOW, excluded)
    return bobbing, axial


def candidates_table(runs, experiment):
    header_row = ["silicone", "model", "parameter set",
                  "twice the swing (Hz)", "bobbing f (Hz)",
                  "bobbing amplitude (mm)", "axial mode of experiment 1 (Hz)",
                  "axial f (Hz)", "axial amplitude (mm)", "larger"]
    rows = []
    for run in runs:
        if run["experiment"] != experiment or run["dim"] != 3:
            continue
        axial_run = companion(runs, run, 1, "3D quarter model")
        axial_vertical = axial_run["spectrum"]["vertical"]
        bobbing, axial = vertical_candidates(
            run, axial_vertical["f_peak_Hz"]
            if axial_vertical["peak"] == "dominant" else None)
        horizontal = run["spectrum"]["horizontal"]
        larger = DASH
        if bobbing and axial:
            larger = "bobbing" if bobbing[1] > axial[1] else "axial"
        rows.append([run["silicone"], run["model"], run["parameter_set"],
                     frequency(2. * horizontal["f_peak_Hz"])
                     if horizontal["peak"] == "dominant" else DASH,
                     frequency(bobbing[0]) if bobbing else "no maximum",
                     number(bobbing[1], 3) if bobbing else DASH,
                     frequency(axial_run["spectrum"]["vertical"]["f_peak_Hz"]),
                     frequency(axial[0]) if axial else "no maximum",
                     number(axial[1], 3) if axial else DASH, larger])
    if experiment != 2:
        return (["The two candidates of the vertical motion, as in experiment "
                 "2:", ""] + table(header_row, rows) + [""])
    return (["The two candidates of the vertical motion: the bobbing at twice "
             "the swing frequency and the axial mode that experiment 1 "
             "measures. Each is the largest local maximum of the vertical "
             "amplitude spectrum within %d %% of twice the dominant horizontal "
             "frequency, and within %d %% of the frequency of experiment 1 on "
             "the same silicone and parameter set (outside the bobbing's "
             "window)." % (round(100 * BOBBING_WINDOW), round(100 * AXIAL_WINDOW)),
             ""] + table(header_row, rows) + [""])


# @sect{The reduced models against the 3D model}

def reduced_models_table(runs):
    """The 1D column against the 3D quarter model (experiment 1, vertical)
    and the 2D strip against the 3D half model (experiment 2, horizontal)."""
    header_row = ["experiment", "silicone", "parameter set", "reduced model",
                  "f (Hz)", "3D f (Hz)", "difference (%)", "ξ fit", "3D ξ fit",
                  "wall time (s)", "3D wall time (s)"]
    pairs = [(1, "1D column", "3D quarter model", "vertical"),
             (2, "2D strip", "3D half model", "horizontal")]
    rows = []
    for experiment, reduced_model, full_model, direction in pairs:
        for run in runs:
            if run["experiment"] != experiment or run["model"] != reduced_model:
                continue
            full = companion(runs, run, experiment, full_model)
            a, b = run["spectrum"][direction], full["spectrum"][direction]
            both = a["peak"] == "dominant" and b["peak"] == "dominant"
            rows.append([str(experiment), run["silicone"], run["parameter_set"],
                         reduced_model,
                         frequency(a["f_peak_Hz"]) if a["peak"] == "dominant" else DASH,
                         frequency(b["f_peak_Hz"]) if b["peak"] == "dominant" else DASH,
                         error_percent(a["f_peak_Hz"], b["f_peak_Hz"]) if both else DASH,
                         damping(a["xi_fit"]), damping(b["xi_fit"]),
                         number(run["wall"], 1), number(full["wall"], 1)])
    return (["## The reduced models against the 3D model", "",
             "The 1D column and the 2D strip take their geometry from the 3D "
             "model (`calibrate reduced-models`). Their dominant frequency "
             "against that of the 3D scene of the same experiment, silicone "
             "and parameter set (experiment 1: the vertical motion; "
             "experiment 2: the swing), and the cost of each.", ""]
            + table(header_row, rows) + [""])


def peak_to_peak(trajectory, component):
    if component not in trajectory:
        return DASH
    values = trajectory[component]
    return "%.2f" % (values.max() - values.min())


def runs_table(runs):
    header_row = ["scene", "steps", "Newton iterations per step", "cutbacks",
                  "cells", "element", "dofs", "wall time (s)",
                  "peak-to-peak u_x (mm)", "peak-to-peak u_y (mm)",
                  "peak-to-peak u_z (mm)"]
    rows = []
    for run in runs:
        log = run["log"]
        rows.append(["`%s`" % run["name"], count(log["steps"]),
                     number(log["newton"] / log["steps"], 2)
                     if log["steps"] else DASH,
                     count(log["cutbacks"]),
                     "%s %s" % (count(log["cells"]), log["cell_type"]),
                     "`%s`" % log["element"], count(log["dofs"]),
                     number(run["wall"], 1)]
                    + [peak_to_peak(run["trajectory"], component)
                       for component, _ in COMPONENTS])
    total = sum(run["wall"] for run in runs)
    three_d = [run for run in runs if run["dim"] == 3]
    total_3d = sum(run["wall"] for run in three_d)
    return (["## Runs", "",
             "Time-stepping statistics from each run's log, and the tip's "
             "peak-to-peak displacement over the whole run.", ""]
            + table(header_row, rows)
            + ["", "Total wall time of the %d scenes: %s s (%.2f h); of the "
               "%d 3D scenes alone: %s s (%.2f h)."
               % (len(runs), number(total, 1), total / 3600., len(three_d),
                  number(total_3d, 1), total_3d / 3600.)]
            + elapsed_line(runs) + [""])


def elapsed_line(runs):
    """The wall time of the whole set, from the first start to the last
    end, when every run recorded its interval and all ran in one
    invocation of validate."""
    intervals = [run.get("interval") for run in runs]
    if not intervals or any(interval is None for interval in intervals):
        return []
    invocations = {run["info"]["set"] for run in runs}
    if len(invocations) > 1:
        return ["The scenes ran in %d invocations of `validate` (resumed "
                "with `--resume`), so the set has no wall time of its own."
                % len(invocations)]
    elapsed = (max(end for _, end in intervals)
               - min(start for start, _ in intervals))
    return ["The whole set, %s scenes at a time, took %s s (%.1f min) from "
            "the first start to the last end."
            % (runs[0]["info"]["jobs"], number(elapsed, 1), elapsed / 60.)]


def warnings_table(runs):
    rows = []
    for run in runs:
        for direction in DIRECTIONS[run["dim"]]:
            entry = run["spectrum"][direction]
            if entry["warnings"]:
                rows.append(["`%s`" % run["name"], direction,
                             escape(entry["warnings"])])
    lines = ["## Warnings of the spectral analysis", ""]
    if not rows:
        return lines + ["The spectral analysis raised no warnings.", ""]
    return (lines
            + ["Warnings of the dominant peak of each direction, and the "
               "reason where a direction has no peak.", ""]
            + table(["scene", "direction", "warnings"], rows) + [""])


def figures_section(runs):
    lines = ["## Figures", "",
             "Top: the tip displacement components against time. Bottom: "
             "the amplitude spectrum of each direction of the tip motion, its "
             "dominant peak marked; in experiment 1 the dashed line is the "
             "measured frequency.", ""]
    for experiment, title in EXPERIMENTS.items():
        lines += ["### " + title, ""]
        for run in runs:
            if run["experiment"] == experiment:
                lines += ["![%s](figures/validation/%s.png)"
                          % (run["name"], run["name"]), "",
                          "`%s`: %s." % (run["name"], scene_label(run)), ""]
    return lines


# @sect{The figure of one scene}

def plot_scene(run, path):
    figure, (top, bottom) = plt.subplots(2, 1, figsize=(8, 6))
    t = run["trajectory"]["t"]
    for component, direction in COMPONENTS:
        if component in run["trajectory"]:
            top.plot(t, run["trajectory"][component], lw=1,
                     color=COLOURS[direction],
                     label="$u_%s$ (%s)" % (component[-1], direction))
    top.set_xlabel("time [s]")
    top.set_ylabel("tip displacement [mm]")
    top.legend(fontsize=8, loc="upper right")
    top.grid(True, alpha=0.3)

    # Log-log spectrum between 0.1 Hz and 50 Hz (or the Nyquist frequency);
    # f = 0 and exact zeros (a motion that is zero by symmetry) are left out.
    frequencies = run["frequencies"]
    upper = min(50., frequencies[-1])
    shown = (frequencies >= 0.1) & (frequencies <= upper)
    largest, smallest = 0., np.inf
    for direction in DIRECTIONS[run["dim"]]:
        magnitude = np.where(run["magnitudes"][direction] > 0.,
                             run["magnitudes"][direction], np.nan)[shown]
        entry = run["spectrum"][direction]
        label = direction
        if entry["peak"] == "none":
            label += " (no peak)"
        else:
            label += ", f_peak = %.3f Hz" % entry["f_peak_Hz"]
        bottom.loglog(frequencies[shown], magnitude, lw=1,
                      color=COLOURS[direction], label=label)
        if entry["peak"] == "dominant":
            bottom.plot(entry["f_peak_Hz"], entry["magnitude"], "o", ms=4,
                        color=COLOURS[direction])
        if np.isfinite(magnitude).any():
            largest = max(largest, np.nanmax(magnitude))
            smallest = min(smallest, np.nanmin(magnitude))
    if run["experiment"] == 1:
        measured = MEASURED[run["key"]][0]
        bottom.axvline(measured, color="k", ls="--", lw=1,
                       label="measured, %.2f Hz" % measured)
    bottom.set_xlim(0.1, upper)
    if largest > 0.:
        # Down to the smallest amplitude shown, but at most six decades below
        # the largest: round-off noise of components that vanish by symmetry
        # would otherwise set the scale.
        bottom.set_ylim(max(smallest / 2., largest * 1e-6), largest * 3.)
    bottom.set_xlabel("frequency [Hz]")
    bottom.set_ylabel("amplitude spectrum [mm]")
    bottom.legend(fontsize=8, loc="lower left")
    bottom.grid(True, alpha=0.3)

    figure.suptitle("%s: %s" % (run["name"], scene_label(run)), fontsize=10)
    figure.tight_layout()
    save_small_png(figure, path)
    plt.close(figure)


def save_small_png(figure, path):
    """Save with a 128-colour palette: the figures are committed to git, and
    this makes them three times smaller than matplotlib's RGBA output with no
    visible difference for line plots. (Pillow is a dependency of
    matplotlib.)"""
    buffer = io.BytesIO()
    figure.savefig(buffer, format="png", dpi=110)
    buffer.seek(0)
    Image.open(buffer).convert("RGB").quantize(128).save(path, optimize=True)


# @sect{Main}

def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    output_dir, doc_dir = Path(sys.argv[1]), Path(sys.argv[2])
    try:
        runs = [read_scene(output_dir, scene) for scene in scene_list()]
        check_inputs(runs)
    except (ReportError, OSError) as error:
        sys.exit("validation_report.py: %s" % error)

    # The header first: it names the commit and whether the working tree
    # differs from it, which the figures written below would change.
    lines = header(runs, doc_dir)
    figure_dir = doc_dir / "figures" / "validation"
    figure_dir.mkdir(parents=True, exist_ok=True)
    for run in runs:
        plot_scene(run, figure_dir / (run["name"] + ".png"))

    lines += (experiment_1(runs)
             + prediction_table(runs, 2) + prediction_table(runs, 3)
             + reduced_models_table(runs) + runs_table(runs) + warnings_table(runs)
             + figures_section(runs))
    report = doc_dir / "validation.md"
    temporary = doc_dir / "validation.md.tmp"
    temporary.write_text("\n".join(lines).rstrip("\n") + "\n")
    os.replace(temporary, report)


if __name__ == "__main__":
    main()
