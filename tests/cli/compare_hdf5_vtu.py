#!/usr/bin/env python3
# SPDX-License-Identifier: LGPL-2.1-or-later
"""Reads back the HDF5/XDMF output of a run and compares it with the VTU
output of the same run.

Usage: compare_hdf5_vtu.py OUTPUT_DIRECTORY

Checks: the XDMF record and the PVD record list the same times; for every
output the nodal fields of the HDF5 files equal those of the VTU pieces at
the same points (to single precision, the VTU files' precision), the cell
fields are cell data in both (a <CellData> section in the VTU pieces,
Center="Cell" in the XDMF record) and equal cell by cell (matched by the
centres of the cells), and every value is finite. Needs Debian's
python3-h5py and python3-numpy. Exits with 1 and a message on a mismatch.
"""
import base64
import struct
import sys
import xml.etree.ElementTree as ElementTree
import zlib
from pathlib import Path

import h5py
import numpy as np

VTK_TYPES = {"Float32": "f4", "Float64": "f8", "Int32": "i4", "UInt32": "u4",
             "Int64": "i8", "UInt64": "u8", "UInt8": "u1", "Int8": "i1"}


def fail(message):
    sys.exit("compare_hdf5_vtu: " + message)


def decode(array, compressed):
    """The values of a binary DataArray of a VTU file (32-bit headers)."""
    text = array.text.strip()
    dtype = np.dtype(VTK_TYPES[array.get("type")])
    if compressed:
        header = base64.b64decode(text[:24])
        blocks, _, _, size = struct.unpack("<4I", header[:16])
        if blocks != 1:
            fail("a compressed array of more than one block")
        data = zlib.decompress(base64.b64decode(text[24:]))
    else:
        raw = base64.b64decode(text)
        data = raw[4:4 + struct.unpack("<I", raw[:4])[0]]
    values = np.frombuffer(data, dtype=dtype)
    components = int(array.get("NumberOfComponents", "1"))
    return values.reshape(-1, components) if components > 1 else values


def read_vtu(file):
    root = ElementTree.parse(file).getroot()
    compressed = root.get("compressor") is not None
    piece = root.find("UnstructuredGrid/Piece")
    points = decode(piece.find("Points/DataArray"), compressed)
    cells = piece.find("Cells")
    arrays = {a.get("Name"): a for a in cells.findall("DataArray")}
    connectivity = decode(arrays["connectivity"], compressed)
    offsets = decode(arrays["offsets"], compressed)
    starts = np.concatenate([[0], offsets[:-1]])
    centres = np.array([points[connectivity[s:e]].mean(axis=0)
                        for s, e in zip(starts, offsets)])
    point_data = {a.get("Name"): decode(a, compressed)
                  for a in piece.findall("PointData/DataArray")}
    if piece.find("CellData") is None:
        fail(f"{file} has no <CellData> section")
    cell_data = {a.get("Name"): decode(a, compressed)
                 for a in piece.findall("CellData/DataArray")}
    return points, centres, point_data, cell_data


def nearest(points, targets, scale, what):
    """For each point the index of the target at the same place (to single
    precision)."""
    indices = []
    for start in range(0, len(points), 1000):
        block = points[start:start + 1000]
        distance = np.linalg.norm(block[:, None, :] - targets[None, :, :], axis=2)
        best = np.argmin(distance, axis=1)
        if np.any(distance[np.arange(len(block)), best] > 1e-5 * scale):
            fail(f"{what} of the VTU output is not in the HDF5 output")
        indices.extend(best)
    return indices


def compare_output(directory, pvtu, grid, scale):
    record = ElementTree.parse(directory / pvtu).getroot()
    pieces = [p.get("Source") for p in record.findall("PUnstructuredGrid/Piece")]
    if record.find("PUnstructuredGrid/PCellData") is None:
        fail(f"{pvtu} has no <PCellData> list")
    vtu_points, vtu_centres, vtu_nodes, vtu_cells = [], [], {}, {}
    for piece in pieces:
        points, centres, nodes, cells = read_vtu(directory / piece)
        vtu_points.append(points)
        vtu_centres.append(centres)
        for name, values in nodes.items():
            vtu_nodes.setdefault(name, []).append(values)
        for name, values in cells.items():
            vtu_cells.setdefault(name, []).append(values)
    vtu_points = np.concatenate(vtu_points)
    vtu_centres = np.concatenate(vtu_centres)

    attributes = {a.get("Name"): a for a in grid.findall("Attribute")}
    mesh_file, _ = grid.find("Geometry/DataItem").text.strip().split(":/")
    with h5py.File(directory / mesh_file) as mesh:
        nodes = mesh["nodes"][:]
        cells = mesh["cells"][:]
    dim = vtu_points.shape[1]
    nodes3 = np.zeros((len(nodes), 3))
    nodes3[:, :nodes.shape[1]] = nodes
    h5_centres = nodes3[cells].mean(axis=1)
    vtu_points3 = np.zeros((len(vtu_points), 3))
    vtu_points3[:, :dim] = vtu_points
    vtu_centres3 = np.zeros((len(vtu_centres), 3))
    vtu_centres3[:, :dim] = vtu_centres
    to_h5_node = nearest(vtu_points3, nodes3, scale, f"{pvtu}: a point")
    to_h5_cell = nearest(vtu_centres3, h5_centres, scale, f"{pvtu}: a cell")
    if len(set(to_h5_cell)) != len(h5_centres):
        fail(f"{pvtu}: {len(h5_centres)} cells in the HDF5 mesh, "
             f"{len(set(to_h5_cell))} in the VTU pieces")

    for name, pieces_values in vtu_nodes.items():
        vtu = np.concatenate(pieces_values)
        if name not in attributes or attributes[name].get("Center") != "Node":
            fail(f"{pvtu}: the XDMF record has no node attribute {name}")
        h5_file, dataset = attributes[name].find("DataItem").text.strip().split(":/")
        with h5py.File(directory / h5_file) as solution:
            h5 = solution[dataset][:]
        h5 = h5.reshape(len(nodes), -1)[to_h5_node]
        vtu = vtu.reshape(len(vtu), -1)
        width = min(h5.shape[1], vtu.shape[1])
        if not (np.all(np.isfinite(h5)) and np.all(np.isfinite(vtu))):
            fail(f"{pvtu}: {name} is not finite")
        error = np.max(np.abs(h5[:, :width] - vtu[:, :width]), initial=0.)
        size = np.max(np.abs(h5), initial=0.)
        if error > 1e-6 * max(size, 1e-30):
            fail(f"{pvtu}: {name} differs by {error:g} (largest value {size:g})")
    for name, pieces_values in vtu_cells.items():
        vtu = np.concatenate(pieces_values)
        if name not in attributes or attributes[name].get("Center") != "Cell":
            fail(f"{pvtu}: the XDMF record has no cell attribute {name}")
        h5_file, dataset = attributes[name].find("DataItem").text.strip().split(":/")
        with h5py.File(directory / h5_file) as solution:
            h5 = solution[dataset][:][to_h5_cell]
        if not np.array_equal(h5, vtu):
            fail(f"{pvtu}: the cell field {name} differs")
    return len(vtu_cells), len(h5_centres)


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    directory = Path(sys.argv[1])
    pvd = ElementTree.parse(directory / "solution.pvd").getroot()
    datasets = pvd.findall("Collection/DataSet")
    xdmf = ElementTree.parse(directory / "solution.xdmf").getroot()
    grids = xdmf.findall("Domain/Grid/Grid")
    pvd_times = [float(d.get("timestep")) for d in datasets]
    xdmf_times = [float(g.find("Time").get("Value")) for g in grids]
    if len(datasets) < 2 or not np.allclose(pvd_times, xdmf_times):
        fail(f"the PVD record has the times {pvd_times}, the XDMF record {xdmf_times}")
    with h5py.File(directory / "solution_mesh.h5") as mesh:
        nodes = mesh["nodes"][:]
    scale = max(np.ptp(nodes, axis=0).max(), 1e-30)
    for dataset, grid in zip(datasets, grids):
        n_fields, n_cells = compare_output(directory, dataset.get("file"), grid, scale)
    print(f"{len(datasets)} outputs agree: nodal fields and {n_fields} cell "
          f"fields on {n_cells} cells")


if __name__ == "__main__":
    main()
