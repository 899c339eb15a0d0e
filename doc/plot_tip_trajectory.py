#!/usr/bin/env python3
"""Plot tip trajectories written by soft-robot (one figure per file).

Usage: python3 doc/plot_tip_trajectory.py OUTPUT.png TRAJECTORY.csv [LABEL] [COMMIT]

Top: the tip displacement components against time. Bottom: the energy
balance of the run (kinetic, strain, gravitational, dissipated by damping,
and the remainder, which is the algorithmic dissipation of HHT).
Needs Debian's python3-matplotlib and python3-numpy.
"""
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np


def read(csv_file):
    with open(csv_file) as stream:
        lines = [line for line in stream if not line.startswith("#")]
    names = lines[0].strip().split(",")
    data = np.array([[float(v) for v in line.split(",")] for line in lines[1:]])
    return {name: data[:, k] for k, name in enumerate(names)}


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    output, csv_file = sys.argv[1], sys.argv[2]
    label = sys.argv[3] if len(sys.argv) > 3 else csv_file
    commit = sys.argv[4] if len(sys.argv) > 4 else ""
    columns = read(csv_file)
    t = columns["t"]
    figure, (top, bottom) = plt.subplots(2, 1, figsize=(7, 6), sharex=True)
    for axis in "xyz":
        if "u_" + axis in columns:
            top.plot(t, columns["u_" + axis], label="$u_%s$" % axis)
    top.set_ylabel("tip displacement [mm]")
    top.legend()
    top.grid(True, alpha=0.3)
    top.set_title(label, fontsize=10)
    for name, text in [("kinetic", "kinetic"), ("strain", "strain"),
                       ("gravity_potential", "gravitational"),
                       ("damping_dissipation", "dissipated by damping"),
                       ("energy_balance", "balance (HHT dissipation)")]:
        bottom.plot(t, columns[name] * 1e-3, label=text)
    bottom.set_xlabel("time [s]")
    bottom.set_ylabel("energy [mJ]")
    bottom.legend(fontsize=8)
    bottom.grid(True, alpha=0.3)
    if commit:
        figure.text(0.99, 0.005, "commit " + commit, ha="right", fontsize=7,
                    color="gray")
    figure.tight_layout()
    figure.savefig(output, dpi=110)


if __name__ == "__main__":
    main()
