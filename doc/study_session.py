# SPDX-License-Identifier: LGPL-2.1-or-later

"""The command line and the session record shared by the study scripts
doc/locking/run_locking.py, doc/error_vs_runtime/run_error_vs_runtime.py and
doc/twisting_column/run_twisting_column.py: which cases to run, running
them one at a time (in the order the script lists them), and the list of runs (command, commit, machine, load,
date, duration) that the report names. A run of all cases starts the list
afresh; a run with --cases adds itself to it, and the report shows its cases
with those of the earlier runs. --report-only writes the report from the
output directory alone. And the `--set` entries, tetrahedral_defaults(),
with which every study that runs the bellows scenes restores them as it
knew them."""

import argparse
import json
import os
import sys
import time
from pathlib import Path

REPOSITORY = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPOSITORY / "doc" / "performance"))

# The bellows scenes as the studies knew them (commit 08e483a, the files
# they include followed): what has changed since, with its old value. The
# silicones' calibrated shear moduli (kPa) of parameters/silicones.prm,
# fitted with the linear tetrahedra.
_SILICONES = ["Silicone library/Silicone 1/Calibrated shear modulus=27.31",
              "Silicone library/Silicone 2/Calibrated shear modulus=169.9",
              "Silicone library/Silicone 3/Calibrated shear modulus=312.4"]
# The time step and the Newton solver (the program's defaults then) of
# every scene.
_SOLVER = ["Time integration/Time step=0.005",
           "Nonlinear solver/Tangent update=every step",
           "Nonlinear solver/Relative tolerance=1e-9",
           "Nonlinear solver/Absolute tolerance=1e-8",
           "Nonlinear solver/Acceleration depth=2"]
# The 3D scenes: linear tetrahedra on the gmsh meshes (the mesh file and the
# constants of the hold or push on the box-shaped block are the scene's).
_TETRAHEDRA = _SILICONES + _SOLVER + [
    "Geometry/Mesh source=file",
    "Finite element/Polynomial degree=1",
    "Finite element/Volumetric formulation=displacement",
    "Linear solver/Symmetric factorization=false"]
# The 1D and 2D scenes: the sections and the geometry that `calibrate
# reduced-models` computed from the linear tetrahedra are the scene's; the
# column's cells along the axis (mm) are those of every reduced scene.
_REDUCED = _SILICONES + _SOLVER
_AXIAL = "5.225," * 20 + "5,5"
TETRAHEDRAL_DEFAULTS = {
    "column_ds20_1d": _REDUCED + [
        "Material 1/Section=29.436",
        "Material 2/Section=29.436",
        "Loads and constraints/Function constants=force=958.4, section=29.436",
        f"Geometry/Generator arguments={_AXIAL}: -15.25: 99.25: true"],
    "column_ds20_1d_calibrated": _REDUCED + [
        "Material 1/Section=26.269",
        "Material 2/Section=26.269",
        "Loads and constraints/Function constants=force=958.4, section=26.269",
        f"Geometry/Generator arguments={_AXIAL}: -15.25: 99.25: true"],
    "column_ds30_1d": _REDUCED + [
        "Material 1/Section=25.592",
        "Material 2/Section=25.592",
        "Loads and constraints/Function constants=force=958.4, section=25.592",
        f"Geometry/Generator arguments={_AXIAL}: -15.25: 99.25: true"],
    "column_ds30_1d_calibrated": _REDUCED + [
        "Material 1/Section=23.139",
        "Material 2/Section=23.139",
        "Loads and constraints/Function constants=force=958.4, section=23.139",
        f"Geometry/Generator arguments={_AXIAL}: -15.25: 99.25: true"],
    "column_ef50_1d": _REDUCED + [
        "Material 1/Section=62.343",
        "Material 2/Section=62.343",
        "Loads and constraints/Function constants=force=958.4, section=62.343",
        f"Geometry/Generator arguments={_AXIAL}: -15.25: 99.25: true"],
    "column_ef50_1d_calibrated": _REDUCED + [
        "Material 1/Section=56.319",
        "Material 2/Section=56.319",
        "Loads and constraints/Function constants=force=958.4, section=56.319",
        f"Geometry/Generator arguments={_AXIAL}: -15.25: 99.25: true"],
    "inflation_ds20_1d": _REDUCED + [
        "Material 1/Section=29.436",
        "Material 2/Section=29.436",
        "Loads and constraints/Function constants=force=958.4, section=29.436",
        f"Geometry/Generator arguments={_AXIAL}: -15.25: 99.25: true",
        "Pneumatics/Equivalent area=328"],
    "inflation_ds20_2d": _REDUCED + [
        "Material 1/Section=0.90868",
        "Material 2/Section=0.90868",
        "Loads and constraints/Function constants=force=958.4, end_area=28.984",
        f"Geometry/Generator arguments={_AXIAL}; 7.97425,7.97425,7.97425,7.97425: "
        "-15.25, -15.9485: 99.25, 15.9485: true",
        "Pneumatics/Equivalent area=328"],
    "inflation_ds20_3d": _TETRAHEDRA + [
        "Geometry/Mesh file=../../meshes/bellows_quarter_coarse.msh",
        "Loads and constraints/Function constants=hold=1.1397, p_max=8"],
    "oscillation_ds20_3d": _TETRAHEDRA + [
        "Geometry/Mesh file=../../meshes/bellows_quarter_coarse.msh",
        "Loads and constraints/Function constants=hold=1.1397, p_amp=0.2, f_drive=3.53"],
    "planar_ds20_2d": _REDUCED + [
        "Material 1/Section=0.90868",
        "Material 2/Section=0.90868",
        "Loads and constraints/Function constants=force=958.4, end_area=28.984",
        f"Geometry/Generator arguments={_AXIAL}; 7.97425,7.97425,7.97425,7.97425: "
        "-15.25, -15.9485: 99.25, 15.9485: true"],
    "planar_ds20_2d_calibrated": _REDUCED + [
        "Material 1/Section=0.81016",
        "Material 2/Section=0.81016",
        "Loads and constraints/Function constants=force=958.4, end_area=25.834",
        f"Geometry/Generator arguments={_AXIAL}; 7.972,7.972,7.972,7.972: "
        "-15.25, -15.944: 99.25, 15.944: true"],
    "planar_ds20_3d": _TETRAHEDRA + [
        "Geometry/Mesh file=../../meshes/bellows_half_coarse.msh",
        "Loads and constraints/Function constants=push=1.1397"],
    "planar_ds20_3d_calibrated": _TETRAHEDRA + [
        "Geometry/Mesh file=../../meshes/bellows_half_coarse.msh",
        "Loads and constraints/Function constants=push=1.1397"],
    "planar_ds30_2d": _REDUCED + [
        "Material 1/Section=0.78924",
        "Material 2/Section=0.78924",
        "Loads and constraints/Function constants=force=958.4, end_area=25.164",
        f"Geometry/Generator arguments={_AXIAL}; 7.971,7.971,7.971,7.971: "
        "-15.25, -15.942: 99.25, 15.942: true"],
    "planar_ds30_2d_calibrated": _REDUCED + [
        "Material 1/Section=0.71361",
        "Material 2/Section=0.71361",
        "Loads and constraints/Function constants=force=958.4, end_area=22.738",
        f"Geometry/Generator arguments={_AXIAL}; 7.966,7.966,7.966,7.966: "
        "-15.25, -15.932: 99.25, 15.932: true"],
    "planar_ds30_3d": _TETRAHEDRA + [
        "Geometry/Mesh file=../../meshes/bellows_half_coarse.msh",
        "Loads and constraints/Function constants=push=1.1397"],
    "planar_ds30_3d_calibrated": _TETRAHEDRA + [
        "Geometry/Mesh file=../../meshes/bellows_half_coarse.msh",
        "Loads and constraints/Function constants=push=1.1397"],
    "planar_ef50_2d": _REDUCED + [
        "Material 1/Section=1.9402",
        "Material 2/Section=1.9402",
        "Loads and constraints/Function constants=force=958.4, end_area=61.921",
        f"Geometry/Generator arguments={_AXIAL}; 7.97875,7.97875,7.97875,7.97875: "
        "-15.25, -15.9575: 99.25, 15.9575: true"],
    "planar_ef50_2d_calibrated": _REDUCED + [
        "Material 1/Section=1.7503",
        "Material 2/Section=1.7503",
        "Loads and constraints/Function constants=force=958.4, end_area=55.859",
        f"Geometry/Generator arguments={_AXIAL}; 7.9785,7.9785,7.9785,7.9785: "
        "-15.25, -15.957: 99.25, 15.957: true"],
    "planar_ef50_3d": _TETRAHEDRA + [
        "Geometry/Mesh file=../../meshes/bellows_half_coarse.msh",
        "Loads and constraints/Function constants=push=1.1397"],
    "planar_ef50_3d_calibrated": _TETRAHEDRA + [
        "Geometry/Mesh file=../../meshes/bellows_half_coarse.msh",
        "Loads and constraints/Function constants=push=1.1397"],
    "spherical_ds20_3d": _TETRAHEDRA + [
        "Geometry/Mesh file=../../meshes/bellows_full_coarse.msh",
        "Loads and constraints/Function constants=push=1.1397, v_tip=200",
        "Initial conditions/Velocity=0; 0; v_tip * (x + 15.25) / 109.5",
        "Initial conditions/Velocity coordinates=reference"],
    "spherical_ds20_3d_calibrated": _TETRAHEDRA + [
        "Geometry/Mesh file=../../meshes/bellows_full_coarse.msh",
        "Loads and constraints/Function constants=push=1.1397, v_tip=200",
        "Initial conditions/Velocity=0; 0; v_tip * (x + 15.25) / 109.5",
        "Initial conditions/Velocity coordinates=reference"],
    "spherical_ds30_3d": _TETRAHEDRA + [
        "Geometry/Mesh file=../../meshes/bellows_full_coarse.msh",
        "Loads and constraints/Function constants=push=1.1397, v_tip=200",
        "Initial conditions/Velocity=0; 0; v_tip * (x + 15.25) / 109.5",
        "Initial conditions/Velocity coordinates=reference"],
    "spherical_ds30_3d_calibrated": _TETRAHEDRA + [
        "Geometry/Mesh file=../../meshes/bellows_full_coarse.msh",
        "Loads and constraints/Function constants=push=1.1397, v_tip=200",
        "Initial conditions/Velocity=0; 0; v_tip * (x + 15.25) / 109.5",
        "Initial conditions/Velocity coordinates=reference"],
    "spherical_ef50_3d": _TETRAHEDRA + [
        "Geometry/Mesh file=../../meshes/bellows_full_coarse.msh",
        "Loads and constraints/Function constants=push=1.1397, v_tip=200",
        "Initial conditions/Velocity=0; 0; v_tip * (x + 15.25) / 109.5",
        "Initial conditions/Velocity coordinates=reference"],
    "spherical_ef50_3d_calibrated": _TETRAHEDRA + [
        "Geometry/Mesh file=../../meshes/bellows_full_coarse.msh",
        "Loads and constraints/Function constants=push=1.1397, v_tip=200",
        "Initial conditions/Velocity=0; 0; v_tip * (x + 15.25) / 109.5",
        "Initial conditions/Velocity coordinates=reference"],
    "vacuum_release_ds20_3d": _TETRAHEDRA + [
        "Geometry/Mesh file=../../meshes/bellows_quarter_coarse.msh",
        "Loads and constraints/Function constants=hold=1.1397, vacuum=2.74"],
    "vacuum_release_ds30_3d": _TETRAHEDRA + [
        "Geometry/Mesh file=../../meshes/bellows_quarter_coarse.msh",
        "Loads and constraints/Function constants=hold=1.1397, vacuum=2.71"],
    "vacuum_release_ef50_3d": _TETRAHEDRA + [
        "Geometry/Mesh file=../../meshes/bellows_quarter_coarse.msh",
        "Loads and constraints/Function constants=hold=1.1397, vacuum=3.11"],
    "vertical_ds20_3d": _TETRAHEDRA + [
        "Geometry/Mesh file=../../meshes/bellows_quarter_coarse.msh",
        "Loads and constraints/Function constants=hold=1.1397"],
    "vertical_ds20_3d_calibrated": _TETRAHEDRA + [
        "Geometry/Mesh file=../../meshes/bellows_quarter_coarse.msh",
        "Loads and constraints/Function constants=hold=1.1397"],
    "vertical_ds30_3d": _TETRAHEDRA + [
        "Geometry/Mesh file=../../meshes/bellows_quarter_coarse.msh",
        "Loads and constraints/Function constants=hold=1.1397"],
    "vertical_ds30_3d_calibrated": _TETRAHEDRA + [
        "Geometry/Mesh file=../../meshes/bellows_quarter_coarse.msh",
        "Loads and constraints/Function constants=hold=1.1397"],
    "vertical_ef50_3d": _TETRAHEDRA + [
        "Geometry/Mesh file=../../meshes/bellows_quarter_coarse.msh",
        "Loads and constraints/Function constants=hold=1.1397"],
    "vertical_ef50_3d_calibrated": _TETRAHEDRA + [
        "Geometry/Mesh file=../../meshes/bellows_quarter_coarse.msh",
        "Loads and constraints/Function constants=hold=1.1397"],
}


def tetrahedral_defaults(scene):
    """The `--set` entries ("Subsection/Entry=value") that restore a bellows
    scene (a path or a name: parameters/bellows/vertical_ds20_3d.prm or
    vertical_ds20_3d) as the studies knew it. The studies were written for
    the scenes' linear tetrahedra; these entries restore that
    discretisation and the constants that went with it, so that the
    reports stay reproducible. A study puts them first, so that its case's
    own overrides win."""
    name = Path(scene).name.removesuffix(".prm")
    if name not in TETRAHEDRAL_DEFAULTS:
        raise KeyError(f"{scene}: not a scene of parameters/bellows")
    return list(TETRAHEDRAL_DEFAULTS[name])


def run_lines(session):
    """One line of the report per run of the script."""
    return [f"- `{run['command']}`: commit `{run['commit']}`, {run['date']}, "
            f"{run['total_seconds']:.0f} s; {run['machine']}; load average at the "
            f"start {run['load']}; the program ran with {run['threads']} thread(s), "
            "one case at a time" for run in session["runs"]]


def study_main(description, script, output, report, cases, run_case, load_case,
               write_report):
    """Parses the command line, runs the selected cases with
    run_case(build, output_root, name, timeout, threads), and writes the
    report with write_report(path, results, session) from the results
    load_case(output_root, name) finds (None for a case that has not run)."""
    # Here, not at the top: run_benchmarks imports this module.
    from run_benchmarks import commit, machine_description
    parser = argparse.ArgumentParser(description=description,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("build", help="the Release build directory (with soft-robot)")
    parser.add_argument("--cases", help="comma-separated case names (default: all)")
    parser.add_argument("--output", default=output)
    parser.add_argument("--report", default=report)
    parser.add_argument("--timeout", type=float, default=1800.,
                        help="seconds after which a case is killed (default 1800)")
    parser.add_argument("--threads", type=int, default=1,
                        help="threads of the program (DEAL_II_NUM_THREADS, default 1)")
    parser.add_argument("--report-only", action="store_true",
                        help="write the report from the output of earlier runs")
    arguments = parser.parse_args()

    build = Path(arguments.build).resolve()
    output_root = (REPOSITORY / arguments.output).resolve()
    output_root.mkdir(parents=True, exist_ok=True)
    selected = cases
    if arguments.cases:
        names = arguments.cases.split(",")
        unknown = set(names) - set(cases)
        if unknown:
            sys.exit(f"unknown case(s): {', '.join(sorted(unknown))}; "
                     f"known: {', '.join(cases)}")
        selected = [name for name in cases if name in names]
    session_path = output_root / "session.json"
    session = json.loads(session_path.read_text()) if session_path.exists() else {"runs": []}
    if not arguments.report_only:
        if not (build / "soft-robot").exists():
            sys.exit(f"{build / 'soft-robot'} does not exist: build in Release first")
        try:
            shown = str(build.relative_to(REPOSITORY))
        except ValueError:
            shown = "<Release build directory>"
        run = {"command": f"/usr/bin/python3 {script} {shown}"
                          + (f" --cases {arguments.cases}" if arguments.cases else ""),
               "commit": commit(), "machine": machine_description(),
               "load": ", ".join(f"{x:.2f}" for x in os.getloadavg()),
               "date": time.strftime("%Y-%m-%d"), "threads": arguments.threads,
               "timeout": arguments.timeout,
               "cases": arguments.cases.split(",") if arguments.cases else None}
        start = time.perf_counter()
        for name in selected:
            run_case(build, output_root, name, arguments.timeout, arguments.threads)
        run["total_seconds"] = time.perf_counter() - start
        # Read again: another session of the same study may have finished
        # meanwhile (two studies on the two cores).
        session = (json.loads(session_path.read_text()) if session_path.exists()
                   else {"runs": []})
        # An earlier run whose cases this one has all run again produces no
        # row of the report any more (a run without --cases ran them all).
        kept = [earlier for earlier in session["runs"]
                if arguments.cases
                and not set(earlier.get("cases") or cases) <= set(run["cases"])]
        session["runs"] = kept + [run]
        session_path.write_text(json.dumps(session, indent=1) + "\n")
    results = [r for r in (load_case(output_root, name) for name in cases) if r]
    write_report(REPOSITORY / arguments.report, results, session)
