#!/usr/bin/python3
# SPDX-License-Identifier: LGPL-2.1-or-later
"""The reference solution of experiment 1 (issue 23): how far the
discretisation that does not lock -- quadratic tetrahedra in the
mean-dilatation formulation -- is from converged, in time and in space, on
the vertical oscillation of the quarter model, for the three silicones.
Each case is one run of the Release build of soft-robot; the report
doc/reference.md gives the frequency and damping ratio of each run (the
modal fit of the vertical tip motion, `tip_spectrum.csv`), their changes
under halving the step and under refining the mesh, the step-size limit
extrapolated from the observed order, and the silicone volume each mesh
holds. Its discussion is doc/reference_discussion.md.

    /usr/bin/python3 doc/reference/run_reference.py build-release
        [--cases a,b] [--timeout 1800] [--threads 1] [--report-only]

The runs. The scenes `parameters/bellows/vertical_<silicone>_3d.prm`
with `Polynomial degree = 2`, `Volumetric formulation = mean dilatation`,
`Time integration/End time = 2.5` (six periods; the spectral analysis
skips the first second, as in the scenes) and without VTU output. The
Newton solver keeps its matrix across steps (`Tangent update = when
needed`) and stops at 1e-6 of the force scale: the benchmark's
`p2md_headline` and `p2md_headline_kept` cases show that this changes the
frequency by less than 1e-8 relative, far below the differences measured
here; one case stops at 1e-4 instead, to show what a looser tolerance
saves and changes. The meshes are the committed coarse, medium, fine and
extrafine quarter meshes (meshes/README.md); on the extrafine ones the
direct solver is MUMPS. A second extrafine mesh, made with another
surface mesher (extrafine-frontal), measures how much two meshes of one
size disagree.
It and the curved coarse and medium meshes (10-node tetrahedra, their
mid-edge nodes on the CAD surfaces) are not committed: the study writes
them with meshes/generate_meshes.sh.

Nothing here is a test: the numbers are reported, not checked.
"""

import csv
import json
import math
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

REPOSITORY = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(REPOSITORY / "doc" / "performance"))
sys.path.insert(0, str(REPOSITORY / "doc" / "stability"))
sys.path.insert(0, str(REPOSITORY / "doc"))
from run_benchmarks import write_with_discussion_link  # noqa: E402
from study_session import run_lines, study_main, tetrahedral_defaults  # noqa: E402
from run_stability import run_program  # noqa: E402

RECORD = 2.5  # s
MESHES = "../../meshes/bellows_quarter"  # relative to the scene's directory
SILICONES = {"ds20": "Dragon Skin 20", "ds30": "Dragon Skin 30",
             "ef50": "Ecoflex 00-50"}
SOLVER = ["Finite element/Polynomial degree=2",
          "Finite element/Volumetric formulation=mean dilatation",
          "Nonlinear solver/Tangent update=when needed",
          "Nonlinear solver/Relative tolerance=1e-6",
          "Nonlinear solver/Absolute tolerance=0",
          "Nonlinear solver/Acceleration depth=5",
          "Output/Progress interval=0", "Output/Write VTU=false"]

# name, silicone key, mesh level, time step
CASES = ([("ds20_coarse_dt" + f"{dt:g}", "ds20", "coarse", dt)
          for dt in (0.01, 0.005, 0.0025)] +
         [("ds20_medium_dt" + f"{dt:g}", "ds20", "medium", dt)
          for dt in (0.01, 0.005)] +
         [("ds20_fine_dt0.01", "ds20", "fine", 0.01),
          ("ds20_extrafine_dt0.01", "ds20", "extrafine", 0.01)] +
         [(f"{s}_{level}_dt0.01", s, level, 0.01)
          for s in ("ds30", "ef50") for level in ("coarse", "medium", "extrafine")] +
         [(f"ds20_{level}_dt0.01", "ds20", level, 0.01)
          for level in ("coarse-curved", "medium-curved", "extrafine-frontal")] +
         [("ds20_coarse_dt0.01_tolerance1e-4", "ds20", "coarse", 0.01)])
CASE_NAMES = [c[0] for c in CASES]
# Cases that change a setting of SOLVER: the Newton tolerance 100 times
# looser, to see what it saves and what it changes.
EXTRA = {"ds20_coarse_dt0.01_tolerance1e-4": ["Nonlinear solver/Relative tolerance=1e-4"]}
LEVELS = ("coarse", "medium", "fine", "extrafine")
# The curved meshes (10-node tetrahedra, include/core/curved_geometry.h) and
# the flat level each is compared with: the coarse one has the same cells
# as the flat coarse mesh; the medium one is made with another surface
# mesher (meshes/generate_meshes.sh), so its cells differ from the flat
# medium mesh's.
CURVED = {"coarse-curved": ("coarse", True), "medium-curved": ("medium", False)}


def overrides(name, level, dt):
    # MUMPS on the extrafine meshes (about 115,000 unknowns), the direct
    # solver that Linear solver/Direct solver recommends for large meshes;
    # the answer does not depend on the direct solver.
    solver = (["Linear solver/Direct solver=MUMPS"] if level.startswith("extrafine")
              else [])
    return SOLVER + solver + [f"Time integration/End time={RECORD:g}",
                              f"Geometry/Mesh file={MESHES}_{level}.msh",
                              f"Time integration/Time step={dt:g}"] + EXTRA.get(name, [])


def read_vertical(output):
    """Frequency and damping ratio of the vertical motion's modal fit."""
    path = output / "tip_spectrum.csv"
    if not path.exists():
        return None
    with open(path) as file:
        for row in csv.DictReader(file):
            if row["direction"] == "vertical" and row["peak"] == "dominant":
                return {"f": float(row["f_damped_fit_Hz"]),
                        "xi": float(row["xi_fit"])}
    return None


def silicone_volume(materials):
    """The silicone volume of the model, mm^3, from the printed density
    and mass of material 1."""
    for line in materials:
        match = re.match(r"Material 1 .*density = ([0-9.e+-]+) kg/mm\^3, "
                         r"mass in the model = ([0-9.e+-]+) kg", line)
        if match:
            return float(match.group(2)) / float(match.group(1))
    return None


def ensure_mesh(level):
    """Writes a mesh that is not committed (the curved ones, the second
    extrafine one) with meshes/generate_meshes.sh."""
    mesh = REPOSITORY / "meshes" / f"bellows_quarter_{level}.msh"
    if not mesh.exists():
        print(f"writing {mesh.name} with gmsh", flush=True)
        subprocess.run(["bash", str(REPOSITORY / "meshes/generate_meshes.sh"),
                        "quarter", level], check=True)


def run_scene(build, output, name, scene, entries, timeout, threads, read_spectrum):
    """One run of `scene` with the `--set` entries (after those of
    tetrahedral_defaults) into a fresh `output`;
    writes its result.json (the run, the spectrum read_spectrum(output)
    finds, the silicone volume). Shared with run_swing_reference.py."""
    if output.exists():
        shutil.rmtree(output)
    output.mkdir(parents=True)
    command = [str(build / "soft-robot"), scene,
               "--set", f"Problem/Output directory={output}"]
    for entry in tetrahedral_defaults(scene) + entries:
        command += ["--set", entry]
    environment = dict(os.environ, OMP_NUM_THREADS="1",
                       DEAL_II_NUM_THREADS=str(threads))
    print(f"[{name}]", flush=True)
    _, result = run_program(command, environment, output, timeout)
    result["spectrum"] = read_spectrum(output)
    result["volume"] = silicone_volume(result["materials"])
    (output / "result.json").write_text(json.dumps(result))
    wall = read_statistics(output).get("wall_seconds", float("nan"))
    print(f"    {result['status']}, {wall:.1f} s, {result['spectrum']}", flush=True)


def run_case(build, output_root, name, timeout, threads):
    _, silicone, level, dt = next(c for c in CASES if c[0] == name)
    ensure_mesh(level)
    run_scene(build, output_root / name, name,
              f"parameters/bellows/vertical_{silicone}_3d.prm",
              overrides(name, level, dt), timeout, threads, read_vertical)


def read_statistics(output):
    """What the report uses of the program's run_statistics.json."""
    path = output / "run_statistics.json"
    if not path.exists():
        return {}
    s = json.loads(path.read_text())
    return {k: s[k] for k in ("wall_seconds", "dofs", "cells", "steps",
                              "newton_iterations", "factorizations_or_amg_setups",
                              "cutbacks", "peak_memory_mb")}


def load_case(output_root, name):
    path = output_root / name / "result.json"
    if not path.exists():
        return None
    result = json.loads(path.read_text())
    result.update(read_statistics(output_root / name))
    result["name"] = name
    return result


def percent(value, reference, digits=2):
    return f"{100. * (value / reference - 1.):+.{digits}f} %"


def write_report(path, results, session):
    by_name = {r["name"]: r for r in results
               if r.get("status") == "finished" and r.get("spectrum")}
    lines = ["<!-- Written by doc/reference/run_reference.py; the discussion is in "
             "doc/reference_discussion.md. -->",
             "# The reference of experiment 1", ""]
    lines += run_lines(session)
    lines += ["",
              "Quadratic tetrahedra in the mean-dilatation formulation, HHT "
              "α = −0.25, baseline parameter set, 2.5 s of the vertical "
              "oscillation; f and ξ are the modal fit of the vertical tip "
              "motion after the first second. The silicone volume is that of the "
              "mesh (the density is set so that the model carries the measured "
              "mass; the section's revolved volume is 16,871 mm³ per quarter, "
              "meshes/README.md). Wall times are the program's own, with the "
              "threads the line of each run above gives; sessions listed with "
              "the same start load ran at the same time, one on each core.",
              "", "## All runs", "",
              "| case | silicone | mesh | dofs | silicone volume mm³ | dt s | "
              "f Hz | ξ | wall s | Newton/step | factorizations/step |",
              "|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for name, silicone, level, dt in CASES:
        r = by_name.get(name)
        if not r:
            lines.append(f"| {name} | {SILICONES[silicone]} | {level} | | | {dt:g} "
                         "| not run | | | | |")
            continue
        lines.append(
            f"| {name} | {SILICONES[silicone]} | {level} | {r['dofs']} | "
            f"{r['volume']:.0f} | {dt:g} | {r['spectrum']['f']:.5f} | "
            f"{r['spectrum']['xi']:.5f} | {r['wall_seconds']:.1f} | "
            f"{r['newton_iterations'] / r['steps']:.2f} | "
            f"{r['factorizations_or_amg_setups'] / r['steps']:.2f} |")

    # The step: the coarse Dragon Skin 20 series, its observed order and
    # the extrapolated limit.
    series = [by_name.get(f"ds20_coarse_dt{dt:g}") for dt in (0.01, 0.005, 0.0025)]
    lines += ["", "## The time step (Dragon Skin 20, coarse mesh)", ""]
    if all(series):
        lines += ["| quantity | dt = 0.01 | dt = 0.005 | dt = 0.0025 | observed order "
                  "| limit dt → 0 | error at 0.01 | error at 0.005 |",
                  "|---|---:|---:|---:|---:|---:|---:|---:|"]
        for key, label in (("f", "f Hz"), ("xi", "ξ")):
            a, b, c = (s["spectrum"][key] for s in series)
            if (a - b) * (b - c) > 0 and abs(b - c) > 0:
                order = math.log(abs(a - b) / abs(b - c)) / math.log(2.)
                limit = c + (c - b) / (2. ** order - 1.)
                lines.append(f"| {label} | {a:.6g} | {b:.6g} | {c:.6g} | {order:.2f} | "
                             f"{limit:.6g} | {percent(a, limit)} | {percent(b, limit)} |")
            else:
                lines.append(f"| {label} | {a:.6g} | {b:.6g} | {c:.6g} | not monotone "
                             "| | | |")
    else:
        lines.append("Not all three runs have finished.")

    # The mesh: the change from each level to the next, per silicone, at
    # dt = 0.01 s, and at dt = 0.005 s where both levels ran.
    lines += ["", "## The mesh", "",
              "| silicone | dt s | from | to | change of f | change of ξ | "
              "change of the silicone volume |",
              "|---|---:|---|---|---:|---:|---:|"]
    for silicone in SILICONES:
        for dt in (0.01, 0.005):
            for coarse, fine in zip(LEVELS, LEVELS[1:]):
                a = by_name.get(f"{silicone}_{coarse}_dt{dt:g}")
                b = by_name.get(f"{silicone}_{fine}_dt{dt:g}")
                if a and b:
                    lines.append(
                        f"| {SILICONES[silicone]} | {dt:g} | {coarse} | {fine} | "
                        f"{percent(a['spectrum']['f'], b['spectrum']['f'])} → "
                        f"{b['spectrum']['f']:.5f} Hz | "
                        f"{percent(a['spectrum']['xi'], b['spectrum']['xi'])} | "
                        f"{percent(a['volume'], b['volume'])} |")
    lines += ["", "A change is that of the coarser level relative to the finer one.",
              "", "Against the finest mesh run with the same silicone and step:", "",
              "| silicone | dt s | mesh | against | error of f | error of ξ |",
              "|---|---:|---|---|---:|---:|"]
    for silicone in SILICONES:
        for dt in (0.01, 0.005):
            runs = [(level, by_name.get(f"{silicone}_{level}_dt{dt:g}"))
                    for level in LEVELS]
            runs = [(level, r) for level, r in runs if r]
            if len(runs) < 3:
                continue
            finest_level, finest = runs[-1]
            for level, r in runs[:-1]:
                lines.append(
                    f"| {SILICONES[silicone]} | {dt:g} | {level} | {finest_level} | "
                    f"{percent(r['spectrum']['f'], finest['spectrum']['f'])} | "
                    f"{percent(r['spectrum']['xi'], finest['spectrum']['xi'])} |")

    # The curved geometry against the flat one and against the finest
    # flat mesh.
    lines += ["", "## Curved geometry (Dragon Skin 20, dt = 0.01 s)", "",
              "| mesh | dofs | silicone volume mm³ | f Hz | ξ | against | same cells "
              "| change of f | change of ξ | error of f against extrafine "
              "| error of ξ against extrafine | wall s |",
              "|---|---:|---:|---:|---:|---|---|---:|---:|---:|---:|---:|"]
    finest = by_name.get("ds20_extrafine_dt0.01")
    for level, (flat_level, same) in CURVED.items():
        r = by_name.get(f"ds20_{level}_dt0.01")
        flat = by_name.get(f"ds20_{flat_level}_dt0.01")
        if not r:
            continue
        change = ((percent(r["spectrum"]["f"], flat["spectrum"]["f"]),
                   percent(r["spectrum"]["xi"], flat["spectrum"]["xi"]))
                  if flat else ("", ""))
        error = ((percent(r["spectrum"]["f"], finest["spectrum"]["f"]),
                  percent(r["spectrum"]["xi"], finest["spectrum"]["xi"]))
                 if finest else ("", ""))
        lines.append(
            f"| {level} | {r['dofs']} | {r['volume']:.0f} | {r['spectrum']['f']:.5f} | "
            f"{r['spectrum']['xi']:.5f} | {flat_level} | {'yes' if same else 'no'} | "
            f"{change[0]} | {change[1]} | {error[0]} | {error[1]} | "
            f"{r['wall_seconds']:.1f} |")
    lines += ["", "A change is that of the curved mesh relative to the flat one."]

    # Two meshes of one size, made with different surface meshers.
    lines += ["", "## Two meshes of one size (Dragon Skin 20, dt = 0.01 s)", "",
              "| mesh | dofs | silicone volume mm³ | f Hz | ξ | against "
              "| change of f | change of ξ |", "|---|---:|---:|---:|---:|---|---:|---:|"]
    r = by_name.get("ds20_extrafine-frontal_dt0.01")
    other = by_name.get("ds20_extrafine_dt0.01")
    if r and other:
        lines.append(
            f"| extrafine-frontal | {r['dofs']} | {r['volume']:.0f} | "
            f"{r['spectrum']['f']:.5f} | {r['spectrum']['xi']:.5f} | extrafine | "
            f"{percent(r['spectrum']['f'], other['spectrum']['f'])} | "
            f"{percent(r['spectrum']['xi'], other['spectrum']['xi'])} |")
    else:
        lines.append("| extrafine-frontal | | | not run | | extrafine | | |")

    # The Newton tolerance.
    lines += ["", "## The Newton tolerance (Dragon Skin 20, coarse mesh, dt = 0.01 s)", "",
              "| relative tolerance | f Hz | ξ | change of f | change of ξ | steps "
              "| cutbacks | Newton iterations | Newton/step | wall s |",
              "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    base = by_name.get("ds20_coarse_dt0.01")
    loose = by_name.get("ds20_coarse_dt0.01_tolerance1e-4")
    if base and loose:
        for tolerance, r in (("1e-6", base), ("1e-4", loose)):
            lines.append(
                f"| {tolerance} | {r['spectrum']['f']:.6f} | {r['spectrum']['xi']:.6f} | "
                f"{percent(r['spectrum']['f'], base['spectrum']['f'], 3)} | "
                f"{percent(r['spectrum']['xi'], base['spectrum']['xi'], 3)} | "
                f"{r['steps']} | {r['cutbacks']} | {r['newton_iterations']} | "
                f"{r['newton_iterations'] / r['steps']:.2f} | {r['wall_seconds']:.1f} |")
    else:
        lines.append("| | not run | | | | | | | | |")
    write_with_discussion_link(path, lines, "reference_discussion.md")


if __name__ == "__main__":
    study_main(__doc__, "doc/reference/run_reference.py", "output/reference",
               "doc/reference.md", CASE_NAMES, run_case, load_case, write_report)
