#!/usr/bin/env python3
# SPDX-License-Identifier: LGPL-2.1-or-later
"""The speed benchmark: runs named cases with the Release build of
soft-robot, one at a time, and writes doc/performance.md.

    ./soft-robot.sh benchmark               (builds, then runs this script)
    python3 doc/performance/run_benchmarks.py build-release [--cases a,b]
                                              [--skip-calculix]
    ./soft-robot.sh benchmark --cases studies   (writes doc/performance_studies.md)

Without --cases the benchmark runs the group `default`: the three
experiments on the scenes' default discretisation (quadratic hexahedra),
its refinement series, the headline of the linear tetrahedra and the
reduced scenes, into doc/performance.md. The group `studies` holds the
studies of the discretisations the scenes used before (linear tetrahedra
with the sparse direct solvers and multigrid over a refinement series,
quadratic tetrahedra in the mean-dilatation formulation).

Every case is a scene of parameters/bellows/ with command-line overrides
(`--set`). The program writes `run_statistics.json` into its output
directory (cells, dofs, steps, Newton and linear iterations, the wall time
of each timed section, peak memory); this script adds the tip frequency
from `tip_spectrum.csv` and the wall time it measured itself, and prints
one table. Cases marked "window" run only the first part of the motion
(their cost per step is what they measure; a tip frequency needs the whole
record). The peer, CalculiX, runs the scenes' default (default_vertical, C3D20),
the headline of the linear tetrahedra (C3D4) and the quadratic tetrahedra
(p2md_headline_kept, C3D10) through calculix_peer.py in the same session,
each if its case ran.

Nothing here is a test: the numbers depend on the machine, and they are
reported, not checked.
"""

import argparse
import csv
import json
import math
import os
import platform
import re
import subprocess
import sys
import time
from pathlib import Path

REPOSITORY = Path(__file__).resolve().parents[2]
# The scenes' linear tetrahedra, restored for every case (doc/study_session.py).
sys.path.insert(0, str(REPOSITORY / "doc"))
from study_session import tetrahedral_defaults  # noqa: E402

HEADLINE = "parameters/bellows/vertical_ds20_3d.prm"
# (the repeats of a case run into the same directory)
QUIET = ["Output/Progress interval=0", "Output/Existing output=replace"]
# The timed sections of the assemblies: the residuals of the Newton
# iterations, the state a step ends in (with the viscosity of the next
# step), the matrices, and the tractions.
ASSEMBLY = ("Assemble residual", "Assemble state", "Assemble system", "Assemble tractions")

# The meshes of the refinement series: the quarter model's gmsh meshes with
# element sizes 10.5 (coarse), 5, 3, 2 and 1 mm. The ultrafine one is not
# committed; meshes/generate_meshes.sh writes it when a case needs it.
SERIES_LEVELS = ("coarse", "medium", "fine", "extrafine", "ultrafine")

# The solvers of the refinement series: the prefix of the case name, the
# overrides, what the description adds, the meshes they run on (KLU not
# on the ultrafine mesh: MUMPS factorizes it in 2.3 s, KLU would take
# several times that) and the MPI processes. Epetra's products and ML's
# multigrid run in one thread per process, so CG with multigrid uses the
# second core only with a second process.
SERIES_SOLVER = {"": (["Linear solver/Direct solver=KLU"], "", SERIES_LEVELS[:4], 1),
                 "mumps_": (["Linear solver/Direct solver=MUMPS"],
                            ", direct solver MUMPS instead of KLU", SERIES_LEVELS, 1),
                 "amg_": (["Linear solver/Solver=CG"],
                          ", CG with algebraic multigrid", SERIES_LEVELS, 1),
                 "amg_mpi2_": (["Linear solver/Solver=CG"],
                               ", CG with algebraic multigrid, 2 MPI processes",
                               SERIES_LEVELS, 2)}

# Quadratic tetrahedra in the mean-dilatation formulation; the modified
# Newton method that keeps its matrix across steps, stopping at 1e-6 of the
# force scale (Anderson acceleration over five iterates).
P2MD = ["Finite element/Polynomial degree=2",
        "Finite element/Volumetric formulation=mean dilatation"]
KEPT = ["Nonlinear solver/Tangent update=when needed",
        "Nonlinear solver/Relative tolerance=1e-6",
        "Nonlinear solver/Absolute tolerance=0",
        "Nonlinear solver/Acceleration depth=5"]

# The hexahedral mesh of the bellows with quadratic hexahedra and the linear
# dilatation (the README's overrides; hex-1-3-1-2, within 0.4 % of the
# reference of experiment 1, doc/reference_discussion.md), and the hold in
# kPa on the cylindrical block's face (958.4 mN on 880.69 mm^2). Also used
# by calculix_peer.py and doc/reference/run_hex_reference.py.
HEX_OVERRIDES = ["Geometry/Mesh source=bellows",
                 "Geometry/Mesh file=../../meshes/bellows.geo",
                 "Finite element/Polynomial degree=2",
                 "Finite element/Volumetric formulation=linear dilatation"]
HEX_HOLD_TRACTION = 1.08824
HEX = HEX_OVERRIDES + [f"Loads and constraints/Function constants=hold={HEX_HOLD_TRACTION:g}"]

# The hexahedral meshes, named hex-T-F-C-Q by their cells through the wall,
# along a flank, per chord of a fold and per quarter turn (Geometry/Bellows):
# their overrides of the scenes' hex-1-3-1-2 and what they are. Also used by
# doc/reference/run_hex_reference.py.
HEX_MESHES = {
    "hex-1-3-1-2": ([], "the scenes' default"),
    "hex-1-2-1-2": (["Geometry/Bellows/Cells along a flank=2"], "fewer cells on the flanks"),
    "hex-2-3-1-2": (["Geometry/Bellows/Cells through the wall=2"], "two cells through the wall"),
    "hex-2-6-1-2": (["Geometry/Bellows/Cells through the wall=2",
                     "Geometry/Bellows/Cells along a flank=6"], "and six on a flank"),
    "hex-2-6-2-2": (["Geometry/Bellows/Cells through the wall=2",
                     "Geometry/Bellows/Cells along a flank=6",
                     "Geometry/Bellows/Cells per chord=2"], "and two per chord"),
    "hex-2-6-1-4": (["Geometry/Bellows/Cells through the wall=2",
                     "Geometry/Bellows/Cells along a flank=6",
                     "Geometry/Bellows/Cells per quarter turn=4"], "and four per quarter turn"),
    "hex-1-3-1-2-refined": (["Geometry/Global refinements=1"],
                            "the default refined once"),
}

# The refinement series of the scenes' default discretisation (cases
# default_<mesh>_window): the default mesh, the reference of experiment 2
# and the reference mesh of experiment 1.
DEFAULT_SERIES = ("hex-1-3-1-2", "hex-2-6-2-2", "hex-1-3-1-2-refined")

# The refinement series of the quadratic discretisation (P2MD + KEPT): the
# quarter model's coarse, medium and fine meshes (11,931 to about 55,000
# unknowns; the extrafine one would need about 140,000), the first 0.25 s
# each, the static equilibrium included.
P2MD_SERIES_LEVELS = SERIES_LEVELS[:3]

# name, scene, overrides, MPI processes, description. The benchmark proper
# (`./soft-robot.sh benchmark`, or `--cases default`): the three experiments
# on the scenes' default discretisation, the first of them the headline, its
# refinement series, the headline of the linear tetrahedra the scenes used
# before (with its CalculiX peer; it must not get slower) and the reduced
# scenes.
DEFAULT_CASES = [
    # The scenes as they are (cases default_*: the tetrahedral defaults are
    # not restored): quadratic hexahedra with the linear dilatation, the
    # matrix kept across steps, Newton tolerance 1e-5 of the force scale
    # (the static start 1e-6).
    ("default_vertical", HEADLINE, [], 1,
     "exp. 1 DS20 quarter on the scenes' default (hex-1-3-1-2, quadratic "
     "hexahedra with linear dilatation), 5.25 s"),
    ("default_planar", "parameters/bellows/planar_ds20_3d.prm", [], 1,
     "exp. 2 DS20 half model on the scenes' default, 6 s"),
    ("default_spherical", "parameters/bellows/spherical_ds20_3d.prm", [], 1,
     "exp. 3 DS20 full model on the scenes' default, 6 s"),
] + [
    (f"default_{mesh}_window", HEADLINE,
     HEX_MESHES[mesh][0] + ["Time integration/End time=0.25",
                            "Output/Spectral analysis=false"], 1,
     f"exp. 1 DS20 quarter on the scenes' default with mesh {mesh} "
     f"({HEX_MESHES[mesh][1]}), first 0.25 s")
    for mesh in DEFAULT_SERIES
] + [
    ("headline", HEADLINE, [], 1,
     "exp. 1 DS20 quarter, coarse P1 (the scenes' linear tetrahedra before the "
     "hexahedral default), 5.25 s (the reference's 1,800 s case)"),
    ("column_1d", "parameters/bellows/column_ds20_1d.prm", [], 1,
     "reduced 1D column, 5.25 s"),
    ("planar_2d", "parameters/bellows/planar_ds20_2d.prm", [], 1,
     "reduced 2D strip, 6 s"),
]

# The studies of the discretisations and solvers the scenes used before the
# hexahedral default (these cases restore the linear tetrahedra, see
# run_case_once()) and of the quadratic tetrahedra in the mean-dilatation
# formulation: `--cases studies` runs them all, into
# doc/performance_studies.md.
STUDY_CASES = [
    ("headline_1_thread", HEADLINE, [], 1,
     "the linear headline with one thread (DEAL_II_NUM_THREADS=1)"),
    ("headline_mpi2", HEADLINE, [], 2,
     "the linear headline on 2 MPI processes"),
    ("headline_full_newton", HEADLINE,
     ["Nonlinear solver/Tangent update=every iteration"], 1,
     "the linear headline with a new tangent in every Newton iteration"),
    ("headline_no_output", HEADLINE,
     ["Output/Write VTU=false"], 1,
     "the linear headline without VTU output"),
    ("headline_reference_assembly", HEADLINE,
     ["Finite element/Direct addresses=false"], 1,
     "the linear headline with the reference global addition (AffineConstraints) "
     "instead of the direct-address assembler"),
    # The refinement series: the quarter model's gmsh meshes, the first
    # 0.5 s each, with the sparse direct solvers and with CG and algebraic
    # multigrid; the extrafine mesh with CG solving to 1e-8 instead of the
    # default 1e-2; and the coarse mesh refined once by deal.II (each
    # tetrahedron cut into 8).
] + [
    (f"{prefix}quarter_{level}_window", HEADLINE,
     [f"Geometry/Mesh file=../../meshes/bellows_quarter_{level}.msh",
      "Time integration/End time=0.5", "Output/Spectral analysis=false"]
     + SERIES_SOLVER[prefix][0], SERIES_SOLVER[prefix][3],
     f"{level} quarter mesh, first 0.5 s{SERIES_SOLVER[prefix][1]}")
    for prefix in SERIES_SOLVER for level in SERIES_SOLVER[prefix][2]
] + [
    ("amg_quarter_extrafine_tolerance_1e-8", HEADLINE,
     ["Geometry/Mesh file=../../meshes/bellows_quarter_extrafine.msh",
      "Time integration/End time=0.5", "Output/Spectral analysis=false",
      "Linear solver/Solver=CG", "Linear solver/Relative tolerance=1e-8"], 1,
     "extrafine quarter mesh, first 0.5 s, CG with algebraic multigrid "
     "solving to 1e-8 instead of 1e-2"),
    ("quarter_refined_window", HEADLINE,
     ["Geometry/Global refinements=1",
      "Time integration/End time=0.5", "Output/Spectral analysis=false"], 1,
     "coarse quarter mesh refined once (8x cells), first 0.5 s"),
    # What makes multigrid slow here: the same medium-mesh window with
    # kappa/mu = 2 and 10 instead of 100.
] + [
    (f"amg_quarter_medium_kappa{ratio}", HEADLINE,
     ["Geometry/Mesh file=../../meshes/bellows_quarter_medium.msh",
      "Time integration/End time=0.5", "Output/Spectral analysis=false",
      "Linear solver/Solver=CG",
      f"Silicone library/Silicone 2/Bulk-to-shear ratio={ratio}"], 1,
     f"medium quarter mesh, first 0.5 s, CG with algebraic multigrid, "
     f"kappa/mu = {ratio} instead of 100")
    for ratio in (2, 10)
] + [
    ("quarter_p2_window", HEADLINE,
     ["Finite element/Polynomial degree=2",
      "Time integration/End time=0.2", "Output/Spectral analysis=false"], 1,
     "coarse quarter mesh, quadratic elements, first 0.2 s"),
    # The discretisation that does not lock (quadratic tetrahedra, mean
    # dilatation) on experiment 1, with the default modified Newton method
    # and with the matrix kept across steps and a convergence test at 1e-6
    # of the force scale; the same solver settings on the headline.
    ("p2md_headline", HEADLINE, P2MD, 1,
     "exp. 1 DS20 quarter, coarse P2 mean dilatation, 5.25 s"),
    ("p2md_headline_kept", HEADLINE, P2MD + KEPT, 1,
     "the same, matrix kept across steps, Newton tolerance 1e-6"),
    ("p2md_headline_kept_1_thread", HEADLINE, P2MD + KEPT, 1,
     "the same with one thread (DEAL_II_NUM_THREADS=1)"),
] + [
    (f"p2md_quarter_{level}_window", HEADLINE,
     [f"Geometry/Mesh file=../../meshes/bellows_quarter_{level}.msh",
      "Time integration/End time=0.25", "Output/Spectral analysis=false"] + P2MD + KEPT, 1,
     f"{level} quarter mesh, quadratic elements with mean dilatation, matrix kept "
     f"across steps, first 0.25 s")
    for level in P2MD_SERIES_LEVELS
] + [
    ("headline_kept", HEADLINE, KEPT, 1,
     "the headline, matrix kept across steps, Newton tolerance 1e-6"),
    ("planar_3d", "parameters/bellows/planar_ds20_3d.prm", [], 1,
     "exp. 2 DS20 half model, 6 s (reference: 5,000 s)"),
    ("spherical_3d", "parameters/bellows/spherical_ds20_3d.prm", [], 1,
     "exp. 3 DS20 full model, 6 s (reference: 2,200 s)"),
]

CASES = DEFAULT_CASES + STUDY_CASES
GROUPS = {"default": [case[0] for case in DEFAULT_CASES],
          "studies": [case[0] for case in STUDY_CASES]}

REFERENCE_SECONDS = {"headline": 1800., "planar_3d": 5000., "spherical_3d": 2200.,
                     "default_vertical": 1800., "default_planar": 5000.,
                     "default_spherical": 2200.}


def tip_frequency(output):
    """The dominant peak of the direction with the largest magnitude."""
    path = output / "tip_spectrum.csv"
    if not path.exists():
        return None
    best = None
    with open(path) as file:
        for row in csv.DictReader(file):
            if row["peak"] != "dominant" or not row["f_peak_Hz"]:
                continue
            magnitude = float(row["magnitude"])
            if best is None or magnitude > best[0]:
                best = (magnitude, float(row["f_peak_Hz"]), row["direction"])
    return None if best is None else (best[1], best[2])


def output_seconds(s):
    """The output's time in the time loop, and that of the thread that
    writes the files (missing in the statistics of older runs' parallel
    cases)."""
    foreground = s["sections"].get("Output", 0.)
    thread = s["sections"].get("Output (writing thread)")
    return (f"{foreground:.2f}" if thread is None
            else f"{foreground:.2f} (+{thread:.2f} thread)")


# The headline case runs this many times; the report gives the run with the
# median process time and the range. The machine's speed varies by 10-20 %
# from run to run (it is a virtual machine), more than some of the
# differences the table shows, and by up to 40 % within minutes. The windows
# of the refinement series on the four smaller meshes (a few seconds to half
# a minute each) run as often, and the report gives the run with the median
# time per Newton iteration: the exponents of the series compare single
# runs minutes apart.
HEADLINE_REPEATS = 3
SERIES_REPEATS = 3
REPEATED_SERIES_LEVELS = SERIES_LEVELS[:4]


def repeats_of(name):
    """How often a case runs, and the statistic whose median run counts."""
    if name == "headline":
        return HEADLINE_REPEATS, "process"
    if any(name == f"{prefix}quarter_{level}_window"
           for prefix in SERIES_SOLVER for level in REPEATED_SERIES_LEVELS):
        return SERIES_REPEATS, "per_iteration"
    return 1, None


def final_tip(output):
    """The tip displacement (u_x, u_y, u_z) at the end of the record, as
    printed, to compare runs that should give the same motion."""
    path = output / "tip_trajectory.csv"
    if not path.exists():
        return None
    with open(path) as file:
        rows = list(csv.DictReader(line for line in file if not line.startswith("#")))
    return ", ".join(rows[-1][key] for key in ("u_x", "u_y", "u_z") if key in rows[-1])


def run_case(build, output_root, case, reuse=False):
    """Runs a case (some of them several times, see repeats_of()) and
    returns its statistics, those of the run with the median process time
    or time per Newton iteration."""
    name = case[0]
    count, criterion = repeats_of(name)
    if count == 1 or reuse:
        return run_case_once(build, output_root, case, reuse)
    runs = [run_case_once(build, output_root, case, False, f"run {k + 1}")
            for k in range(count)]
    key = ((lambda run: run["measured_seconds"]) if criterion == "process"
           else per_iteration)
    median = sorted(runs, key=key)[len(runs) // 2]
    median["repeats"] = {"process_seconds": [run["measured_seconds"] for run in runs],
                         "wall_seconds": [run["wall_seconds"] for run in runs],
                         "ms_per_newton_iteration": [per_iteration(run) for run in runs],
                         "newton_iterations": [run["newton_iterations"] for run in runs]}
    (output_root / name / "repeats.json").write_text(
        json.dumps(median["repeats"], indent=2) + "\n")
    # The runs share the output directory, which keeps the last run's
    # statistics; the median's are kept beside them for --report-only.
    (output_root / name / "median_statistics.json").write_text(
        json.dumps(median, indent=2) + "\n")
    return median


def ensure_mesh(overrides):
    """Writes the mesh a case names with meshes/generate_meshes.sh if it is
    not there (the ultrafine mesh is not committed)."""
    for entry in overrides:
        if entry.startswith("Geometry/Mesh file="):
            mesh = (REPOSITORY / "parameters/bellows" / entry.split("=", 1)[1]).resolve()
            if not mesh.exists():
                model, level = mesh.stem.split("_")[1:3]
                print(f"writing {mesh.name} with gmsh", flush=True)
                subprocess.run(["bash", str(REPOSITORY / "meshes/generate_meshes.sh"),
                                model, level], check=True)


def run_case_once(build, output_root, case, reuse=False, label=""):
    name, scene, overrides, processes, description = case
    output = output_root / name
    if reuse:
        median = output / "median_statistics.json"
        if median.exists():
            statistics = json.loads(median.read_text())
        else:
            statistics = json.loads((output / "run_statistics.json").read_text())
            statistics["measured_seconds"] = float(
                (output / "process_seconds").read_text())
        statistics["tip"] = tip_frequency(output)
        statistics["final_tip"] = final_tip(output)
        if (output / "repeats.json").exists():
            statistics["repeats"] = json.loads(
                (output / "repeats.json").read_text())
        return statistics
    ensure_mesh(overrides)
    command = [str(build / "soft-robot"), scene,
               "--set", f"Problem/Output directory={output}"]
    # The studies and the linear tetrahedra's headline run the scenes as the
    # studies knew them; the other cases of the benchmark run them as they are.
    restored = (tetrahedral_defaults(scene)
                if name == "headline" or name in GROUPS["studies"] else [])
    for entry in restored + QUIET + overrides:
        command += ["--set", entry]
    if processes > 1:
        command = ["mpirun", "-np", str(processes)] + command
    environment = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1",
                       OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1", OMP_NUM_THREADS="1")
    if name.endswith("_1_thread"):
        environment["DEAL_II_NUM_THREADS"] = "1"
    print(f"[{name}{' ' + label if label else ''}] {description}", flush=True)
    start = time.perf_counter()
    result = subprocess.run(command, cwd=REPOSITORY, env=environment,
                            capture_output=True, text=True)
    seconds = time.perf_counter() - start
    output.mkdir(parents=True, exist_ok=True)
    (output / "run.log").write_text(result.stdout + result.stderr)
    if result.returncode != 0:
        sys.exit(f"case {name} failed (exit {result.returncode}); "
                 f"see {output / 'run.log'}")
    statistics = json.loads((output / "run_statistics.json").read_text())
    statistics["measured_seconds"] = seconds
    (output / "process_seconds").write_text(f"{seconds:.4f}\n")
    statistics["tip"] = tip_frequency(output)
    statistics["final_tip"] = final_tip(output)
    print(f"    {statistics['wall_seconds']:.2f} s, "
          f"{statistics['dofs']} dofs, f = {statistics['tip']}", flush=True)
    return statistics


# The peers: our case, the mesh options of calculix_peer.py, the directory
# of its output (under the benchmark's output).
PEERS = (("default_vertical", ["--hex"], "calculix_peer_c3d20"),
         ("headline", ["--degree", "1"], "calculix_peer"),
         ("p2md_headline_kept", ["--degree", "2"], "calculix_peer_c3d10"))


def run_calculix(output_root, cases):
    """Runs the peers of the cases that ran; returns {our case: the peer's
    calculix_peer.json}."""
    peers = {}
    for case, options, directory in PEERS:
        if case not in cases:
            continue
        workdir = output_root / directory
        command = [sys.executable, str(REPOSITORY / "doc/performance/calculix_peer.py"),
                   "--workdir", str(workdir)] + options
        ours = output_root / case / "tip_trajectory.csv"
        if ours.exists():
            command += ["--compare", str(ours)]
        print(f"[calculix] the case {case} with CalculiX ({' '.join(options)}, 1 thread)",
              flush=True)
        result = subprocess.run(command, cwd=REPOSITORY, capture_output=True, text=True,
                                env=peer_environment(output_root / case))
        if result.returncode != 0:
            print(result.stdout[-2000:] + result.stderr[-2000:])
            continue
        peers[case] = json.loads((workdir / "calculix_peer.json").read_text())
    return peers


def peer_environment(our_output):
    """The environment of a CalculiX peer: CalculiX uses the same OpenBLAS,
    which may not know this processor either; it gets the kernels our run
    used (its run_statistics.json, solvers/blas_kernels.h), unless the user
    chose them with OPENBLAS_CORETYPE."""
    environment = dict(os.environ)
    statistics = our_output / "run_statistics.json"
    if "OPENBLAS_CORETYPE" not in environment and statistics.exists():
        kernels = json.loads(statistics.read_text()).get("blas_kernels", "")
        if kernels:
            environment["OPENBLAS_CORETYPE"] = kernels
    return environment


def blas_kernels(results):
    """The BLAS kernels of the runs, as their statistics name them."""
    names = sorted({s.get("blas_kernels", "") for _, _, s in results} - {""})
    return ", ".join(names) if names else "not OpenBLAS, or not recorded"


def read_calculix(output_root):
    """The peers' results of the last run (for --report-only)."""
    peers = {}
    for case, _, directory in PEERS:
        path = output_root / directory / "calculix_peer.json"
        if path.exists():
            peers[case] = json.loads(path.read_text())
    return peers


def machine_description():
    model = "unknown CPU"
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                model = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    return f"{os.cpu_count()} cores ({model}), {platform.system()} {platform.release()}"


def commit():
    """The commit the run starts from, with "+ changes" when tracked files
    differ from it (the run then used code that no commit holds)."""
    try:
        head = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=REPOSITORY,
                              capture_output=True, text=True).stdout.strip()
        changed = subprocess.run(["git", "diff", "--quiet", "HEAD"],
                                 cwd=REPOSITORY).returncode != 0
        return head + (" + changes" if changed else "")
    except OSError:
        return "unknown"


def per_iteration(s):
    """Milliseconds of assembly, solver set-up and solves per Newton
    iteration."""
    work = section(s, *ASSEMBLY, "Factorization", "Preconditioner setup",
                   "Linear solve")
    return 1000 * work / max(s["newton_iterations"], 1)


def section(statistics, *names):
    return sum(statistics["sections"].get(name, 0.) for name in names)


def cost_series_table(lines, series, title, what):
    """A refinement series' cost per time step: a table with the growth
    exponent from mesh to mesh, then the growth from the first mesh to the
    last, taken apart; nothing if the series has fewer than two meshes."""
    if len(series) < 2:
        return
    lines.append(f"## {title}\n")
    lines.append(what + " Per time step: "
                 "the time of the assemblies, the solver set-ups and the solves "
                 "divided by the steps, and the exponent p of t ~ N^p from the "
                 "mesh before; the Newton iterations and the factorizations per "
                 "step, the linear solves per Newton iteration (one back "
                 "substitution each with the direct solver), the direct solver "
                 "that `automatic` chose, and the peak memory per unknown.\n")
    lines.append("| mesh | dofs | ms per step | exponent | assembly ms | set-up ms | "
                 "solve ms | Newton/step | factorizations/step | solves per Newton "
                 "iteration | solver | peak MB | kB per dof |")
    lines.append("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|---:|---:|")

    def step_ms(r):
        return 1000 * section(r, *ASSEMBLY, "Factorization", "Preconditioner setup",
                              "Linear solve") / max(r["steps"], 1)

    previous = None
    for level, r in series:
        steps = max(r["steps"], 1)
        per_step = step_ms(r)
        exponent = ("–" if previous is None else
                    f"{math.log(per_step / previous[1]) / math.log(r['dofs'] / previous[0]):.2f}")
        lines.append(
            f"| {level} | {r['dofs']} | {per_step:.1f} | {exponent} "
            f"| {1000 * section(r, *ASSEMBLY) / steps:.1f} "
            f"| {1000 * section(r, 'Factorization', 'Preconditioner setup') / steps:.1f} "
            f"| {1000 * section(r, 'Linear solve') / steps:.1f} "
            f"| {r['newton_iterations'] / steps:.2f} "
            f"| {r['factorizations_or_amg_setups'] / steps:.2f} "
            f"| {r['linear_iterations'] / max(r['newton_iterations'], 1):.2f} "
            f"| {r.get('solver_in_use', '–')} | {r['peak_memory_mb']:.0f} "
            f"| {1024 * r['peak_memory_mb'] / r['dofs']:.1f} |")
        previous = (r["dofs"], per_step)
    (first_level, a), (last_level, b) = series[0], series[-1]
    log_n = math.log(b["dofs"] / a["dofs"])
    parts = []
    for label, names in (("assembly", ASSEMBLY),
                         ("factorizations", ("Factorization", "Preconditioner setup")),
                         ("solves", ("Linear solve",))):
        ta, tb = section(a, *names) / a["steps"], section(b, *names) / b["steps"]
        if ta > 0 and tb > 0:
            parts.append(f"{label} N^{math.log(tb / ta) / log_n:.2f}")
    lines.append(
        f"\nFrom the {first_level} to the {last_level} mesh the cost per step grows "
        f"like N^{math.log(step_ms(b) / step_ms(a)) / log_n:.2f}; by part: "
        + ", ".join(parts) + ". The peak memory beyond the first mesh's grows by "
        f"{1024 * (b['peak_memory_mb'] - a['peak_memory_mb']) / (b['dofs'] - a['dofs']):.1f} "
        "kB per added unknown (the per-unknown column above includes the libraries "
        "and the process's fixed memory).\n")


def write_report(path, results, calculix, run, title):
    lines = []
    lines.append("<!-- Written by doc/performance/run_benchmarks.py; "
                 "the discussion is in doc/performance_discussion.md. -->")
    lines.append(f"# {title}\n")
    lines.append(f"Command: `{run['command']}`  ")
    lines.append(f"Commit: `{run['commit']}`, Release build  ")
    lines.append(f"Machine: {run['machine']}  ")
    lines.append(f"OpenBLAS kernels: {blas_kernels(results)} "
                 "(`solvers/blas_kernels.h`; the CalculiX peers use the same)  ")
    lines.append(f"Date: {run['date']}\n")
    lines.append("All times are wall-clock seconds. \"wall s\" is the run as "
                 "the program measures it (mesh, set-up, initial static "
                 "equilibrium, time loop, output); \"process s\" is the whole "
                 "process as this script measures it, with the loading of the "
                 "libraries, MPI's start and the spectral analysis at the end. "
                 "Cases run one after the other on an otherwise idle machine. "
                 "Output is the output's time in the time loop (the cell data "
                 "and the hand-over of the fields); a thread of its own, one per "
                 "process, builds and writes the files meanwhile (its time in "
                 "parentheses, the largest over the processes). Newton/step "
                 "counts all iterations, those with an old tangent included. "
                 "Assembly is the residual, state (the forces and the next "
                 "step's viscosity at the end of a step) and matrix "
                 "assemblies; solver set-up is the sparse factorizations (or "
                 "multigrid set-ups); solve is the back substitutions (or CG "
                 "iterations). kB per dof is the "
                 "peak memory divided by the unknowns (the libraries and the "
                 "process's fixed memory included).\n")
    if any(name == "default_vertical" for name, _, _ in results):
        lines.append("The headline is `default_vertical`: experiment 1 on the scenes' "
                     "default discretisation. `headline` is the same experiment on "
                     "the linear tetrahedra the scenes used before, kept to show "
                     "that it does not get slower.\n")
    lines.append("| case | cells | dofs | steps | wall s | process s | ms/step "
                 "| Newton/step | factorizations | assembly s | solver set-up s "
                 "| solve s | output s | peak MB | kB per dof | tip f (Hz) |")
    lines.append("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|")
    for name, description, s in results:
        tip = "–" if not s["tip"] else f"{s['tip'][0]:.4f} ({s['tip'][1]})"
        lines.append(
            f"| {name} | {s['cells']} | {s['dofs']} | {s['steps']} "
            f"| {s['wall_seconds']:.2f} | {s['measured_seconds']:.2f} "
            f"| {1000 * s['wall_seconds'] / max(s['steps'], 1):.1f} "
            f"| {s['newton_iterations'] / max(s['steps'], 1):.2f} "
            f"| {s['factorizations_or_amg_setups']} "
            f"| {section(s, *ASSEMBLY):.2f} "
            f"| {section(s, 'Factorization', 'Preconditioner setup'):.2f} "
            f"| {section(s, 'Linear solve'):.2f} | {output_seconds(s)} "
            f"| {s['peak_memory_mb']:.0f} | {1024 * s['peak_memory_mb'] / s['dofs']:.1f} "
            f"| {tip} |")
    lines.append("")
    for name, description, s in results:
        lines.append(f"- **{name}**: {description}; {s['mpi_processes']} process(es) "
                     f"with {s.get('threads_per_process', 1)} thread(s) each, "
                     f"linear solver {s['linear_solver']}, tangent update "
                     f"'{s['tangent_update']}'.")
    lines.append("")

    by_name = {name: s for name, _, s in results}
    if "repeats" in by_name.get("headline", {}):
        repeats = by_name["headline"]["repeats"]
        lines.append(
            f"The headline case ran {len(repeats['process_seconds'])} times; "
            f"the table shows the run with the median process time. Process "
            f"times: {', '.join(f'{t:.2f}' for t in repeats['process_seconds'])} s; "
            f"the program's wall times: "
            f"{', '.join(f'{t:.2f}' for t in repeats['wall_seconds'])} s.\n")
    peers = [(case, calculix[case]) for case, _, _ in PEERS
             if calculix and case in calculix and case in by_name]
    references = [name for name in REFERENCE_SECONDS if name in by_name]
    if references or peers:
        lines.append("## Against the reference and the peer\n")
        lines.append("Our times here are those of the whole process (\"process s\" "
                     "above: start-up and the spectral analysis included), as "
                     "CalculiX's are.\n")
    if references:
        lines.append("| case | this program s | reference s | speed-up |")
        lines.append("|---|---:|---:|---:|")
        for name in references:
            ours = by_name[name]["measured_seconds"]
            reference = REFERENCE_SECONDS[name]
            lines.append(f"| {name} | {ours:.2f} | {reference:.0f} (4 threads) "
                         f"| {reference / ours:.0f}x |")
        lines.append("")
    if peers:
        version = peers[0][1]["ccx_version"]
        lines.append(
            f"CalculiX {version} on the same cases (same mesh and element degree, "
            f"material, damping coefficient, time step, HHT alpha and duration; one "
            f"thread). Tip frequency: the vertical FFT peak of the tip's mean "
            f"displacement, by calculix_peer.py's estimator for both programs.\n")
        lines.append("| case | elements | CalculiX s | this program s | ratio | CalculiX "
                     "Newton iterations | ours | CalculiX f (Hz) | our f (Hz) | "
                     "difference | CalculiX peak MiB |")
        lines.append("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
        for case, peer in peers:
            ours = by_name[case]
            our_f = peer.get("ours", {}).get("f_peak_Hz")
            lines.append(
                f"| {case} | {peer['element_type']} | {peer['wall_seconds']:.2f} | "
                f"{ours['measured_seconds']:.2f} | "
                f"{peer['wall_seconds'] / ours['measured_seconds']:.2f} | "
                f"{peer['dynamic_iterations']} | {ours['newton_iterations']} | "
                f"{peer['f_peak_Hz']:.4f} | "
                + (f"{our_f:.4f} | {100 * (peer['f_peak_Hz'] / our_f - 1):+.2f} % | "
                   if our_f else "– | – | ")
                + f"{peer['peak_memory_MiB']:.0f} |")
        lines.append("")
        lines.append("Differences of the peers' models (from calculix_peer.py):\n")
        caveats = []
        for _, peer in peers:
            caveats += [c for c in peer["caveats"] if c not in caveats]
        for caveat in caveats:
            lines.append(f"- {caveat}")
        lines.append("")

    p2md_series = [(level, by_name[f"p2md_quarter_{level}_window"])
                   for level in P2MD_SERIES_LEVELS if f"p2md_quarter_{level}_window" in by_name]
    cost_series_table(
        lines, p2md_series, "Cost per time step over the quadratic refinement series",
        "Quadratic tetrahedra in the mean-dilatation formulation, the matrix kept "
        "across steps (the settings of `p2md_headline_kept`), on the quarter model's "
        "coarse, medium and fine gmsh meshes, the first 0.25 s each with the static "
        "equilibrium.")
    default_series = [(mesh, by_name[f"default_{mesh}_window"])
                      for mesh in DEFAULT_SERIES if f"default_{mesh}_window" in by_name]
    cost_series_table(
        lines, default_series,
        "Cost per time step over the refinement series of the scenes' default",
        "The scenes' default discretisation (quadratic hexahedra with the linear "
        "dilatation, the matrix kept across steps; experiment 1 of Dragon Skin 20 as "
        "`default_vertical`) on three hexahedral meshes of the quarter model "
        "(`doc/reference_hex.md` names them), the first 0.25 s each with the static "
        "equilibrium.")

    def per_cg_iteration(s):
        """Nanoseconds per unknown per CG iteration (the solves' time)."""
        return 1e9 * section(s, "Linear solve") / max(s["linear_iterations"], 1) / s["dofs"]

    def hierarchy_nonzeros(s):
        """The nonzeros of all the multigrid levels' matrices, or None for
        a run without them in its statistics."""
        if not s.get("matrix_nonzeros") or not s.get("multigrid_operator_complexity"):
            return None
        return s["matrix_nonzeros"] * s["multigrid_operator_complexity"]

    levels = [level for level in SERIES_LEVELS
              if any(f"{prefix}quarter_{level}_window" in by_name
                     for prefix in SERIES_SOLVER)]
    if len(levels) >= 2:
        lines.append("## Cost per Newton iteration over the refinement series\n")
        lines.append("The quarter model's gmsh meshes (element sizes 10.5, 5, 3, "
                     "2 and 1 mm), the first 0.5 s each (the static equilibrium "
                     "included). Per Newton iteration: the time of the "
                     "assemblies, the solver set-ups and the solves divided by "
                     "the number of Newton iterations, and the exponent p of "
                     "t ~ N^p from the mesh before; with the sparse "
                     "direct solvers KLU and MUMPS and with CG preconditioned by ML's "
                     "algebraic multigrid (rigid-body modes as its near null "
                     "space, 2 Chebyshev sweeps, relative tolerance 1e-2: the "
                     "forcing term of an inexact Newton method, see "
                     "`Linear solver/Relative tolerance`), on one process "
                     "(two threads in the assemblies, one for the solver) and, "
                     "for CG with multigrid, also on two MPI processes (one "
                     "thread each: both cores in the solver too). For CG on "
                     "one process also the "
                     "iterations per solve, the solves' time per unknown "
                     "and CG iteration, the matrix's nonzeros per unknown, "
                     "ML's operator complexity (the nonzeros of all the "
                     "hierarchy's matrices over those of the finest) and the "
                     "solves' time per nonzero of the hierarchy and CG "
                     "iteration, which would stay constant if the "
                     "machine's memory were equally fast for all sizes.\n")
        lines.append("| mesh | dofs | KLU: ms per Newton iteration | exponent "
                     "| MUMPS: ms per Newton iteration | exponent "
                     "| AMG: ms per Newton iteration | exponent "
                     "| AMG, 2 processes: ms per Newton iteration | exponent "
                     "| CG iterations per solve | ns per dof and CG iteration "
                     "| nonzeros per dof | operator complexity "
                     "| ns per hierarchy nonzero and CG iteration |")
        lines.append("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
        previous = None
        first = {}
        last = {}
        for level in levels:
            runs = [by_name.get(f"{prefix}quarter_{level}_window")
                    for prefix in SERIES_SOLVER]
            dofs = next(r for r in runs if r)["dofs"]
            now = [dofs] + [per_iteration(r) if r else None for r in runs]
            cells = []
            for k in (1, 2, 3, 4):
                exponent = "–"
                if previous and now[k] and previous[k]:
                    p = math.log(now[k] / previous[k]) / math.log(dofs / previous[0])
                    exponent = f"{p:.2f}"
                if now[k]:
                    first.setdefault(k, (dofs, now[k], level))
                    last[k] = (dofs, now[k], level)
                cells.append("– | –" if now[k] is None else
                             f"{now[k]:.{2 if k < 3 else 1}f} | {exponent}")
            amg = runs[2]
            iterations = ("– | –" if not amg else
                          f"{amg['linear_iterations'] / max(amg['newton_iterations'], 1):.0f} "
                          f"| {per_cg_iteration(amg):.0f}")
            if amg and hierarchy_nonzeros(amg):
                iterations += (f" | {amg['matrix_nonzeros'] / amg['dofs']:.1f} "
                               f"| {amg['multigrid_operator_complexity']:.2f} "
                               f"| {per_cg_iteration(amg) * amg['dofs'] / hierarchy_nonzeros(amg):.2f}")
            else:
                iterations += " | – | – | –"
            lines.append(f"| {level} | {dofs} | {' | '.join(cells)} | {iterations} |")
            previous = now
        if "quarter_refined_window" in by_name:
            refined = by_name["quarter_refined_window"]
            lines.append(f"| coarse refined once | {refined['dofs']} "
                         f"| {per_iteration(refined):.2f} | | | | | | | | | | | | |")
        lines.append("")
        names = {1: "KLU", 2: "MUMPS", 3: "CG+AMG", 4: "CG+AMG on 2 processes"}
        overall = [f"{names[k]} N^{math.log(last[k][1] / first[k][1]) / math.log(last[k][0] / first[k][0]):.2f} "
                   f"({first[k][2]} to {last[k][2]} mesh)"
                   for k in sorted(last) if last[k][0] > first[k][0]]
        lines.append("Over the whole series: " + ", ".join(overall) + ".\n")
        # The CG solves' exponent taken apart: their time per Newton
        # iteration is (CG iterations per Newton iteration) x (nonzeros of
        # the hierarchy) x (time per hierarchy nonzero and CG iteration), so
        # the exponent is 1 (the unknowns) plus one term per factor, which
        # is positive where the factor grows.
        amg_runs = [(level, by_name.get(f"amg_quarter_{level}_window")) for level in levels]
        amg_runs = [(level, run) for level, run in amg_runs
                    if run and hierarchy_nonzeros(run)]
        if len(amg_runs) >= 2 and amg_runs[-1][1]["dofs"] > amg_runs[0][1]["dofs"]:
            (first_level, a), (last_level, b) = amg_runs[0], amg_runs[-1]
            log_n = math.log(b["dofs"] / a["dofs"])

            def term(value):
                return math.log(value(b) / value(a)) / log_n

            def solves(s):
                return section(s, "Linear solve") / max(s["newton_iterations"], 1)

            def iterations(s):
                return s["linear_iterations"] / max(s["newton_iterations"], 1)

            def nonzeros_per_dof(s):
                return hierarchy_nonzeros(s) / s["dofs"]

            def per_nonzero(s):
                return per_cg_iteration(s) * s["dofs"] / hierarchy_nonzeros(s)

            lines.append(
                f"The CG solves on one process, from the {first_level} "
                f"to the {last_level} mesh, taken apart: their time per Newton "
                f"iteration grows like N^{term(solves):.2f} "
                f"({1000 * solves(a):.2f} to {1000 * solves(b):.1f} ms). "
                f"Of the exponent's part above 1, "
                f"{term(nonzeros_per_dof):+.3f} are the hierarchy's nonzeros per unknown "
                f"({nonzeros_per_dof(a):.1f} to {nonzeros_per_dof(b):.1f}: the matrix's "
                f"{a['matrix_nonzeros'] / a['dofs']:.1f} to {b['matrix_nonzeros'] / b['dofs']:.1f} "
                f"times the operator complexity), {term(per_nonzero):+.3f} the time per "
                f"hierarchy nonzero and CG iteration ({per_nonzero(a):.2f} to "
                f"{per_nonzero(b):.2f} ns: the machine's memory) and "
                f"{term(iterations):+.3f} the CG iterations per solve "
                f"({iterations(a):.1f} to {iterations(b):.1f}).\n")
        spread = []
        same_counts = True
        for level in levels:
            ranges = []
            for prefix in SERIES_SOLVER:
                run = by_name.get(f"{prefix}quarter_{level}_window")
                times = (run or {}).get("repeats", {}).get("ms_per_newton_iteration")
                counts = (run or {}).get("repeats", {}).get("newton_iterations", [])
                same_counts = same_counts and len(set(counts)) <= 1
                ranges.append(f"{min(times):.2f}–{max(times):.2f}" if times else "–")
            if any(r != "–" for r in ranges):
                spread.append(f"| {level} | " + " | ".join(ranges) + " |")
        if spread:
            lines.append(f"The windows on the {', '.join(REPEATED_SERIES_LEVELS[:-1])} "
                         f"and {REPEATED_SERIES_LEVELS[-1]} meshes ran {SERIES_REPEATS} "
                         "times each; the table above gives the run with the median "
                         "time per Newton iteration, this one the smallest and the "
                         "largest of the runs (ms per Newton iteration; "
                         + ("the same Newton iteration counts in the runs of a case"
                            if same_counts else
                            "the Newton iteration counts differ between runs of a "
                            "case, see repeats.json")
                         + "):\n")
            lines.append("| mesh | KLU | MUMPS | AMG | AMG, 2 processes |")
            lines.append("|---|---:|---:|---:|---:|")
            lines.extend(spread)
            lines.append("")
        tight = by_name.get("amg_quarter_extrafine_tolerance_1e-8")
        loose = by_name.get("amg_quarter_extrafine_window")
        if tight and loose:
            lines.append("| extrafine mesh, CG+AMG | Newton iterations | CG iterations per solve "
                         "| ms per Newton iteration | solves s | tip displacement at 0.5 s (mm) |")
            lines.append("|---|---:|---:|---:|---:|---|")
            for label, s in (("relative tolerance 1e-2 (default)", loose),
                             ("relative tolerance 1e-8", tight)):
                lines.append(f"| {label} | {s['newton_iterations']} "
                             f"| {s['linear_iterations'] / max(s['newton_iterations'], 1):.0f} "
                             f"| {per_iteration(s):.1f} | {section(s, 'Linear solve'):.2f} "
                             f"| {s['final_tip']} |")
            lines.append("")
    ratios = [(ratio, by_name[name]) for ratio, name in
              ((2, "amg_quarter_medium_kappa2"), (10, "amg_quarter_medium_kappa10"),
               (100, "amg_quarter_medium_window")) if name in by_name]
    if len(ratios) >= 2:
        lines.append("CG iterations per solve with algebraic multigrid on the "
                     "medium mesh against the bulk-to-shear ratio of the "
                     "silicone (the scenes use 100):\n")
        lines.append("| kappa/mu | CG iterations per solve | ms per Newton iteration |")
        lines.append("|---:|---:|---:|")
        for ratio, s in ratios:
            lines.append(f"| {ratio} | "
                         f"{s['linear_iterations'] / max(s['newton_iterations'], 1):.0f} "
                         f"| {per_iteration(s):.1f} |")
        lines.append("")

    write_with_discussion_link(path, lines, "performance_discussion.md")


def write_with_discussion_link(path, lines, discussion_name):
    """Writes the generated lines, with a link below the title to the
    hand-written discussion of the results, doc/<discussion_name> (which
    the report links to and does not copy)."""
    link = (f"The discussion of these results is in "
            f"[{discussion_name}]({discussion_name}).")
    text = re.sub(r"^(# .*)\n+", lambda m: f"{m.group(1)}\n\n{link}\n\n",
                  "\n".join(lines), count=1, flags=re.M)
    path.write_text(text + "\n")
    print(f"wrote {path}")


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("build", help="the Release build directory")
    parser.add_argument("--cases",
                        help="comma-separated case names or groups: 'default' (the "
                        "benchmark, what runs without --cases) or 'studies' (the "
                        "earlier discretisations' studies)")
    parser.add_argument("--output", default="output/benchmarks")
    parser.add_argument("--report",
                        help="the report to write (default: doc/performance.md, or "
                        "doc/performance_studies.md when only studies run)")
    parser.add_argument("--skip-calculix", action="store_true")
    parser.add_argument("--report-only", action="store_true",
                        help="write the report from the output of the last run")
    arguments = parser.parse_args()

    build = Path(arguments.build).resolve()
    if not (build / "soft-robot").exists():
        sys.exit(f"{build / 'soft-robot'} does not exist: build in Release first")
    names = []
    for name in (arguments.cases or "default").split(","):
        names += GROUPS.get(name, [name])
    unknown = set(names) - {case[0] for case in CASES}
    if unknown:
        sys.exit(f"unknown case(s): {', '.join(sorted(unknown))}; known: the groups "
                 f"{', '.join(GROUPS)} and {', '.join(case[0] for case in CASES)}")
    selected = [case for case in CASES if case[0] in names]
    studies_only = all(case[0] in GROUPS["studies"] for case in selected)
    report = arguments.report or ("doc/performance_studies.md" if studies_only
                                  else "doc/performance.md")
    output_root = (REPOSITORY / arguments.output).resolve()
    output_root.mkdir(parents=True, exist_ok=True)

    # What the report says about the run: kept with the results, so that a
    # report written later (--report-only) names the commit that ran.
    run_file = output_root / "benchmark_run.json"
    if arguments.report_only:
        run = json.loads(run_file.read_text())
    else:
        run = {"command": "./soft-robot.sh benchmark" + (
                   f" (cases: {arguments.cases})" if arguments.cases else ""),
               "commit": commit(), "machine": machine_description(),
               "date": time.strftime("%Y-%m-%d")}
        run_file.write_text(json.dumps(run, indent=2) + "\n")
    results = [(case[0], case[4], run_case(build, output_root, case, arguments.report_only))
               for case in selected]
    if arguments.report_only:
        calculix = read_calculix(output_root)
    else:
        calculix = (None if arguments.skip_calculix
                    else run_calculix(output_root, [case[0] for case in selected]))
    write_report(REPOSITORY / report, results, calculix, run,
                 "Performance: studies of the earlier discretisations" if studies_only
                 else "Performance")


if __name__ == "__main__":
    main()
