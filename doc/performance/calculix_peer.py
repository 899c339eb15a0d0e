#!/usr/bin/env python3
# SPDX-License-Identifier: LGPL-2.1-or-later
"""Run the CalculiX peer of the speed benchmark's experiment-1 cases.

The case is parameters/bellows/vertical_ds20_3d.prm (with the files it
includes, protocol_vertical_3d.prm and ../silicones.prm): the quarter
model of the bellows actuator on the coarse mesh, Dragon Skin 20 with the
baseline shear modulus, hanging from its base under gravity, released at
t = 0 from a "hold" on the tip block and ringing for 5.25 s. With
--degree 1 (the default) the elements are linear tetrahedra (ccx's C3D4,
the benchmark's headline), with --degree 2 quadratic ones on the same
mesh (C3D10, the mid-edge nodes at the edges' midpoints, as deal.II's
quadratic elements on this straight-sided mesh). With --hex it runs the
same experiment on the hexahedral mesh of the bellows (Geometry/Mesh
source = bellows, the quarter model's first mesh hex-1-3-1-2 unless
--hex-overrides says otherwise) in ccx's 20-node hexahedra, C3D20 (full
integration). The reduced-integration C3D20R, the usual element for
nearly incompressible rubber, is not offered: in ccx 2.20 its static step
converges on this mesh, but its first dynamic increment diverges, at
dt = 0.01 s and at 0.002 s alike.
This script builds the case for CalculiX (ccx), runs it, and reports
ccx's wall time and the frequency of the tip.

Usage (from anywhere; paths default to the repository of this script):

    python3 doc/performance/calculix_peer.py                  # full run
    python3 doc/performance/calculix_peer.py --end-time 0.5   # quick try
    python3 doc/performance/calculix_peer.py --threads 2
    python3 doc/performance/calculix_peer.py --degree 2
    python3 doc/performance/calculix_peer.py --hex --time-step 0.01
    python3 doc/performance/calculix_peer.py \\
        --compare output/vertical_ds20_3d/tip_trajectory.csv

Needs ccx (Debian: calculix-ccx) and Python 3 with numpy; --hex also needs
our program (build-release/soft-robot, or --build) and the vtk module
(Debian: python3-paraview).

Steps:
  1. read the gmsh MSH 2.2 mesh (no gmsh module needed) and write
     WORKDIR/job.inp: C3D4 (or C3D10) elements, one element set per material, node
     sets for the constrained boundaries, the materials, a static NLGEOM
     step under gravity and the hold, and a *DYNAMIC NLGEOM step (HHT,
     ALPHA=-0.25, fixed increments) with the hold removed;
  2. run `ccx -i job` in WORKDIR, timing it (wall clock) and recording the
     peak resident memory of the child process;
  3. read the tip motion from WORKDIR/job.dat and compute its peak
     frequency (FFT with zero padding and parabolic interpolation of the
     magnitude peak) and, as checks, the frequency from zero crossings and
     a damping ratio from the decay of the cycle amplitudes;
  4. print a summary and write WORKDIR/calculix_peer.json (and the tip
     history WORKDIR/tip_history.csv); with --compare, put our
     tip_trajectory.csv through the same estimators.

Units are those of the scene: mm, kg, s (force mN, stress kPa, density
kg/mm^3, gravity 9810 mm/s^2).

Differences from our model (also written to the JSON file as caveats):
  * Material law. Our energy is
        Psi = mu/2 (J^(-2/3) I1 - 3) + kappa/4 (J^2 - 1 - 2 ln J).
    By default (--law arruda-boyce) the script uses ccx's ARRUDA-BOYCE
    potential
        U = mu {1/2 (I1bar - 3) + 1/(20 lm^2) (I1bar^2 - 9) + ...}
            + 1/D ((J^2 - 1)/2 - ln J)
    with a locking stretch lm = 1e4 (the terms beyond the first are then
    below 1e-8 relative) and D = 2/kappa: the same energy as ours. With
    --law neo-hooke it uses ccx's NEO HOOKE potential
        U = C10 (I1bar - 3) + (J - 1)^2 / D1,  C10 = mu/2, D1 = 2/kappa,
    which has the same shear and small-strain bulk modulus but a
    different volumetric term at finite strain.
  * Damping. ccx 2.20 has Rayleigh damping C = alpha M + beta K in
    implicit *DYNAMIC steps (*DAMPING, ALPHA=, BETA=; the card must follow
    a *MATERIAL card but is global: "only one *DAMPING card can be used
    ... It applies to the whole model"). So beta = zeta of the silicone
    also damps the tip block, which carries no damping in our model.
    Stiffness-proportional damping does not act on rigid-body motion, and
    the block moves nearly rigidly (it is 86 times stiffer than the
    silicone), so this should matter little for the tip.
  * Hold load. Our hold is a nominal (dead) traction on the bottom face
    of the block. By default (--hold-load pressure) it is a *DLOAD
    pressure on those element faces, which ccx applies, with NLGEOM, on
    the deformed faces (a follower load); the stiff block barely deforms
    or rotates, so the two agree closely. --hold-load cload applies the
    consistent nodal forces of the nominal traction (*CLOAD, dead loads)
    instead, exactly our load.
  * Release. Our hold acts for t <= 0, so the HHT-weighted external force
    of our first time step still carries -alpha = 25 % of it; in ccx the
    loads of a step apply in full from its start.
  * Elements. ccx's C3D4 are linear tetrahedra as ours. Its C3D10 are
    quadratic tetrahedra in the pure displacement formulation, where the
    benchmark's quadratic case uses the mean-dilatation formulation
    (Finite element/Volumetric formulation); at kappa = 100 mu the
    displacement formulation locks in part: on the coarse quarter mesh our
    own rings 7.9 % above our mean dilatation (doc/locking.md). The
    mass matrix and the gravity load are ccx's own (not necessarily the
    same quadrature as ours).
  * Hexahedra (--hex). Our program writes the mesh: one step of the scene
    from rest with the hexahedral overrides, whose first VTU file holds
    each cell's 27 points placed by our mapping of degree 2 (deal.II's
    lexicographic patch points; shared points are merged and must number
    exactly the mesh's quadratic nodes). ccx's 20-node elements take the
    corners and mid-edge points, not the face and cell centres: the
    serendipity element, where ours is the 27-node Lagrange one with the
    linear dilatation (Finite element/Volumetric formulation). The clamp
    is the nodes at the smallest x (the base face), the symmetry planes
    the nodes at y = 0 and z = 0, the hold the block's faces at the
    largest x, with the cylindrical block's 1.08824 kPa.
  * Tip quantity. We track the centre of mass of material 2. Here the tip
    displacement is the volume-weighted mean displacement of material 2,
    sum over its elements of V_e times the mean of the element's four
    nodal displacements, divided by the volume: with linear elements and
    a uniform density this is the displacement of its centre of mass
    exactly. With quadratic elements the weights are the integrals of the
    shape functions, -V_e/20 for a corner node and V_e/5 for a mid-edge
    node of a straight-sided tetrahedron, which again give the centre of
    mass exactly. (The plain mean over its nodes and the node on the axis at
    the bottom face are written to tip_history.csv as well.)
"""
import argparse
import json
import math
import os
import re
import resource
import shutil
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

REPOSITORY = Path(__file__).resolve().parents[2]

# ---------------------------------------------------------------------------
# The case: numbers of parameters/bellows/vertical_ds20_3d.prm and the files
# it includes (units mm, kg, s).
# ---------------------------------------------------------------------------
CASE = {
    "scene": "parameters/bellows/vertical_ds20_3d.prm",
    "mesh": "meshes/bellows_quarter_coarse.msh",
    "model_fraction": 0.25,  # quarter model: masses are divided by 4
    "gravity": 9810.0,  # mm/s^2 along +x (the axis points down)
    # Material 1, Dragon Skin 20, baseline set of ../silicones.prm:
    # mu = Neo-Hookean C1 = 116 kPa, kappa = 100 mu, zeta = xi / (pi f)
    # with the experiment-1 frequency f = 4.20 Hz and damping ratio 0.021.
    "silicone": {
        "mu": 116.0,
        "kappa": 100 * 116.0,
        "mass": 0.0766,  # kg, whole body
        "zeta": 0.021 / (math.pi * 4.20),  # s
    },
    # Material 2, the tip block (protocol_vertical_3d.prm), no damping.
    "block": {"mu": 1e4, "kappa": 2e4, "mass": 0.1188},
    # Hold: until t = 0 a traction of 1.1397 kPa in -x on the faces of
    # boundary 5 with x > 99.2 (the bottom face of the block).
    "hold_traction": 1.1397,
    "hold_boundary": 5,
    "hold_x_min": 99.2,
    # Constraints: base clamped, y = 0 and z = 0 symmetry planes.
    "fixed": {1: (1, 3), 3: (2, 2), 4: (3, 3)},  # boundary id: dof range
    "time_step": 0.005,
    "end_time": 5.25,
    "alpha": -0.25,
}

# The hexahedral mesh (--hex): the overrides that make it and the hold on
# the cylindrical block's end face, those of the benchmark's hexahedral case.
sys.path.insert(0, str(Path(__file__).resolve().parent))
from run_benchmarks import HEX_HOLD_TRACTION, HEX_OVERRIDES  # noqa: E402
# The scene as the benchmark knew it, under the hexahedral overrides.
sys.path.insert(0, str(REPOSITORY / "doc"))
from study_session import tetrahedral_defaults  # noqa: E402

ARRUDA_BOYCE_LOCKING_STRETCH = 1e4  # large: the potential is neo-Hookean
JOB = "job"


# ---------------------------------------------------------------------------
# Mesh
# ---------------------------------------------------------------------------
def read_msh(path):
    """Read a gmsh MSH 2.2 ASCII file.

    Returns (node_ids, coordinates, tets, triangles): node_ids and
    coordinates as arrays, tets and triangles as dicts from the physical
    tag to an (n, 4) or (n, 3) array of node ids.
    """
    with open(path) as stream:
        lines = stream.read().splitlines()

    def section(name):
        start = lines.index("$" + name)
        count = int(lines[start + 1])
        return lines[start + 2 : start + 2 + count]

    version, file_type = lines[lines.index("$MeshFormat") + 1].split()[:2]
    if not version.startswith("2") or file_type != "0":
        sys.exit("%s: expected gmsh MSH 2.x ASCII, found version %s, file type %s"
                 % (path, version, file_type))

    rows = [line.split() for line in section("Nodes")]
    node_ids = np.array([int(row[0]) for row in rows])
    coordinates = np.array([[float(v) for v in row[1:4]] for row in rows])

    tets, triangles = {}, {}
    for line in section("Elements"):
        values = [int(v) for v in line.split()]
        element_type, n_tags, physical = values[1], values[2], values[3]
        nodes = values[3 + n_tags :]
        if element_type == 4:  # 4-node tetrahedron
            tets.setdefault(physical, []).append(nodes)
        elif element_type == 2:  # 3-node triangle
            triangles.setdefault(physical, []).append(nodes)
    tets = {tag: np.array(v) for tag, v in tets.items()}
    triangles = {tag: np.array(v) for tag, v in triangles.items()}
    return node_ids, coordinates, tets, triangles


def tet_volumes(points, tets):
    """Signed volumes of the tetrahedra (positive for ccx's C3D4 ordering)."""
    p = [points[tets[:, k]] for k in range(4)]
    return np.einsum("ij,ij->i", np.cross(p[1] - p[0], p[2] - p[0]), p[3] - p[0]) / 6.0


def hold_faces(points, index, block_tets, triangles, x_min):
    """The faces of block tetrahedra under the hold traction: the boundary
    triangles with all nodes at x > x_min.

    Returns a list of (element position in block_tets, ccx face number,
    triangle node ids, triangle area, outward unit normal).
    ccx's C3D4 faces (manual, *DLOAD): 1: 1-2-3, 2: 1-4-2, 3: 2-4-3,
    4: 3-4-1, i.e. the face number follows from the local node *not* on
    the face.
    """
    face_without = {3: 1, 2: 2, 0: 3, 1: 4}
    by_nodes = {}
    for e, tet in enumerate(block_tets):
        for local in range(4):
            face = frozenset(n for k, n in enumerate(tet) if k != local)
            by_nodes[face] = (e, face_without[local])
    faces = []
    for tri in triangles:
        x = points[[index[n] for n in tri]]
        if np.all(x[:, 0] > x_min):
            e, number = by_nodes[frozenset(tri)]
            normal = np.cross(x[1] - x[0], x[2] - x[0])
            area = 0.5 * np.linalg.norm(normal)
            normal /= 2 * area
            # outwards: away from the element's centre
            centre = points[[index[n] for n in block_tets[e]]].mean(axis=0)
            if np.dot(normal, x.mean(axis=0) - centre) < 0:
                normal = -normal
            faces.append((e, number, tri, area, normal))
    return faces


# The edges of ccx's C3D10 (manual, element C3D10): nodes 5 to 10 sit on
# the edges 1-2, 2-3, 3-1, 1-4, 2-4 and 3-4; the faces are numbered as for
# C3D4.
C3D10_EDGES = ((0, 1), (1, 2), (2, 0), (0, 3), (1, 3), (2, 3))


def add_mid_edge_nodes(node_ids, points, connectivities, triangles):
    """Quadratic elements on the linear mesh: one new node at the midpoint
    of every edge of the tetrahedra. Returns the extended node ids and
    coordinates, the 10-node connectivities (ccx's order, from the 4-node
    ones as given, so orient those first) and the mid-edge nodes of every
    boundary triangle, by physical tag (for the node sets)."""
    index = {n: k for k, n in enumerate(node_ids)}
    next_id = int(node_ids.max()) + 1
    mid = {}
    new_points = []

    def node_on(a, b):
        nonlocal next_id
        key = (a, b) if a < b else (b, a)
        if key not in mid:
            mid[key] = next_id
            new_points.append(0.5 * (points[index[a]] + points[index[b]]))
            next_id += 1
        return mid[key]

    quadratic = {}
    for name, conn in connectivities.items():
        quadratic[name] = np.array(
            [list(tet) + [node_on(tet[i], tet[j]) for i, j in C3D10_EDGES] for tet in conn])
    on_faces = {}
    for tag, tris in triangles.items():
        nodes = []
        for tri in tris:
            for i, j in ((0, 1), (1, 2), (2, 0)):
                key = (tri[i], tri[j]) if tri[i] < tri[j] else (tri[j], tri[i])
                if key in mid:  # every boundary edge is an edge of a tetrahedron
                    nodes.append(mid[key])
        on_faces[tag] = np.array(nodes, dtype=int)
    all_ids = np.concatenate([node_ids, np.arange(int(node_ids.max()) + 1, next_id)])
    all_points = np.vstack([points, np.array(new_points)]) if new_points else points
    return all_ids, all_points, quadratic, on_faces


def build_model(mesh_path, degree=1):
    """Everything the input deck and the evaluation need from the mesh."""
    node_ids, points, tets, triangles = read_msh(mesh_path)
    index = {n: k for k, n in enumerate(node_ids)}
    as_index = np.vectorize(index.get)

    model = {"degree": degree, "element_type": "C3D4" if degree == 1 else "C3D10",
             "node_sets": {}, "elements": {}}
    first = 1
    for tag, name in ((1, "SILICONE"), (2, "BLOCK")):
        conn = tets[tag].copy()
        volume = tet_volumes(points, as_index(conn))
        flipped = volume < 0  # ccx needs positive volumes: swap two nodes
        conn[flipped, 1], conn[flipped, 2] = conn[flipped, 2], conn[flipped, 1].copy()
        model["elements"][name] = {
            "ids": np.arange(first, first + len(conn)),
            "conn": conn,
            "volumes": np.abs(volume),
        }
        first += len(conn)

    block = model["elements"]["BLOCK"]
    model["hold"] = hold_faces(points, index, block["conn"],
                               triangles[CASE["hold_boundary"]], CASE["hold_x_min"])

    mid_edge_nodes = {tag: np.zeros(0, dtype=int) for tag in triangles}
    if degree == 2:
        node_ids, points, quadratic, mid_edge_nodes = add_mid_edge_nodes(
            node_ids, points, {name: e["conn"] for name, e in model["elements"].items()},
            triangles)
        for name, conn in quadratic.items():
            model["elements"][name]["conn"] = conn
        index = {n: k for k, n in enumerate(node_ids)}
        as_index = np.vectorize(index.get)
    model["node_ids"], model["points"] = node_ids, points

    for boundary in CASE["fixed"]:
        model["node_sets"]["NB%d" % boundary] = np.unique(
            np.concatenate([triangles[boundary].ravel(), mid_edge_nodes[boundary]]))

    # Tip: all nodes of the block, weighted so that the weighted sum of the
    # nodal displacements is the block's mean displacement (the integral of
    # each node's shape function over each element, divided by the block's
    # volume: V_e/4 per node for linear elements; -V_e/20 per corner and
    # V_e/5 per mid-edge node for quadratic ones).
    tip_nodes = np.unique(block["conn"])
    weights = dict.fromkeys(tip_nodes.tolist(), 0.0)
    share = [0.25] * 4 if degree == 1 else [-0.05] * 4 + [0.2] * 6
    for conn, volume in zip(block["conn"], block["volumes"]):
        for n, fraction in zip(conn, share):
            weights[n] += fraction * volume
    model["tip_nodes"] = tip_nodes
    model["tip_weights"] = np.array([weights[n] for n in tip_nodes]) / block["volumes"].sum()
    # the node on the axis (y = z = 0) in the bottom face of the block
    p = points[as_index(tip_nodes)]
    on_axis = np.nonzero(np.abs(p[:, 1]) + np.abs(p[:, 2]) < 1e-9)[0]
    model["axis_node"] = int(tip_nodes[on_axis[np.argmax(p[on_axis, 0])]])
    return model


# ---------------------------------------------------------------------------
# The hexahedral mesh (--hex)
# ---------------------------------------------------------------------------
# deal.II's patch points of a hexahedron are lexicographic in the reference
# coordinates (xi, eta, zeta), index i + 3 j + 9 k for i, j, k in {0, 1, 2}.
# ccx's C3D20 (manual, element C3D20): corners 1-4 at zeta = -1 and 5-8 at
# zeta = 1, then the mid-edge nodes of the edges 1-2, 2-3, 3-4, 4-1, 5-6,
# 6-7, 7-8, 8-5, 1-5, 2-6, 3-7, 4-8.
C3D20_FROM_LEXICOGRAPHIC = (0, 2, 8, 6, 18, 20, 26, 24,
                            1, 5, 7, 3, 19, 23, 25, 21, 9, 11, 17, 15)
# The reference coordinate that is constant on each of ccx's six faces
# (manual, *DLOAD: 1: 1-2-3-4, 2: 5-8-7-6, 3: 1-5-6-2, 4: 2-6-7-3,
# 5: 3-7-8-4, 6: 4-8-5-1), as (axis, index).
C3D20_FACES = {1: (2, 0), 2: (2, 2), 3: (1, 0), 4: (0, 2), 5: (1, 2), 6: (0, 0)}
GAUSS_3 = (np.array([-math.sqrt(0.6), 0.0, math.sqrt(0.6)]), np.array([5.0, 8.0, 5.0]) / 9.0)


def quadratic_1d(s):
    """The three quadratic Lagrange polynomials on [-1, 1] with nodes -1, 0,
    1 at s, and their derivatives."""
    return (np.array([0.5 * s * (s - 1), 1 - s * s, 0.5 * s * (s + 1)]),
            np.array([s - 0.5, -2 * s, s + 0.5]))


def lexicographic_jacobian(points27, xi):
    """The Jacobian of the 27-node map at the reference point xi."""
    (a, da), (b, db), (c, dc) = (quadratic_1d(x) for x in xi)
    jacobian = np.zeros((3, 3))
    for k in range(3):
        for j in range(3):
            for i in range(3):
                x = points27[i + 3 * j + 9 * k]
                jacobian[:, 0] += x * da[i] * b[j] * c[k]
                jacobian[:, 1] += x * a[i] * db[j] * c[k]
                jacobian[:, 2] += x * a[i] * b[j] * dc[k]
    return jacobian


def serendipity_values(xi):
    """The shape functions of the 20-node hexahedron at xi, in ccx's order."""
    values = []
    for index in C3D20_FROM_LEXICOGRAPHIC:
        node = np.array([index % 3, (index // 3) % 3, index // 9]) - 1.0
        if np.all(node != 0):
            values.append(np.prod(1 + xi * node) * (np.dot(xi, node) - 2) / 8)
        else:
            value = 0.25
            for x, n in zip(xi, node):
                value *= (1 - x * x) if n == 0 else (1 + x * n)
            values.append(value)
    return np.array(values)


def element_integrals(points27):
    """Volume of a cell (27-node map, 3 x 3 x 3 Gauss points) and the
    integrals of the 20 serendipity shape functions over it."""
    nodes, weights = GAUSS_3
    volume, integrals = 0.0, np.zeros(20)
    for k in range(3):
        for j in range(3):
            for i in range(3):
                xi = np.array([nodes[i], nodes[j], nodes[k]])
                dv = np.linalg.det(lexicographic_jacobian(points27, xi)) * \
                    weights[i] * weights[j] * weights[k]
                volume += dv
                integrals += serendipity_values(xi) * dv
    return volume, integrals


def face_area(points27, axis, index):
    """Area of one face of a cell, from its 3 x 3 points (Gauss 3 x 3)."""
    grid = np.array(points27).reshape(3, 3, 3, 3)  # [k][j][i][coordinate]
    face = np.take(grid, index, axis=2 - axis)  # the 3 x 3 points of the face
    nodes, weights = GAUSS_3
    area = 0.0
    for b in range(3):
        for a in range(3):
            (la, da), (lb, db) = quadratic_1d(nodes[a]), quadratic_1d(nodes[b])
            ds = sum(face[n][m] * da[m] * lb[n] for n in range(3) for m in range(3))
            dt = sum(face[n][m] * la[m] * db[n] for n in range(3) for m in range(3))
            area += np.linalg.norm(np.cross(ds, dt)) * weights[a] * weights[b]
    return area


def write_hex_mesh(options, workdir):
    """Run our program for one step of the scene from rest on the
    hexahedral mesh, with VTU output; returns the first VTU file."""
    program = Path(options.build) / "soft-robot"
    if not program.exists():
        sys.exit("%s not found: build the program first (--build names its directory)" % program)
    output = workdir / "mesh"
    entries = (tetrahedral_defaults(CASE["scene"]) + HEX_OVERRIDES
               + options.hex_overrides) + [
        "Loads and constraints/Function constants=hold=%g" % HEX_HOLD_TRACTION,
        "Initial conditions/Type=expressions",
        "Time integration/Time step=%g" % options.time_step,
        "Time integration/End time=%g" % options.time_step,
        "Output/Write VTU=true", "Output/Spectral analysis=false",
        "Output/Existing output=replace", "Problem/Output directory=%s" % output]
    command = [str(program), CASE["scene"]]
    for entry in entries:
        command += ["--set", entry]
    result = subprocess.run(command, cwd=REPOSITORY, capture_output=True, text=True)
    if result.returncode != 0:
        sys.exit("writing the hexahedral mesh failed:\n%s%s" % (result.stdout, result.stderr))
    match = re.search(r"Degrees of freedom: (\d+)", result.stdout)
    return output / "solution_00000.0.vtu", int(match.group(1)) if match else None


def build_hex_model(options, workdir):
    """The model dictionary of build_model() for the hexahedral mesh, from
    the cells' 27 points in our VTU output (see the docstring)."""
    try:
        import vtk
        from vtk.util.numpy_support import vtk_to_numpy
    except ImportError:
        sys.exit("--hex needs the vtk module (Debian: python3-paraview)")
    path, our_dofs = write_hex_mesh(options, workdir)
    reader = vtk.vtkXMLUnstructuredGridReader()
    reader.SetFileName(str(path))
    reader.Update()
    grid = reader.GetOutput()
    points = vtk_to_numpy(grid.GetPoints().GetData()).astype(float)
    material = vtk_to_numpy(grid.GetCellData().GetArray("material_id"))
    n_cells = len(points) // 27
    subcells = len(material) // n_cells  # linear cells per patch (8)
    # shared points: equal to the precision of the file's numbers
    scale = 1e-5 * np.abs(points).max()
    keys, numbers = np.unique(np.round(points / scale).astype(np.int64), axis=0,
                              return_inverse=True)
    numbers = numbers.ravel()
    if our_dofs is not None and 3 * len(keys) != our_dofs:
        sys.exit("%s: %d distinct points for %d unknowns: the cells' points do not match"
                 % (path, len(keys), our_dofs))
    node_points = np.zeros((len(keys), 3))
    node_points[numbers] = points

    model = {"degree": 2, "element_type": "C3D20", "node_sets": {},
             "elements": {}, "hold_traction": HEX_HOLD_TRACTION}
    cells = {1: [], 2: []}
    mirror = [2 - (i % 3) + 3 * ((i // 3) % 3) + 9 * (i // 9) for i in range(27)]
    for cell in range(n_cells):
        patch = list(range(27 * cell, 27 * cell + 27))
        if np.linalg.det(lexicographic_jacobian(points[patch], np.zeros(3))) < 0:
            patch = [patch[m] for m in mirror]  # ccx needs positive volumes
        cells[int(material[cell * subcells])].append(patch)
    x_max = node_points[:, 0].max()
    first = 1
    tip_integrals = {}
    for tag, name in ((1, "SILICONE"), (2, "BLOCK")):
        conn, volumes = [], []
        for patch in cells[tag]:
            volume, integrals = element_integrals(points[patch])
            nodes = [int(numbers[patch[m]]) + 1 for m in C3D20_FROM_LEXICOGRAPHIC]
            conn.append(nodes)
            volumes.append(volume)
            if tag == 2:
                for n, w in zip(nodes, integrals):
                    tip_integrals[n] = tip_integrals.get(n, 0.0) + w
        model["elements"][name] = {"ids": np.arange(first, first + len(conn)),
                                   "conn": np.array(conn), "volumes": np.array(volumes)}
        first += len(conn)
    # The hold: the block's faces all of whose points lie at the largest x.
    model["hold"] = []
    for e, patch in enumerate(cells[2]):
        grid_points = points[patch].reshape(3, 3, 3, 3)
        for number, (axis, index) in C3D20_FACES.items():
            face = np.take(grid_points, index, axis=2 - axis).reshape(-1, 3)
            if np.all(face[:, 0] > x_max - 1e-6):
                model["hold"].append((e, number, None, face_area(points[patch], axis, index),
                                      np.array([1.0, 0.0, 0.0])))
    used = np.unique(np.concatenate([e["conn"].ravel() for e in model["elements"].values()]))
    model["node_ids"], model["points"] = used, node_points[used - 1]
    p = model["points"]
    tolerance = 1e-6 * np.abs(p).max()
    model["node_sets"]["NB1"] = used[p[:, 0] < p[:, 0].min() + tolerance]
    model["node_sets"]["NB3"] = used[np.abs(p[:, 1]) < tolerance]
    model["node_sets"]["NB4"] = used[np.abs(p[:, 2]) < tolerance]
    block_volume = model["elements"]["BLOCK"]["volumes"].sum()
    model["tip_nodes"] = np.array(sorted(tip_integrals))
    model["tip_weights"] = np.array([tip_integrals[n] for n in model["tip_nodes"]]) / block_volume
    index = {n: k for k, n in enumerate(used)}
    q = np.array([p[index[n]] for n in model["tip_nodes"]])
    on_axis = np.nonzero(np.abs(q[:, 1]) + np.abs(q[:, 2]) < tolerance)[0]
    model["axis_node"] = int(model["tip_nodes"][on_axis[np.argmax(q[on_axis, 0])]])
    model["label"] = "hexahedral bellows mesh%s" % (
        " (%s)" % ", ".join(options.hex_overrides) if options.hex_overrides else " hex-1-3-1-2")
    return model


def densities_from_masses(model):
    """The scene prescribes masses (the mesh's volume is not that of the
    revolved section), so the densities follow from the mesh's volumes."""
    densities = {}
    for name, key in (("SILICONE", "silicone"), ("BLOCK", "block")):
        volume = model["elements"][name]["volumes"].sum()
        densities[name] = CASE[key]["mass"] * CASE["model_fraction"] / volume
    return densities


def count_dofs(model):
    """All and unconstrained displacement components."""
    n_nodes = len(model["node_ids"])
    constrained = set()
    for boundary, (first, last) in CASE["fixed"].items():
        for n in model["node_sets"]["NB%d" % boundary]:
            constrained.update((int(n), d) for d in range(first, last + 1))
    return 3 * n_nodes, 3 * n_nodes - len(constrained)


# ---------------------------------------------------------------------------
# Input deck
# ---------------------------------------------------------------------------
def id_lines(ids, per_line=16):
    """Ids for a set card, 16 a line (ccx's lines hold at most 132 characters)."""
    ids = [str(i) for i in ids]
    return "\n".join(", ".join(ids[k : k + per_line]) for k in range(0, len(ids), per_line))


def material_cards(name, properties, density, law):
    mu, kappa = properties["mu"], properties["kappa"]
    if law == "arruda-boyce":  # mu, locking stretch, D
        hyper = ["*HYPERELASTIC, ARRUDA-BOYCE",
                 "%.10g, %.10g, %.10g" % (mu, ARRUDA_BOYCE_LOCKING_STRETCH, 2.0 / kappa)]
    else:  # C10, D1
        hyper = ["*HYPERELASTIC, NEO HOOKE", "%.10g, %.10g" % (mu / 2.0, 2.0 / kappa)]
    return ["*MATERIAL, NAME=%s" % name] + hyper + ["*DENSITY", "%.10g" % density]


def write_input(path, model, options, densities):
    """Write the ccx input deck; returns the total hold force [mN]."""
    out = ["** CalculiX peer of %s, written by doc/performance/calculix_peer.py" % CASE["scene"],
           "** units: mm, kg, s (force mN, stress kPa)",
           "*NODE, NSET=NALL"]
    # ccx reads numbers in fields of 20 characters: 12 digits fit
    out += ["%d, %.12g, %.12g, %.12g" % (n, *x) for n, x in zip(model["node_ids"], model["points"])]
    for name, elements in model["elements"].items():
        out.append("*ELEMENT, TYPE=%s, ELSET=%s" % (model["element_type"], name))
        # at most 16 entries a line: a 20-node element continues on a second
        for e, c in zip(elements["ids"], elements["conn"]):
            entries = [str(v) for v in (e, *c)]
            out += [", ".join(entries[:16]) + ("," if len(entries) > 16 else "")]
            if len(entries) > 16:
                out.append(", ".join(entries[16:]))
    out += ["*ELSET, ELSET=EALL", "SILICONE, BLOCK"]
    for name, nodes in model["node_sets"].items():
        out += ["*NSET, NSET=%s" % name, id_lines(nodes)]
    out += ["*NSET, NSET=NTIP", id_lines(model["tip_nodes"])]

    # The hold: one element set per ccx face number (for *DLOAD), and the
    # consistent nodal forces of the nominal traction (for *CLOAD).
    block_ids = model["elements"]["BLOCK"]["ids"]
    hold_sets = {}
    for e, number, _, _, _ in model["hold"]:
        hold_sets.setdefault(number, []).append(block_ids[e])
    for number, ids in sorted(hold_sets.items()):
        out += ["*ELSET, ELSET=HOLD%d" % number, id_lines(ids)]
    # -traction * normal: for linear triangles a third of the face per
    # corner; for quadratic ones (the consistent loads of a uniform
    # traction) nothing at the corners and a third per mid-edge node
    hold_forces = {}
    block_conn = model["elements"]["BLOCK"]["conn"]
    for e, _, tri, area, normal in (model["hold"] if options.hold_load == "cload" else []):
        if model["degree"] == 1:
            loaded = tri
        else:
            corners = list(block_conn[e][:4])
            on_face = {corners.index(n) for n in tri}
            loaded = [block_conn[e][4 + k] for k, (i, j) in enumerate(C3D10_EDGES)
                      if i in on_face and j in on_face]
        for n in loaded:
            force = -model.get("hold_traction", CASE["hold_traction"]) * area / 3 * normal
            hold_forces[n] = hold_forces.get(n, 0.0) + force

    def hold(scale):
        if options.hold_load == "pressure":
            # a positive pressure pushes against the outward normal (+x on
            # the bottom face): a force in -x, upwards
            value = scale * model.get("hold_traction", CASE["hold_traction"])
            return ["*DLOAD"] + ["HOLD%d, P%d, %.10g" % (k, k, value) for k in sorted(hold_sets)]
        lines = ["*CLOAD"]
        for n, force in sorted(hold_forces.items()):
            lines += ["%d, %d, %.10g" % (n, d + 1, scale * force[d] + 0.0)  # no "-0"
                      for d in range(3) if force[d] != 0]
        return lines

    out += material_cards("SILICONE", CASE["silicone"], densities["SILICONE"], options.law)
    if options.damping:
        # global in ccx 2.20 (see the docstring); must follow a *MATERIAL
        out.append("*DAMPING, ALPHA=0., BETA=%.10g" % CASE["silicone"]["zeta"])
    out += material_cards("BLOCK", CASE["block"], densities["BLOCK"], options.law)
    out += ["*SOLID SECTION, ELSET=SILICONE, MATERIAL=SILICONE",
            "*SOLID SECTION, ELSET=BLOCK, MATERIAL=BLOCK",
            "*BOUNDARY"]
    out += ["NB%d, %d, %d" % (b, first, last) for b, (first, last) in CASE["fixed"].items()]

    gravity = "EALL, GRAV, %.10g, 1., 0., 0." % CASE["gravity"]

    # Step 1: static equilibrium under gravity and hold (loads ramped over
    # two or more increments).
    out += ["*STEP, NLGEOM, INC=100", "*STATIC", "0.5, 1.", "*DLOAD", gravity]
    out += hold(1.0)
    out += ["*NODE PRINT, NSET=NTIP", "U"]
    # ccx wants energy output in the first step if a nonlinear dynamic step
    # follows; the total alone is cheap
    out += ["*EL PRINT, ELSET=EALL, TOTALS=ONLY", "ELSE", "*END STEP"]

    # Step 2: release. HHT with fixed increments (DIRECT); the loads of the
    # step apply in full from its start.
    n_increments = int(round(options.end_time / options.time_step))
    out += ["*STEP, NLGEOM, INC=%d" % (n_increments + 10),
            "*DYNAMIC, DIRECT, ALPHA=%g" % CASE["alpha"],
            "%g, %.10g" % (options.time_step, options.end_time)]
    if options.hold_load == "pressure":
        out += ["*DLOAD, OP=NEW", gravity]  # removes the pressures
    else:
        out += hold(0.0)
    out += ["*NODE PRINT, NSET=NTIP, FREQUENCY=1", "U", "*END STEP", ""]
    Path(path).write_text("\n".join(out))

    return model.get("hold_traction", CASE["hold_traction"]) * sum(
        area for _, _, _, area, _ in model["hold"])


# ---------------------------------------------------------------------------
# Running ccx
# ---------------------------------------------------------------------------
def ccx_version(ccx):
    result = subprocess.run([ccx, "-v"], capture_output=True, text=True, timeout=60)
    match = re.search(r"Version\s+(\S+)", result.stdout + result.stderr)
    return match.group(1) if match else "unknown"


def run_ccx(ccx, workdir, threads):
    """Run ccx on WORKDIR/job.inp; returns wall seconds, the peak resident
    memory of the child processes [KiB] and ccx's screen output."""
    env = dict(os.environ)
    for variable in ("OMP_NUM_THREADS", "CCX_NPROC_STIFFNESS", "CCX_NPROC_RESULTS",
                     "CCX_NPROC_EQUATION_SOLVER", "OPENBLAS_NUM_THREADS"):
        env[variable] = str(threads)
    log_path = workdir / (JOB + ".log")
    with open(log_path, "w") as log:
        start = time.perf_counter()
        result = subprocess.run([ccx, "-i", JOB], cwd=workdir, env=env,
                                stdout=log, stderr=subprocess.STDOUT)
        wall = time.perf_counter() - start
    peak_kib = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss  # KiB on Linux
    text = log_path.read_text(errors="replace")
    # ccx may exit with code 0 after an *ERROR
    if result.returncode != 0 or "*ERROR" in text:
        tail = "\n".join(text.splitlines()[-40:])
        sys.exit("ccx failed (exit code %d); the end of %s:\n%s\n\nccx failed, see above"
                 % (result.returncode, log_path, tail))
    return wall, peak_kib, text


# ---------------------------------------------------------------------------
# Results
# ---------------------------------------------------------------------------
def read_displacements(dat_path):
    """The blocks 'displacements (vx,vy,vz) for set NTIP and time T' of the
    .dat file: returns the total times and a list of {node: (ux, uy, uz)}."""
    header = re.compile(r"^\s*displacements \(vx,vy,vz\) for set NTIP and time\s+(\S+)")
    times, blocks, current = [], [], None
    with open(dat_path) as stream:
        for line in stream:
            match = header.match(line)
            if match:
                current = {}
                times.append(float(match.group(1)))
                blocks.append(current)
                continue
            values = line.split()
            if current is not None and len(values) == 4 and values[0].isdigit():
                current[int(values[0])] = tuple(float(v) for v in values[1:])
            elif values and not values[0].isdigit():
                current = None  # another kind of output block
    return np.array(times), blocks


def read_increments(sta_path):
    """Increments and Newton iterations per step from the .sta file."""
    steps = {}
    with open(sta_path) as stream:
        for line in stream:
            values = line.split()
            if len(values) == 7 and values[0].isdigit():
                step = steps.setdefault(int(values[0]), {"increments": 0, "iterations": 0})
                step["increments"] += 1
                step["iterations"] += int(values[3])
    return steps


def peak_frequency(t, u, padding=64):
    """Frequency of the largest FFT magnitude of u - mean(u), zero-padded to
    at least `padding` times its length, refined by the vertex of the
    parabola through the peak bin and its neighbours. Bins below 1/T (the
    leakage of the mean) are skipped."""
    dt = t[1] - t[0]
    signal = u - u.mean()
    n = 1 << int(math.ceil(math.log2(padding * len(signal))))
    magnitude = np.abs(np.fft.rfft(signal, n))
    frequency = np.fft.rfftfreq(n, dt)
    first = max(1, int(np.searchsorted(frequency, 1.0 / (len(signal) * dt))))
    k = first + int(np.argmax(magnitude[first:-1]))
    a, b, c = magnitude[k - 1 : k + 2]
    shift = 0.5 * (a - c) / (a - 2 * b + c)  # in bins
    return frequency[k] + shift * (frequency[1] - frequency[0])


def zero_crossing_frequency(t, u):
    """Frequency from the crossings of u - mean(u) (linearly interpolated):
    (number of crossings - 1) half periods between the first and the last.
    Returns (frequency or None, number of crossings)."""
    s = u - u.mean()
    k = np.nonzero(np.sign(s[:-1]) * np.sign(s[1:]) < 0)[0]
    if len(k) < 3:
        return None, len(k)
    crossings = t[k] - s[k] * (t[k + 1] - t[k]) / (s[k + 1] - s[k])
    return (len(crossings) - 1) / (2 * (crossings[-1] - crossings[0])), len(crossings)


def decay_damping_ratio(t, u, f):
    """Damping ratio from the decay of the cycle amplitudes: half the range
    of u in each full period 1/f, fitted by A0 exp(-2 pi xi f t)."""
    period = 1.0 / f
    starts = np.arange(t[0], t[-1] - period, period)
    if len(starts) < 3:
        return None
    centres, amplitudes = [], []
    for start in starts:
        window = (t >= start) & (t < start + period)
        centres.append(start + period / 2)
        amplitudes.append(0.5 * (u[window].max() - u[window].min()))
    slope = np.polyfit(centres, np.log(amplitudes), 1)[0]
    return -slope / (2 * math.pi * f)


def rounded(value, digits=5):
    return None if value is None else round(float(value), digits)


def analyse(t, u):
    """Frequencies and damping ratio of a tip history (None if too short)."""
    if len(t) < 20:
        return {}
    f_peak = peak_frequency(t, u)
    f_zero, n_crossings = zero_crossing_frequency(t, u)
    return {
        "f_peak_Hz": rounded(f_peak),
        "f_zero_crossings_Hz": rounded(f_zero),
        "zero_crossings": n_crossings,
        "xi_amplitude_decay": rounded(decay_damping_ratio(t, u, f_peak)),
    }


def tip_history(model, workdir):
    """The tip motion from the .dat file, with t = 0 at the end of the
    static step (total time 1); writes WORKDIR/tip_history.csv. Returns t
    and the x-displacement of the block's centre of mass."""
    times, blocks = read_displacements(workdir / (JOB + ".dat"))
    nodes, weights = model["tip_nodes"], model["tip_weights"]
    centre = np.array([sum(w * np.array(b[n]) for n, w in zip(nodes, weights)) for b in blocks])
    nodal_mean = np.array([np.mean([b[n][0] for n in nodes]) for b in blocks])
    axis = np.array([b[model["axis_node"]][0] for b in blocks])
    static_end = np.nonzero(np.isclose(times, 1.0))[0]
    if len(static_end) == 0:
        sys.exit("no output at the end of the static step in %s" % (workdir / (JOB + ".dat")))
    keep = np.arange(static_end[-1], len(times))
    t = times[keep] - 1.0
    with open(workdir / "tip_history.csv", "w") as stream:
        stream.write("# ccx tip motion of material 2 [mm]: u = volume-weighted mean (its centre "
                     "of mass), u_x_nodal_mean, u_x_axis_node (node %d)\n" % model["axis_node"])
        stream.write("t,u_x,u_y,u_z,u_x_nodal_mean,u_x_axis_node\n")
        for k in keep:
            stream.write("%.6g,%.10g,%.10g,%.10g,%.10g,%.10g\n"
                         % (times[k] - 1.0, *centre[k], nodal_mean[k], axis[k]))
    return t, centre[keep, 0]


def compare_with_ours(csv_path, t, ux):
    """Our tip_trajectory.csv, cut at the end time of the ccx run, through
    the same estimators, and the differences of the two histories if they
    share their times."""
    with open(csv_path) as stream:
        lines = [line for line in stream if not line.startswith("#")]
    names = lines[0].strip().split(",")
    data = np.array([[float(v) for v in line.split(",")] for line in lines[1:]])
    t_ours, u_ours = data[:, names.index("t")], data[:, names.index("u_x")]
    within = t_ours <= t[-1] + 1e-9
    t_ours, u_ours = t_ours[within], u_ours[within]
    ours = {"file": str(csv_path), "tip_u_x_t0_mm": rounded(u_ours[0], 4)}
    ours.update(analyse(t_ours, u_ours))
    n = min(len(t), len(t_ours))
    if np.allclose(t[:n], t_ours[:n], atol=1e-6):
        difference = ux[:n] - u_ours[:n]
        ours["max_abs_difference_u_x_mm"] = rounded(np.abs(difference).max(), 4)
        ours["rms_difference_u_x_mm"] = rounded(np.sqrt(np.mean(difference**2)), 4)
    return ours


def caveats(options):
    law = (
        "ccx ARRUDA-BOYCE with locking stretch %g and D = 2/kappa: our neo-Hookean energy up to "
        "< 1e-8 relative" % ARRUDA_BOYCE_LOCKING_STRETCH
        if options.law == "arruda-boyce" else
        "ccx NEO HOOKE (C10 = mu/2, D1 = 2/kappa): volumetric term (J-1)^2/D1 instead of our "
        "kappa/4 (J^2 - 1 - 2 ln J); same small-strain moduli, different at finite volume change")
    damping = (
        "Rayleigh damping (*DAMPING, BETA = zeta) is global in ccx 2.20: it also damps the tip "
        "block, which has no damping in our model"
        if options.damping else "run without damping (--no-damping); ours is damped")
    hold = (
        "hold as *DLOAD pressure: a follower load on the deformed faces (ours: a dead nominal "
        "traction)"
        if options.hold_load == "pressure" else
        "hold as *CLOAD consistent nodal forces: a dead load, as ours")
    return [
        law, damping, hold,
        "hold released in full at the start of the dynamic step (ours: HHT-weighted, 25 % of it "
        "still acts in the first time step)",
        "wall time is the whole ccx run (input, static step, dynamic step, .dat output)",
    ] + ([hex_caveat(options)] if options.hex else [] if options.degree == 1 else [
        "C3D10 in the displacement formulation (ours: the same quadratic elements with mean "
        "dilatation); on this mesh at kappa = 100 mu our displacement formulation rings 7.9 % "
        "higher than our mean dilatation (2.624 against 2.432 Hz at dt 0.01 s, locking.md)"])


def hex_caveat(options):
    return ("C3D20: 20-node serendipity hexahedra, full integration (3 x 3 x 3 points), in the "
            "displacement formulation, on the corners and mid-edge points of our cells (ours: "
            "27-node Lagrange hexahedra with the linear dilatation, or with --set 'Finite "
            "element/Volumetric formulation=displacement' in the displacement formulation too)")


# ---------------------------------------------------------------------------
def parse_arguments():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--workdir", default=str(REPOSITORY / "output" / "calculix_peer"),
                        help="directory for job.inp and ccx's output (default: "
                        "output/calculix_peer in the repository)")
    parser.add_argument("--mesh", default=str(REPOSITORY / CASE["mesh"]),
                        help="gmsh MSH 2.2 mesh (default: %s)" % CASE["mesh"])
    parser.add_argument("--degree", type=int, choices=(1, 2), default=1,
                        help="element degree: 1 for C3D4 (default), 2 for C3D10")
    parser.add_argument("--hex", action="store_true",
                        help="the hexahedral mesh of the bellows (ccx's 20-node hexahedra) "
                        "instead of the gmsh mesh")
    parser.add_argument("--hex-overrides", action="append", default=[], metavar="ENTRY",
                        help="with --hex: a further --set entry of the mesh, e.g. "
                        "'Geometry/Bellows/Cells through the wall=2' (repeatable)")
    parser.add_argument("--build", default=str(REPOSITORY / "build-release"),
                        help="with --hex: the build directory of our program, which writes "
                        "the mesh (default: build-release)")
    parser.add_argument("--end-time", type=float, default=CASE["end_time"],
                        help="end of the oscillation [s] (default: %g)" % CASE["end_time"])
    parser.add_argument("--time-step", type=float, default=CASE["time_step"],
                        help="fixed time increment [s] (default: the scene's %g)"
                        % CASE["time_step"])
    parser.add_argument("--threads", type=int, default=1, help="threads for ccx (default: 1)")
    parser.add_argument("--law", choices=("arruda-boyce", "neo-hooke"), default="arruda-boyce",
                        help="ccx potential: arruda-boyce with a large locking stretch (our "
                        "energy; default) or neo-hooke (volumetric term (J-1)^2/D1)")
    parser.add_argument("--hold-load", choices=("pressure", "cload"), default="pressure",
                        help="the hold as *DLOAD pressure (a follower load; default) or as "
                        "*CLOAD nodal forces (a dead load, as ours)")
    parser.add_argument("--no-damping", dest="damping", action="store_false",
                        help="omit the Rayleigh damping")
    parser.add_argument("--ccx", default="ccx", help="the ccx executable (default: ccx)")
    parser.add_argument("--compare", metavar="CSV",
                        help="our tip_trajectory.csv (e.g. output/vertical_ds20_3d/"
                        "tip_trajectory.csv): apply the same estimators and compare")
    return parser.parse_args()


def main():
    options = parse_arguments()
    ccx = shutil.which(options.ccx)
    if ccx is None:
        sys.exit("ccx not found (%s); on Debian: apt-get install calculix-ccx" % options.ccx)
    version = ccx_version(ccx)

    workdir = Path(options.workdir)
    workdir.mkdir(parents=True, exist_ok=True)
    for suffix in (".dat", ".sta", ".frd", ".cvg", ".log"):
        (workdir / (JOB + suffix)).unlink(missing_ok=True)

    if options.hex and options.hold_load != "pressure":
        sys.exit("--hex applies the hold as a pressure only (--hold-load pressure)")
    model = (build_hex_model(options, workdir) if options.hex
             else build_model(options.mesh, options.degree))
    mesh_label = model.get("label", Path(options.mesh).name)
    densities = densities_from_masses(model)
    hold_force = write_input(workdir / (JOB + ".inp"), model, options, densities)
    n_nodes = len(model["node_ids"])
    n_elements = sum(len(e["ids"]) for e in model["elements"].values())
    n_dofs, n_free_dofs = count_dofs(model)

    print("CalculiX %s peer of %s" % (version, CASE["scene"]))
    print("  mesh %s: %d nodes, %d %s elements, %d dofs (%d unconstrained)"
          % (mesh_label, n_nodes, n_elements, model["element_type"], n_dofs,
             n_free_dofs))
    print("  densities: silicone %.6g, block %.6g kg/mm^3; hold %.5g mN on %d faces"
          % (densities["SILICONE"], densities["BLOCK"], hold_force, len(model["hold"])))
    print("  running ccx in %s, %d thread(s), end time %g s ..."
          % (workdir, options.threads, options.end_time), flush=True)

    wall, peak_kib, log_text = run_ccx(ccx, workdir, options.threads)

    t, ux = tip_history(model, workdir)
    steps = read_increments(workdir / (JOB + ".sta"))
    match = re.search(r"Total CalculiX Time:\s*(\S+)", log_text)
    result = {
        "case": CASE["scene"],
        "solver": "CalculiX ccx",
        "ccx_version": version,
        "mesh": mesh_label,
        "nodes": n_nodes,
        "elements": n_elements,
        "element_type": model["element_type"],
        "dofs": n_dofs,
        "unconstrained_dofs": n_free_dofs,
        "threads": options.threads,
        "wall_seconds": round(wall, 3),
        "ccx_reported_seconds": float(match.group(1)) if match else None,
        "peak_memory_MiB": round(peak_kib / 1024, 1),
        "end_time": options.end_time,
        "time_step": options.time_step,
        "hht_alpha": CASE["alpha"],
        "static_increments": steps.get(1, {}).get("increments"),
        "static_iterations": steps.get(1, {}).get("iterations"),
        "dynamic_increments": steps.get(2, {}).get("increments"),
        "dynamic_iterations": steps.get(2, {}).get("iterations"),
        "material_law": options.law,
        "damping": ("Rayleigh, beta = %.6g s, global" % CASE["silicone"]["zeta"]
                    if options.damping else "none"),
        "hold_load": options.hold_load,
        "hold_force_mN": rounded(hold_force, 3),
        "tip_quantity": "x-displacement of the centre of mass of material 2 "
                        "(volume-weighted mean of its nodal displacements)",
        "tip_u_x_t0_mm": rounded(ux[0], 4),
        "tip_u_x_min_mm": rounded(ux.min(), 4),
        "tip_u_x_max_mm": rounded(ux.max(), 4),
        "tip_u_x_mean_mm": rounded(ux.mean(), 4),
    }
    result.update(analyse(t, ux))
    if options.compare:
        result["ours"] = compare_with_ours(options.compare, t, ux)
        if result.get("f_peak_Hz") and result["ours"].get("f_peak_Hz"):
            result["f_peak_relative_to_ours"] = rounded(
                result["f_peak_Hz"] / result["ours"]["f_peak_Hz"] - 1)
    result["caveats"] = caveats(options)
    (workdir / "calculix_peer.json").write_text(json.dumps(result, indent=2) + "\n")

    print("  wall time %.2f s (%d thread(s)), peak memory %.1f MiB"
          % (wall, options.threads, peak_kib / 1024))
    print("  increments: static %s, dynamic %s (%s Newton iterations)"
          % (result["static_increments"], result["dynamic_increments"],
             result["dynamic_iterations"]))
    print("  tip u_x at t = 0: %.4f mm; range %.3f .. %.3f mm" % (ux[0], ux.min(), ux.max()))
    if result.get("f_peak_Hz"):
        print("  tip frequency: FFT peak %.4f Hz, zero crossings %s Hz (%d crossings)"
              % (result["f_peak_Hz"], result["f_zero_crossings_Hz"], result["zero_crossings"]))
    if result.get("xi_amplitude_decay") is not None:
        print("  damping ratio from the amplitude decay: %.4f" % result["xi_amplitude_decay"])
    if "ours" in result:
        ours = result["ours"]
        print("  ours, same estimators: u_x at t = 0 %s mm, FFT peak %s Hz (ccx %+.2f %%), "
              "zero crossings %s Hz, xi %s"
              % (ours.get("tip_u_x_t0_mm"), ours.get("f_peak_Hz"),
                 100 * result.get("f_peak_relative_to_ours", float("nan")),
                 ours.get("f_zero_crossings_Hz"), ours.get("xi_amplitude_decay")))
        if "max_abs_difference_u_x_mm" in ours:
            print("  u_x(ccx) - u_x(ours): max %.3f mm, rms %.3f mm"
                  % (ours["max_abs_difference_u_x_mm"], ours["rms_difference_u_x_mm"]))
    print("  caveats:\n    - " + "\n    - ".join(result["caveats"]))
    print("  written: %s, %s" % (workdir / "calculix_peer.json", workdir / "tip_history.csv"))


if __name__ == "__main__":
    main()
