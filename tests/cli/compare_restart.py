#!/usr/bin/env python3
# SPDX-License-Identifier: LGPL-2.1-or-later
"""Compares a run continued from a checkpoint with the uninterrupted run.

Usage: compare_restart.py FULL PART [--tolerance T]

FULL and PART are the output directories. Without a tolerance the tip
trajectories must be the same text (every value to its ten digits), and so
must every VTU piece the PVD records name (but for the time of writing in
deal.II's comment); with one, every value of the
trajectory must agree with the uninterrupted run's to T times the largest
magnitude of its column. In both cases the PVD records must list the same
times, the XDMF records (if any) must be the same text, and the run
statistics the same numbers of steps, Newton and linear
iterations, factorizations and cut-backs.
"""
import json
import sys
import xml.etree.ElementTree as ElementTree
from pathlib import Path


def rows(path):
    lines = path.read_text().splitlines()
    comments = [line for line in lines if line.startswith("#")]
    data = [line for line in lines if not line.startswith("#")]
    return comments, data[0], data[1:]


def vtu_content(path):
    """A VTU piece without deal.II's comment with the time of writing."""
    return [line for line in path.read_bytes().splitlines()
            if not line.startswith(b"#This file was generated")]


def main():
    arguments = sys.argv[1:]
    tolerance = None
    if "--tolerance" in arguments:
        index = arguments.index("--tolerance")
        tolerance = float(arguments[index + 1])
        del arguments[index:index + 2]
    if len(arguments) != 2:
        sys.exit(__doc__)
    full, part = Path(arguments[0]), Path(arguments[1])
    failures = []

    comments_full, header_full, data_full = rows(full / "tip_trajectory.csv")
    comments_part, header_part, data_part = rows(part / "tip_trajectory.csv")
    if comments_full != comments_part or header_full != header_part:
        failures.append("the comments or the header of the trajectories differ")
    if len(data_full) != len(data_part):
        failures.append(f"{len(data_part)} rows after the restart, "
                        f"{len(data_full)} in the uninterrupted run")
    identical = sum(a == b for a, b in zip(data_full, data_part))
    values_full = [[float(x) for x in r.split(",")] for r in data_full]
    values_part = [[float(x) for x in r.split(",")] for r in data_part]
    largest = 0.
    for column in range(len(header_full.split(","))):
        scale = max(abs(r[column]) for r in values_full) or 1.
        for a, b in zip(values_full, values_part):
            largest = max(largest, abs(a[column] - b[column]) / scale)
    print(f"compare_restart: {identical} of {len(data_full)} trajectory rows "
          f"identical; largest difference {largest:.3g} of the column's scale")
    if tolerance is None and identical != len(data_full):
        failures.append("the trajectories are not the same text")
    if tolerance is not None and largest > tolerance:
        failures.append(f"the trajectories differ by {largest:.3g} > {tolerance}")

    def records(directory):
        root = ElementTree.parse(directory / "solution.pvd").getroot()
        return [(float(d.get("timestep")), d.get("file"))
                for d in root.findall("Collection/DataSet")]
    if (full / "solution.pvd").exists():
        records_full, records_part = records(full), records(part)
        if records_full != records_part:
            failures.append(f"the PVD records differ: {records_part} after the "
                            f"restart, {records_full} uninterrupted")
        same_pieces = 0
        for _, pvtu in records_part:
            pieces = ElementTree.parse(part / pvtu).getroot().findall(
                "PUnstructuredGrid/Piece")
            for piece in pieces:
                name = piece.get("Source")
                same = vtu_content(part / name) == vtu_content(full / name)
                same_pieces += same
                if tolerance is None and not same:
                    failures.append(f"{name} differs")
        print(f"compare_restart: {len(records_part)} outputs at the same times, "
              f"{same_pieces} VTU pieces identical")

    if (full / "solution.xdmf").exists():
        same = ((full / "solution.xdmf").read_text()
                == (part / "solution.xdmf").read_text())
        print(f"compare_restart: the XDMF records are {'' if same else 'not '}"
              "the same")
        if not same:
            failures.append("the XDMF records differ")

    statistics_full = json.loads((full / "run_statistics.json").read_text())
    statistics_part = json.loads((part / "run_statistics.json").read_text())
    for key in ("steps", "newton_iterations", "linear_iterations",
                "factorizations_or_amg_setups", "cutbacks", "end_time"):
        if statistics_full[key] != statistics_part[key]:
            failures.append(f"{key}: {statistics_part[key]} after the restart, "
                            f"{statistics_full[key]} uninterrupted")
    if failures:
        sys.exit("compare_restart: " + "; ".join(failures))
    print("compare_restart: the continued run is the uninterrupted one")


if __name__ == "__main__":
    main()
