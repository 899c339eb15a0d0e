#!/usr/bin/env python3
# SPDX-License-Identifier: LGPL-2.1-or-later
"""Checks doc/plot_tip_trajectory.py.

Usage: check_plot_script.py PLOT_SCRIPT TRAJECTORY.csv

The script must plot the trajectory of a run (a PNG file that is not
empty, and the energy terms named on its standard output), and must refuse
a trajectory with a header only and one with a value that is not finite,
with a message and a non-zero exit code.
"""
import subprocess
import sys
from pathlib import Path


def run(script, *arguments):
    return subprocess.run([sys.executable, script, *arguments],
                          capture_output=True, text=True)


def main():
    script, trajectory = sys.argv[1], Path(sys.argv[2])
    figure = trajectory.parent / "plot.png"
    result = run(script, str(figure), str(trajectory))
    if result.returncode != 0 or not figure.exists() or figure.stat().st_size == 0:
        sys.exit(f"the plot of a run failed: {result.stderr}")
    if "traction_work" not in result.stdout:
        sys.exit(f"the plot does not name the traction work: {result.stdout}")
    lines = trajectory.read_text().splitlines(keepends=True)
    header = [line for line in lines if line.startswith("#")]
    first_other = next(line for line in lines if not line.startswith("#"))
    header_only = trajectory.parent / "header_only.csv"
    header_only.write_text("".join(header) + first_other)
    result = run(script, str(trajectory.parent / "none.png"), str(header_only))
    if result.returncode == 0 or "no rows" not in result.stderr:
        sys.exit(f"a header-only trajectory was not refused: {result.stderr}")
    rows = [line for line in lines if line[:1].isdigit()]
    broken = trajectory.parent / "not_finite.csv"
    broken.write_text("".join(header) + first_other + rows[0] +
                      ",".join(["nan"] * len(rows[0].split(","))) + "\n")
    result = run(script, str(trajectory.parent / "none.png"), str(broken))
    if result.returncode == 0 or "not finite" not in result.stderr:
        sys.exit(f"a trajectory with nan was not refused: {result.stderr}")
    print("the plot script plots a run and refuses a header-only and a "
          "non-finite trajectory")


if __name__ == "__main__":
    main()
