#!/usr/bin/python3
# SPDX-License-Identifier: LGPL-2.1-or-later
"""The reference of experiment 1 on the hexahedral mesh of the bellows
(issue 23): quadratic hexahedra with pressure and dilatation linear in
each cell (`Geometry/Mesh source = bellows`, include/core/bellows_mesh.h;
`Volumetric formulation = linear dilatation`) over resolutions through
the wall, along the flanks and folds and about the axis, over time steps,
and for the three silicones; on the default mesh also the mean-dilatation
and the displacement formulations; and the tip block's shape (the study's
box against the cylinder of the hexahedral mesh) on one tetrahedral mesh.
The companion of run_reference.py (quadratic tetrahedra), with the same
solver settings (its SOLVER list) and record (2.5 s of the vertical
oscillation, the modal fit after the first second). The report
doc/reference_hex.md; its discussion is the section on hexahedra in
doc/reference_discussion.md.

    /usr/bin/python3 doc/reference/run_hex_reference.py build-release
        [--cases a,b] [--timeout 3600] [--threads 1] [--report-only]

A mesh is named hex-T-F-C-Q: T cells through the wall, F along a flank,
C per chord of a fold, Q per quarter turn (Geometry/Bellows); -refined is
that mesh refined once globally. The hold before the release is the
scene's 958.4 mN on the block's end face, in kPa for its area: 1.08824
for the cylinder (880.69 mm²), 1.1397 for the box (841 mm²).

Nothing here is a test: the numbers are reported, not checked.
"""

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from run_reference import (SOLVER, load_case, percent,  # noqa: E402
                           read_vertical, run_scene)
from run_benchmarks import (HEX_HOLD_TRACTION, HEX_MESHES,  # noqa: E402
                            HEX_OVERRIDES, write_with_discussion_link)
from study_session import run_lines, study_main  # noqa: E402

RECORD = 2.5  # s
HOLD = {"cylinder": f"hold={HEX_HOLD_TRACTION:g}", "box": "hold=1.1397"}
DEFAULT = "hex-1-3-1-2"

HEXAHEDRA = HEX_OVERRIDES
DISPLACEMENT = ["Finite element/Volumetric formulation=displacement"]
MEAN_DILATATION = ["Finite element/Volumetric formulation=mean dilatation"]
TETRAHEDRA = ["Geometry/Mesh source=file",
              "Geometry/Mesh file=../../meshes/bellows_quarter_{level}.msh"]

# name, silicone key, mesh label, time step, extra overrides
CASES = ([(f"ds20_{DEFAULT}_dt{dt:g}", "ds20", DEFAULT, dt, [])
          for dt in (0.01, 0.005, 0.0025)] +
         [(f"ds20_{mesh}_dt0.01", "ds20", mesh, 0.01, [])
          for mesh in HEX_MESHES if mesh != DEFAULT] +
         [(f"ds20_{mesh}_dt0.005", "ds20", mesh, 0.005, [])
          for mesh in ("hex-2-6-2-2", "hex-1-3-1-2-refined")] +
         [(f"{s}_{mesh}_dt0.01", s, mesh, 0.01, [])
          for s in ("ds30", "ef50")
          for mesh in (DEFAULT, "hex-2-6-2-2", "hex-1-3-1-2-refined")] +
         [(f"ds20_{DEFAULT}_mean-dilatation_dt0.01", "ds20", DEFAULT, 0.01,
           MEAN_DILATATION),
          (f"ds20_{DEFAULT}_displacement_dt0.01", "ds20", DEFAULT, 0.01,
           DISPLACEMENT)] +
         [(f"ds20_tet-medium-{shape}_dt0.01", "ds20", f"tet-medium-{shape}", 0.01, [])
          for shape in ("box", "cylinder")] +
         # The displacement formulation refined: its locking errs on the
         # stiff side, so its frequency bounds the converged one from above
         # (the bound the tetrahedral reference must respect).
         [("ds20_hex-1-3-1-2-refined_displacement_dt0.01", "ds20", "hex-1-3-1-2-refined",
           0.01, DISPLACEMENT)])
CASE_NAMES = [c[0] for c in CASES]
# The mesh whose runs the others are compared with, and the finest one with
# a second time step.
REFERENCE_MESH = "hex-1-3-1-2-refined"
FINE_MESH = "hex-2-6-2-2"


def overrides(mesh, dt, extra):
    if mesh.startswith("tet-"):
        _, level, shape = mesh.split("-")
        if shape == "cylinder":
            level += "-cylinder"
        entries = [e.format(level=level) for e in TETRAHEDRA]
        hold = HOLD[shape]
    else:
        entries = HEXAHEDRA + HEX_MESHES[mesh][0]
        hold = HOLD["cylinder"]
    return (SOLVER + entries + extra +
            [f"Loads and constraints/Function constants={hold}",
             f"Time integration/End time={RECORD:g}",
             f"Time integration/Time step={dt:g}"])


def run_case(build, output_root, name, timeout, threads):
    _, silicone, mesh, dt, extra = next(c for c in CASES if c[0] == name)
    if mesh.endswith("cylinder"):
        from run_reference import ensure_mesh
        ensure_mesh("medium-cylinder")
    run_scene(build, output_root / name, name,
              f"parameters/bellows/vertical_{silicone}_3d.prm",
              overrides(mesh, dt, extra), timeout, threads, read_vertical)


def write_report(path, results, session):
    by_name = {r["name"]: r for r in results
               if r.get("status") == "finished" and r.get("spectrum")}
    lines = ["<!-- Written by doc/reference/run_hex_reference.py; the discussion is "
             "in doc/reference_discussion.md. -->",
             "# The reference of experiment 1 on hexahedra", ""]
    lines += run_lines(session)
    lines += ["",
              "Quadratic hexahedra with pressure and dilatation linear in each cell "
              "(unless the case says otherwise; the tetrahedra are quadratic with "
              "mean dilatation), HHT α = −0.25, baseline parameter set, 2.5 s "
              "of the vertical oscillation; f and ξ are the modal fit of the "
              "vertical tip motion after the first second. A mesh hex-T-F-C-Q has "
              "T cells through the wall, F along a flank, C per chord of a fold "
              "and Q per quarter turn. Wall times are the program's own, with the "
              "threads the line of each run above gives; sessions listed with the "
              "same start load ran at the same time, one on each core. The "
              "energy balance is the energy the run lost beyond the damping's "
              "(T + Π + V − W + D at the end, 1e-6 J; HHT's algorithmic "
              "dissipation). The static u_x is the tip's displacement along the "
              "axis in the static equilibrium under gravity and the hold, before the release.", "",
              "## All runs", "",
              "| case | mesh | dofs | dt s | static u_x mm | f Hz | ξ | wall s | "
              "Newton/step | factorizations/step | cutbacks | energy balance |",
              "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for name, silicone, mesh, dt, extra in CASES:
        r = by_name.get(name)
        if not r:
            lines.append(f"| {name} | {mesh} | | {dt:g} | not run | | | | | | | |")
            continue
        lines.append(
            f"| {name} | {mesh} | {r['dofs']} | {dt:g} | "
            f"{r.get('static_u_x', float('nan')):.2f} | {r['spectrum']['f']:.5f} | "
            f"{r['spectrum']['xi']:.5f} | {r['wall_seconds']:.1f} | "
            f"{r['newton_iterations'] / r['steps']:.2f} | "
            f"{r['factorizations_or_amg_setups'] / r['steps']:.2f} | "
            f"{r['cutbacks']} | {r.get('energy_balance', float('nan')):.1f} |")

    lines += ["", f"## Against the reference mesh ({REFERENCE_MESH}, same silicone "
              "and step)", "",
              "| case | error of f | error of ξ |", "|---|---:|---:|"]
    for name, silicone, mesh, dt, extra in CASES:
        reference = by_name.get(f"{silicone}_{REFERENCE_MESH}_dt{dt:g}")
        r = by_name.get(name)
        if r and reference and r is not reference:
            lines.append(
                f"| {name} | {percent(r['spectrum']['f'], reference['spectrum']['f'])} | "
                f"{percent(r['spectrum']['xi'], reference['spectrum']['xi'])} |")

    lines += ["", "## The time step (Dragon Skin 20)", "",
              "| mesh | quantity | dt = 0.01 | dt = 0.005 | dt = 0.0025 | change 0.01 → "
              "0.005 | change 0.005 → 0.0025 |", "|---|---|---:|---:|---:|---:|---:|"]
    for mesh in (DEFAULT, FINE_MESH):
        runs = [by_name.get(f"ds20_{mesh}_dt{dt:g}") for dt in (0.01, 0.005, 0.0025)]
        for key, label in (("f", "f Hz"), ("xi", "ξ")):
            values = [r["spectrum"][key] if r else None for r in runs]
            cells = [f"{v:.6g}" if v is not None else "–" for v in values]
            changes = [percent(a, b, 3) if a is not None and b is not None else "–"
                       for a, b in zip(values, values[1:])]
            lines.append(f"| {mesh} | {label} | {' | '.join(cells)} | "
                         f"{' | '.join(changes)} |")
    lines += ["", "A change is that of the larger step relative to the smaller one."]

    lines += ["", "## The tip block's shape (Dragon Skin 20, medium tetrahedral mesh, "
              "dt = 0.01 s)", "", "| block | f Hz | ξ | change of f | change of ξ |",
              "|---|---:|---:|---:|---:|"]
    box = by_name.get("ds20_tet-medium-box_dt0.01")
    cylinder = by_name.get("ds20_tet-medium-cylinder_dt0.01")
    if box and cylinder:
        for label, r in (("box (the study's)", box), ("cylinder", cylinder)):
            lines.append(f"| {label} | {r['spectrum']['f']:.6f} | "
                         f"{r['spectrum']['xi']:.6f} | "
                         f"{percent(r['spectrum']['f'], box['spectrum']['f'], 3)} | "
                         f"{percent(r['spectrum']['xi'], box['spectrum']['xi'], 3)} |")
    else:
        lines.append("| | not run | | | |")
    write_with_discussion_link(path, lines, "reference_discussion.md")


def load_with_energy(output_root, name):
    """load_case, and the energy balance at the end of the trajectory."""
    result = load_case(output_root, name)
    if result is None:
        return None
    trajectory = output_root / name / "tip_trajectory.csv"
    if trajectory.exists():
        rows = [line for line in trajectory.read_text().splitlines()
                if not line.startswith("#")]
        header = rows[0].split(",")
        if "energy_balance" in header and len(rows) > 1:
            result["energy_balance"] = float(
                rows[-1].split(",")[header.index("energy_balance")])
        if "u_x" in header and len(rows) > 1:
            # the static equilibrium under gravity and the hold
            result["static_u_x"] = float(rows[1].split(",")[header.index("u_x")])
    return result


if __name__ == "__main__":
    study_main(__doc__, "doc/reference/run_hex_reference.py", "output/reference_hex",
               "doc/reference_hex.md", CASE_NAMES, run_case, load_with_energy,
               write_report)
