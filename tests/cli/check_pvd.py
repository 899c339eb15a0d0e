#!/usr/bin/env python3
# SPDX-License-Identifier: LGPL-2.1-or-later
"""Checks the PVD record of a run.

Usage: check_pvd.py OUTPUT_DIRECTORY N_DATASETS [LAST_TIME]

The record must be complete XML, list N_DATASETS outputs at increasing times
(the last at LAST_TIME, if given), and every file it names must exist, with
the pieces its PVTU records name.
"""
import sys
import xml.etree.ElementTree as ElementTree
from pathlib import Path


def main():
    if len(sys.argv) not in (3, 4):
        sys.exit(__doc__)
    directory, expected = Path(sys.argv[1]), int(sys.argv[2])
    try:
        record = ElementTree.parse(directory / "solution.pvd").getroot()
    except (OSError, ElementTree.ParseError) as error:
        sys.exit(f"check_pvd: solution.pvd is not a complete record: {error}")
    datasets = record.findall("Collection/DataSet")
    times = [float(d.get("timestep")) for d in datasets]
    if len(datasets) != expected:
        sys.exit(f"check_pvd: {len(datasets)} datasets, expected {expected}")
    if any(b <= a for a, b in zip(times, times[1:])):
        sys.exit(f"check_pvd: the times {times} do not increase")
    if len(sys.argv) == 4 and abs(times[-1] - float(sys.argv[3])) > 1e-9:
        sys.exit(f"check_pvd: the last output is at t = {times[-1]}, not {sys.argv[3]}")
    for dataset in datasets:
        pvtu = directory / dataset.get("file")
        pieces = ElementTree.parse(pvtu).getroot().findall("PUnstructuredGrid/Piece")
        for piece in pieces:
            ElementTree.parse(directory / piece.get("Source"))
    print(f"check_pvd: {len(datasets)} complete outputs at t = {times}")


if __name__ == "__main__":
    main()
