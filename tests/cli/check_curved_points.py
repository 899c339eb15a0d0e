#!/usr/bin/env python3
# SPDX-License-Identifier: LGPL-2.1-or-later
"""Checks that the VTU output of a curved mesh places every point that
neighbouring cells share at one position.

Usage: check_curved_points.py VTU_FILE

Each cell is written as a patch of its own points. Two points of the file
closer than a quarter of the median distance from a point to its nearest
distinct neighbour must coincide to single precision (the file's): a pair
in between is one point that two cells place differently, as deal.II's
output does when only the cells at the boundary go through the mapping
of a curved mesh. Needs Debian's python3-numpy (and python3-h5py,
for the reader it shares with compare_hdf5_vtu.py).
"""
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from compare_hdf5_vtu import read_vtu  # noqa: E402


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    points = read_vtu(sys.argv[1])[0].astype(float)
    exact = 1e-6 * np.abs(points).max()
    distances = np.linalg.norm(points[:, None, :] - points[None, :, :], axis=2)
    distinct = np.where(distances > exact, distances, np.inf)
    close = 0.25 * np.median(distinct.min(axis=1))
    pairs = np.triu((distances > exact) & (distances < close), k=1)
    count = int(pairs.sum())
    worst = distances[pairs].max() if count else 0.0
    if count:
        sys.exit(f"check_curved_points: {count} pairs of points {exact:.2g} to {close:.2g} "
                 f"apart (largest {worst:.3g}): cells place shared points differently")
    print(f"check_curved_points: {len(points)} points, shared ones coincide")


if __name__ == "__main__":
    main()
