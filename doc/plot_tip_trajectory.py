#!/usr/bin/env python3
# SPDX-License-Identifier: LGPL-2.1-or-later
"""Plot tip trajectories written by soft-robot (one figure per file).

Usage: python3 doc/plot_tip_trajectory.py OUTPUT.png TRAJECTORY.csv [LABEL] [COMMIT]

Top: the tip displacement components against time. Bottom: every term of
the energy balance of the run -- kinetic, strain and gravitational energy,
the work of the tractions (and of any other load with a '*_work' column,
such as a pressure), the energy dissipated by damping, and the remainder,
which is the algorithmic dissipation of HHT. The figure is titled with the
scene and its materials (from the file's comment lines) unless LABEL is
given. If the run's spectral analysis (tip_spectrum.csv) is beside the
trajectory, its result is printed and shown in the figure.

A file without rows, or with a value that is not finite, is refused with a
message (exit code 1). Needs Debian's python3-matplotlib and python3-numpy.
"""
import csv
import math
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np


def refuse(message):
    sys.exit(f"plot_tip_trajectory: {message}")


def read(csv_file):
    """The columns of the trajectory and its comment lines."""
    try:
        with open(csv_file) as stream:
            lines = stream.read().splitlines()
    except OSError as error:
        refuse(f"cannot read {csv_file}: {error}")
    comments = [line[1:].strip() for line in lines if line.startswith("#")]
    table = [line for line in lines if line.strip() and not line.startswith("#")]
    if not table:
        refuse(f"{csv_file} has no header line: is it a tip trajectory?")
    names = table[0].strip().split(",")
    if len(table) < 2:
        refuse(f"{csv_file} has a header but no rows: the run wrote no step "
               "(did it stop at once? see its messages)")
    rows = []
    for number, line in enumerate(table[1:], start=2):
        try:
            values = [float(v) for v in line.split(",")]
        except ValueError:
            refuse(f"{csv_file}: row {number} is not a row of numbers: {line!r}")
        if len(values) != len(names):
            refuse(f"{csv_file}: row {number} has {len(values)} values, the "
                   f"header {len(names)} (a row cut short?)")
        if not all(math.isfinite(v) for v in values):
            refuse(f"{csv_file}: row {number} has a value that is not finite; "
                   "a trajectory of this program never has one")
        rows.append(values)
    data = np.array(rows)
    return {name: data[:, k] for k, name in enumerate(names)}, comments


def title_of(comments, csv_file):
    """The scene (the parameter file the run read) and its materials."""
    scene = next((c.split(", from ", 1)[1] for c in comments if ", from " in c),
                 str(csv_file))
    materials = next((c.split(":", 1)[1].strip() for c in comments
                      if c.startswith("materials:")), "")
    return Path(scene).name + (f"\n{materials}" if materials else "")


def spectral_result(csv_file):
    """The dominant peak per direction of tip_spectrum.csv, as text lines."""
    spectrum = Path(csv_file).parent / "tip_spectrum.csv"
    if not spectrum.exists():
        return []
    with open(spectrum) as stream:
        rows = [row for row in csv.DictReader(stream)]
    lines = []
    for row in rows:
        if row.get("peak") == "none":
            lines.append(f"{row['direction']}: no peak")
        elif row.get("peak") in ("dominant", "1", "0"):
            lines.append(f"{row['direction']}: f = {float(row['f_peak_Hz']):.4g} Hz, "
                         f"xi = {float(row['xi_recommended'] or 'nan'):.3g} "
                         f"({row['xi_recommended_from']})")
    return lines


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    output, csv_file = sys.argv[1], sys.argv[2]
    columns, comments = read(csv_file)
    label = sys.argv[3] if len(sys.argv) > 3 else title_of(comments, csv_file)
    commit = sys.argv[4] if len(sys.argv) > 4 else ""
    t = columns["t"]
    figure, (top, bottom) = plt.subplots(2, 1, figsize=(7, 6.5), sharex=True)
    for axis in "xyz":
        if "u_" + axis in columns:
            top.plot(t, columns["u_" + axis], label="$u_%s$" % axis)
    top.set_ylabel("tip displacement [mm]")
    top.legend()
    top.grid(True, alpha=0.3)
    top.set_title(label, fontsize=9)

    terms = [("kinetic", "kinetic"), ("strain", "strain"),
             ("gravity_potential", "gravitational")]
    terms += [(name, name.replace("_", " ")) for name in columns
              if name.endswith("_work")]
    terms += [("damping_dissipation", "dissipated by damping"),
              ("energy_balance", "balance (HHT dissipation)")]
    drawn = []
    for name, text in terms:
        if name in columns:
            bottom.plot(t, columns[name] * 1e-3, label=text)
            drawn.append(name)
    bottom.set_xlabel("time [s]")
    bottom.set_ylabel("energy [mJ]")
    bottom.legend(fontsize=8)
    bottom.grid(True, alpha=0.3)
    print("energy terms drawn: " + ", ".join(drawn))

    spectral = spectral_result(csv_file)
    if spectral:
        print("spectral analysis (tip_spectrum.csv):")
        for line in spectral:
            print("  " + line)
        top.text(0.99, 0.02, "\n".join(spectral), transform=top.transAxes,
                 ha="right", va="bottom", fontsize=7,
                 bbox=dict(facecolor="white", alpha=0.7, edgecolor="none"))
    if commit:
        figure.text(0.99, 0.005, "commit " + commit, ha="right", fontsize=7,
                    color="gray")
    figure.tight_layout()
    figure.savefig(output, dpi=110)


if __name__ == "__main__":
    main()
