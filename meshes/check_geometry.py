#!/usr/bin/env python3
# SPDX-License-Identifier: LGPL-2.1-or-later
"""Check the parametric bellows geometry and its meshes against the reference.

Usage:
    python3 meshes/check_geometry.py path/to/actuator_section.csv [--plot]

The reference section (shared/paper/actuator_section.csv beside the project)
is only read here, as the yardstick. The section that is checked is the one
bellows.geo builds: gmsh runs the .geo with ExportSection = 1 and the script
reads the polygon it writes, so every design number lives in bellows.geo only
and this script measures exactly what the meshes are made from. The few plain
numbers the mesh checks need (base position, block size) are read from the
assignments at the top of bellows.geo for the same reason.

Checks, each printed in a table; the exit status is 1 if any fails:
  * revolved volume of the section (Pappus) within 2 % of the reference's;
  * Hausdorff distance between the two outlines, both ways, below 0.5 mm;
  * for every meshes/bellows_<model>_<level>.msh present: the meshed volume of
    each physical volume, the tagging of the boundary (every boundary face
    tagged, no interior face tagged, each tag on its plane), the element
    quality and the cavity volume enclosed by the faces tagged 2.

Needs python3 with numpy (Debian: python3-numpy), gmsh on the PATH, and
matplotlib for --plot (writes meshes/section_check.png).
"""

import math
import os
import re
import subprocess
import sys
import tempfile

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
GEO = os.path.join(HERE, "bellows.geo")

# Revolved volume of the reference section as the reference study states it
# (FACTS.md); the volume computed from the CSV must agree with it.
REFERENCE_VOLUME = 67483.0
VOLUME_TOLERANCE = 0.02  # relative, of the section's revolved volume
HAUSDORFF_TOLERANCE = 0.5  # mm, between the outlines
MIN_GAMMA = 0.01  # below this a tetrahedron counts as a sliver

# Quarters of the body in each model (bellows.geo's parameter Model).
MODEL_QUARTERS = {"quarter": 1, "half": 2, "full": 4}
# Boundary ids of the project (see README.md).
BASE, CAVITY, SYMMETRY_Y, SYMMETRY_Z, BLOCK_OUTER, SILICONE_OUTER = 1, 2, 3, 4, 5, 6
SILICONE, TIP_BLOCK = 1, 2


# @sect3{Reading the geometry}
def geo_parameters():
    """The plain numeric assignments `Name = number;` of bellows.geo."""
    values = {}
    with open(GEO) as geo:
        for line in geo:
            match = re.match(r"^(\w+)\s*=\s*(-?[0-9.]+(?:[eE][-+]?[0-9]+)?)\s*;", line)
            if match:
                values[match.group(1)] = float(match.group(2))
    return values


def read_polygon(path):
    """x, r columns of a CSV file; lines starting with '#' or a letter are skipped."""
    points = []
    with open(path) as csv:
        for line in csv:
            line = line.strip()
            if not line or line[0] == "#" or line[0].isalpha():
                continue
            x, r = line.split(",")[:2]
            points.append((float(x), float(r)))
    return np.array(points)


def parametric_section():
    """The section polygon as bellows.geo builds it."""
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "section.csv")
        log = subprocess.run(
            ["gmsh", GEO, "-0", "-setnumber", "ExportSection", "1",
             "-setstring", "SectionFile", path, "-o", os.path.join(tmp, "unrolled.geo")],
            capture_output=True, text=True)
        if log.returncode != 0 or "Error" in log.stdout + log.stderr or not os.path.exists(path):
            sys.exit("gmsh could not export the section:\n" + log.stdout + log.stderr)
        return read_polygon(path)


# @sect3{Section measures}
def revolved_volume(polygon):
    r"""Pappus: V = 2\pi \int r dA; by Green's theorem \int r dA = -\oint r^2/2 dx
    for a counter-clockwise polygon, exact for straight edges."""
    x, r = polygon[:, 0], polygon[:, 1]
    x2, r2 = np.roll(x, -1), np.roll(r, -1)
    return -math.pi / 3 * np.sum((x2 - x) * (r * r + r * r2 + r2 * r2))


def sample_outline(polygon, spacing=0.01):
    """Points along the closed outline, at most `spacing` apart."""
    start, end = polygon, np.roll(polygon, -1, axis=0)
    samples = [start]
    for a, b in zip(start, end):
        n = int(np.ceil(np.linalg.norm(b - a) / spacing))
        t = np.arange(1, n)[:, None] / n
        samples.append(a + t * (b - a))
    return np.vstack(samples)


def distance_to_outline(points, polygon):
    """Distance of each point to the closest edge of the closed polygon."""
    a, b = polygon, np.roll(polygon, -1, axis=0)
    best = np.full(len(points), np.inf)
    for start, end in zip(a, b):
        edge = end - start
        t = np.clip((points - start) @ edge / max(edge @ edge, 1e-300), 0, 1)
        best = np.minimum(best, np.linalg.norm(points - start - t[:, None] * edge, axis=1))
    return best


def directed_hausdorff(a, b):
    """Largest distance from the outline of a to the outline of b (sampled at
    0.01 mm, so exact to 0.005 mm) and where it occurs."""
    points = sample_outline(a)
    d = distance_to_outline(points, b)
    i = int(np.argmax(d))
    return d[i], points[i]


def cavity_polygon(section):
    """The cavity: the section's vertices up to the first one on the axis
    (bellows.geo lists the cavity first, from the base face to the axis),
    closed along the axis back to the base face, counter-clockwise."""
    on_axis = int(np.nonzero(section[:, 1] == 0)[0][0])
    cavity = section[: on_axis + 1]
    return np.vstack([cavity, [[section[0, 0], 0.0]]])[::-1]


# @sect3{Reading a mesh}
def read_msh22(path):
    """Nodes, tetrahedra with their physical tags, triangles with theirs."""
    with open(path) as msh:
        lines = msh.read().split("\n")
    i = lines.index("$Nodes")
    n = int(lines[i + 1])
    nodes = np.array([l.split() for l in lines[i + 2:i + 2 + n]], dtype=float)
    index = {int(tag): k for k, tag in enumerate(nodes[:, 0])}
    xyz = nodes[:, 1:4]
    i = lines.index("$Elements")
    m = int(lines[i + 1])
    tets, tet_tags, tris, tri_tags = [], [], [], []
    for line in lines[i + 2:i + 2 + m]:
        v = [int(s) for s in line.split()]
        kind, ntags = v[1], v[2]
        vertices = [index[k] for k in v[3 + ntags:]]
        if kind == 4:
            tets.append(vertices)
            tet_tags.append(v[3])
        elif kind == 2:
            tris.append(vertices)
            tri_tags.append(v[3])
        else:
            raise ValueError(f"{path}: unexpected element type {kind}")
    return xyz, np.array(tets), np.array(tet_tags), np.array(tris), np.array(tri_tags)


def tet_volumes_and_gamma(xyz, tets):
    """Signed volumes and gmsh's quality gamma = 3 r_in / r_circ (1 for the
    regular tetrahedron, 0 for a flat one)."""
    p = xyz[tets]
    volume = np.einsum("ij,ij->i", np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]), p[:, 3] - p[:, 0]) / 6
    area = sum(np.linalg.norm(np.cross(p[:, b] - p[:, a], p[:, c] - p[:, a]), axis=1) / 2
               for a, b, c in [(0, 1, 2), (0, 1, 3), (0, 2, 3), (1, 2, 3)])
    length = lambda a, b: np.linalg.norm(p[:, a] - p[:, b], axis=1)
    # Circumradius from the products of opposite edges (a formula of Crelle).
    q = np.stack([length(0, 1) * length(2, 3), length(0, 2) * length(1, 3), length(0, 3) * length(1, 2)])
    s = q.sum(axis=0) / 2
    r_circ = np.sqrt(np.maximum(s * (s - q[0]) * (s - q[1]) * (s - q[2]), 0)) / (6 * np.abs(volume))
    r_in = 3 * np.abs(volume) / area
    return volume, 3 * r_in / r_circ


def boundary_faces(tets):
    """Faces of the tetrahedral mesh that belong to one tetrahedron only, as
    sorted vertex triples, each with the vertex of its tetrahedron opposite it."""
    count, opposite = {}, {}
    for tet in tets:
        for k in range(4):
            face = tuple(sorted(np.delete(tet, k)))
            count[face] = count.get(face, 0) + 1
            opposite[face] = tet[k]
    return {face: opposite[face] for face, c in count.items() if c == 1}, count


def inscribed_bounds(xyz, tris, tags):
    r"""How much volume the flat triangles of the curved surfaces can cut off
    or add. Every face of the body is a cone, cylinder or plane annulus about
    the x axis with a straight meridian, so a flat triangle with its vertices
    on it strays from it only around the axis: if its vertices span the angle
    \Delta\theta about the axis and lie at radii up to r_max, no point of it
    lies further inside the surface, radially, than the sagitta
    r_max (1 - \cos(\Delta\theta/2)), and across the surface than that times
    n_r, the radial component of the surface's normal. The triangle lies on
    the solid's side of the outer surface and on the cavity's side of the
    cavity surface (both regions are convex across the axis), so the outer
    surface can only lose volume and the cavity surface only add it, each at
    most \sum A_T n_r r_max (1 - \cos(\Delta\theta_T/2)). Triangles in a plane
    x = const stray not at all."""
    loss = gain = 0.0
    for tri, tag in zip(tris, tags):
        if tag not in (CAVITY, SILICONE_OUTER):
            continue
        p = xyz[tri]
        if np.ptp(p[:, 0]) < 1e-9:
            continue
        area = np.linalg.norm(np.cross(p[1] - p[0], p[2] - p[0])) / 2
        radius = np.hypot(p[:, 1], p[:, 2])
        angle = np.arctan2(p[:, 2], p[:, 1])
        spread = max(abs(math.remainder(a - b, 2 * math.pi)) for a in angle for b in angle)
        # The gap is radial; across the surface it is that times the radial
        # component of the surface normal, |dx| / |(dx, dr)| along the meridian.
        dx, dr = np.ptp(p[:, 0]), np.ptp(radius)
        normal_r = dx / math.hypot(dx, dr)
        bound = area * radius.max() * (1 - math.cos(spread / 2)) * normal_r
        if tag == SILICONE_OUTER:
            loss += bound
        else:
            gain += bound
    return loss, gain


# @sect3{The checks}
class Report:
    def __init__(self):
        self.failed = False

    def row(self, what, value, limit, ok):
        self.failed |= not ok
        print(f"  {what:<46} {value:>22}   {limit:<24} {'ok' if ok else 'FAILED'}")


def check_section(reference_csv, report, plot):
    reference = read_polygon(reference_csv)
    section = parametric_section()
    v_ref_csv = revolved_volume(reference)
    v_section = revolved_volume(section)
    h_sec_ref, where_1 = directed_hausdorff(section, reference)
    h_ref_sec, where_2 = directed_hausdorff(reference, section)
    print(f"Section of bellows.geo ({len(section)} vertices) against {os.path.basename(reference_csv)} "
          f"({len(reference)} vertices)")
    report.row("revolved volume of the reference CSV, mm^3", f"{v_ref_csv:.1f}",
               f"FACTS.md {REFERENCE_VOLUME:.0f} +- 0.1 %",
               abs(v_ref_csv / REFERENCE_VOLUME - 1) < 1e-3)
    error = v_section / REFERENCE_VOLUME - 1
    report.row("revolved volume of bellows.geo, mm^3", f"{v_section:.1f} ({100 * error:+.3f} %)",
               f"within {100 * VOLUME_TOLERANCE:.0f} %", abs(error) < VOLUME_TOLERANCE)
    report.row("Hausdorff bellows.geo -> reference, mm", f"{h_sec_ref:.4f}",
               f"< {HAUSDORFF_TOLERANCE}", h_sec_ref < HAUSDORFF_TOLERANCE)
    report.row("Hausdorff reference -> bellows.geo, mm", f"{h_ref_sec:.4f}",
               f"< {HAUSDORFF_TOLERANCE}", h_ref_sec < HAUSDORFF_TOLERANCE)
    print(f"  (largest gaps at x = {where_1[0]:.3f}, r = {where_1[1]:.3f} and "
          f"x = {where_2[0]:.3f}, r = {where_2[1]:.3f})")
    if plot:
        write_plot(reference, section)
    return section


def write_plot(reference, section):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(2, 1, figsize=(11, 6.5), gridspec_kw={"height_ratios": [1, 1.4]})
    for ax in axes:
        closed = lambda p: np.vstack([p, p[:1]])
        ax.plot(*closed(reference).T, "-", color="0.6", lw=4, label="reference section (CSV)")
        ax.plot(*closed(section).T, "-", color="C3", lw=1, label="bellows.geo")
        ax.plot(*section.T, ".", color="C3", ms=3)
        ax.set_aspect("equal")
        ax.set_xlabel("x (mm), along the axis")
        ax.set_ylabel("r (mm)")
    axes[0].legend(loc="upper right", fontsize=8)
    axes[0].set_title("Axisymmetric section of the bellows actuator")
    axes[1].set_xlim(68, 91)
    axes[1].set_ylim(-0.5, 19.5)
    axes[1].set_title("last convolutions, neck and end cap")
    fig.tight_layout()
    path = os.path.join(HERE, "section_check.png")
    fig.savefig(path, dpi=130)
    print(f"  wrote {os.path.relpath(path)}")


def check_mesh(path, model, section, parameters, report):
    quarters = MODEL_QUARTERS[model]
    fraction = quarters / 4
    x_base = parameters["XBase"]
    x_end = section[:, 0].max()
    block_length, block_width = parameters["BlockLength"], parameters["BlockWidth"]
    xyz, tets, tet_tags, tris, tri_tags = read_msh22(path)
    volume, gamma = tet_volumes_and_gamma(xyz, tets)
    print(f"{os.path.basename(path)}: {len(tets)} tetrahedra, {len(xyz)} nodes, "
          f"{len(tris)} boundary triangles")

    report.row("tetrahedra with non-positive volume", f"{np.sum(volume <= 0)}", "0", np.all(volume > 0))
    report.row("quality gamma: min / mean", f"{gamma.min():.3f} / {gamma.mean():.3f}",
               f"min >= {MIN_GAMMA}", gamma.min() >= MIN_GAMMA)
    print(f"  {'  tetrahedra with gamma < 0.1 / < 0.2':<46} {np.sum(gamma < 0.1):>10} / {np.sum(gamma < 0.2):<10}")

    # Tagging: the tagged triangles must be exactly the boundary faces.
    boundary, _ = boundary_faces(tets)
    tagged = {tuple(sorted(t)): tag for t, tag in zip(tris, tri_tags)}
    untagged = len(set(boundary) - set(tagged))
    interior = len(set(tagged) - set(boundary))
    report.row("boundary faces untagged / tagged faces inside", f"{untagged} / {interior}", "0 / 0",
               untagged == 0 and interior == 0)
    expected_ids = {BASE, CAVITY, BLOCK_OUTER, SILICONE_OUTER}
    expected_ids |= {SYMMETRY_Y, SYMMETRY_Z} if quarters == 1 else {SYMMETRY_Z} if quarters == 2 else set()
    ids = set(int(t) for t in tri_tags)
    report.row("boundary ids present", " ".join(map(str, sorted(ids))),
               " ".join(map(str, sorted(expected_ids))), ids == expected_ids)
    on_plane = {BASE: lambda p: np.abs(p[:, 0] - x_base),
                SYMMETRY_Y: lambda p: np.abs(p[:, 1]),
                SYMMETRY_Z: lambda p: np.abs(p[:, 2])}
    for tag, distance in on_plane.items():
        if tag in ids:
            worst = max(distance(xyz[t]).max() for t in tris[tri_tags == tag])
            report.row(f"faces {tag}: largest distance from their plane", f"{worst:.1e}", "< 1e-9", worst < 1e-9)
    block_points = xyz[tris[tri_tags == BLOCK_OUTER]].reshape(-1, 3)
    half = block_width / 2
    on_box = np.minimum.reduce([np.abs(block_points[:, 0] - x_end),
                                np.abs(block_points[:, 0] - x_end - block_length),
                                np.abs(np.abs(block_points[:, 1]) - half), np.abs(np.abs(block_points[:, 2]) - half),
                                np.abs(block_points[:, 1]), np.abs(block_points[:, 2])])
    report.row("faces 5: largest distance from the block's box", f"{on_box.max():.1e}", "< 1e-9",
               on_box.max() < 1e-9)
    # Bounding box: inside the exact one of the model's sector (the outer
    # crests reach r_max beyond the block's half width), and touching it where
    # nodes are sure to lie: the base, the block's far face, the section in
    # the x-y plane (y = r_max) and the symmetry planes.
    r_max = max(section[:, 1].max(), half)
    lower = np.array([x_base, -r_max if quarters >= 2 else 0.0, -r_max if quarters == 4 else 0.0])
    upper = np.array([x_end + block_length, r_max, r_max])
    low, high = xyz.min(axis=0), xyz.max(axis=0)
    inside = np.all(low >= lower - 1e-9) and np.all(high <= upper + 1e-9)
    touching = [abs(low[0] - lower[0]), abs(high[0] - upper[0]), abs(high[1] - upper[1])]
    touching += [abs(low[1])] if quarters == 1 else []
    touching += [abs(low[2])] if quarters <= 2 else []
    report.row("bounding box", f"{np.round(low, 3)}..{np.round(high, 3)}",
               "inside the exact box", inside and max(touching) < 1e-9)

    # Volumes. The silicone is compared with the exact revolved section within
    # the bounds of inscribed_bounds(); the block is exact.
    exact = revolved_volume(section) * fraction
    silicone = volume[tet_tags == SILICONE].sum()
    block = volume[tet_tags == TIP_BLOCK].sum()
    loss, gain = inscribed_bounds(xyz, tris, tri_tags)
    report.row("silicone volume / exact model fraction", f"{silicone:.1f} / {exact:.1f} ({100 * (silicone / exact - 1):+.2f} %)",
               f"[-{100 * loss / exact:.1f} %, +{100 * gain / exact:.1f} %]",
               exact - loss - 1e-6 * exact <= silicone <= exact + gain + 1e-6 * exact)
    report.row("  fraction of the full body (exact)", f"{silicone / revolved_volume(section):.4f}",
               f"{fraction} less the loss", True)
    exact_block = block_length * block_width ** 2 * fraction
    report.row("tip block volume", f"{block:.4f} / {exact_block:.4f}", "to round-off",
               abs(block - exact_block) < 1e-9 * exact_block)

    # Cavity volume from the faces tagged 2 by the divergence theorem with the
    # field F = (x - x_base, 0, 0): div F = 1, F.n = 0 on the symmetry planes
    # and on the inlet opening, so V = -\int_{cavity} (x - x_base) n_x dA with
    # n the normal pointing out of the silicone (away from the opposite vertex).
    cavity = 0.0
    for tri in tris[tri_tags == CAVITY]:
        face = tuple(sorted(tri))
        p = xyz[list(face)]
        n = np.cross(p[1] - p[0], p[2] - p[0]) / 2
        if n @ (p[0] - xyz[boundary[face]]) < 0:
            n = -n
        cavity -= (p[:, 0].mean() - x_base) * n[0]
    exact_cavity = revolved_volume(cavity_polygon(section)) * fraction
    report.row("cavity volume (faces 2) / exact", f"{cavity:.1f} / {exact_cavity:.1f} ({100 * (cavity / exact_cavity - 1):+.2f} %)",
               f"[-{100 * gain / exact_cavity:.1f} %, 0]", exact_cavity - gain - 1e-6 * exact_cavity <= cavity <= exact_cavity * (1 + 1e-6))
    return {"tets": len(tets), "nodes": len(xyz), "silicone": silicone, "exact": exact}


def main():
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    if len(args) != 1:
        sys.exit(__doc__)
    report = Report()
    section = check_section(args[0], report, "--plot" in sys.argv)
    parameters = geo_parameters()
    meshes = {}
    for level in ("coarse", "medium", "fine", "extrafine", "ultrafine"):
        for model in MODEL_QUARTERS:
            path = os.path.join(HERE, f"bellows_{model}_{level}.msh")
            if os.path.exists(path):
                print()
                meshes[(model, level)] = check_mesh(path, model, section, parameters, report)
    if meshes:
        print("\nSymmetry fractions: silicone volume of the model over that of the exact")
        print("full body, and over that of the full mesh of the same level:")
        full = revolved_volume(section)
        for (model, level), m in meshes.items():
            full_mesh = meshes.get(("full", level))
            ratio = f"{m['silicone'] / full_mesh['silicone']:.4f}" if full_mesh else "-"
            print(f"  {model:<8} {level:<7} {m['tets']:>7} tets {m['nodes']:>7} nodes   "
                  f"{m['silicone'] / full:.4f}  {ratio:>7}  (nominal {MODEL_QUARTERS[model] / 4})")
    print("\nall checks passed" if not report.failed else "\nSOME CHECKS FAILED")
    return 1 if report.failed else 0


if __name__ == "__main__":
    sys.exit(main())
