#!/usr/bin/env bash
# SPDX-License-Identifier: LGPL-2.1-or-later
# The two commands of the README, for a fresh Debian 12 machine (as root):
#
#   ./soft-robot.sh demo       install what is missing, build in Release, run
#                              the vertical oscillation of the Dragon Skin 20
#                              actuator in 3D and its reduced 1D and 2D scenes
#   ./soft-robot.sh test       install what is missing, build in Debug (deal.II's
#                              internal checks on), render the annotated source
#                              (build-debug/doc/html/index.html; fails on any
#                              doxygen warning), run the whole test suite
#   ./soft-robot.sh validate   build in Release, run all thirty bellows scenes
#                              (SOFT_ROBOT_JOBS at a time, default 2) and
#                              write doc/validation.md; with --resume, keep
#                              the scenes already run from the same inputs
#   ./soft-robot.sh benchmark  build in Release, run the speed benchmark (and
#                              CalculiX as the peer) one case at a time and
#                              write doc/performance.md; with --cases studies,
#                              the earlier discretisations' studies into
#                              doc/performance_studies.md
#   ./soft-robot.sh stability  build in Release, run the study of stiff and
#                              extreme cases and write doc/stability.md
#   ./soft-robot.sh locking    build in Release, run the locking study (linear
#                              and quadratic elements, kappa/mu up to 1e4) and
#                              write doc/locking.md
#   ./soft-robot.sh error-vs-runtime
#                              build in Release, run the three experiments on
#                              the default over time steps, on finer meshes
#                              (the references), on tetrahedra and as the
#                              reduced scenes, and write doc/error-vs-runtime.md
#   ./soft-robot.sh twisting-column
#                              build in Release, run the twisting-column
#                              benchmark and write doc/twisting_column.md
#   ./soft-robot.sh pneumatics build in Release, run experiment 1 released
#                              from three vacuum levels and from the hold,
#                              the inflation (static curve and ramp, hold,
#                              vent) and a sinusoidal pressure drive, and
#                              write doc/pneumatics.md
#   ./soft-robot.sh reference  build in Release, run experiment 1 with quadratic
#                              tetrahedra (mean dilatation) over time steps,
#                              meshes and silicones and write doc/reference.md
#   ./soft-robot.sh swing-reference
#                              the same for experiments 2 and 3 (the planar and
#                              the spherical pendulum); writes
#                              doc/reference_swing.md
#   ./soft-robot.sh hex-reference
#                              experiment 1 on the hexahedral mesh (quadratic
#                              hexahedra, linear dilatation) refined in each
#                              direction; writes doc/reference_hex.md
#   ./soft-robot.sh swing-hex-reference
#                              experiments 2 and 3 on the hexahedral mesh: the
#                              scenes' default against finer meshes, the
#                              three silicones; writes doc/reference_swing_hex.md
#   ./soft-robot.sh protocol   build in Release, run the calibrated Dragon Skin
#                              20 pendulums under other pushes and out-of-plane
#                              starts and write doc/protocol.md
#
# Build directories: build-release/ and build-debug/ beside this script.
set -euo pipefail
cd "$(dirname "$0")"

# OpenBLAS in place of Debian's reference BLAS: MUMPS's dense frontal
# matrices run on it (see Linear solver/Direct solver); KLU does not use BLAS.
packages=(cmake make g++ libdeal.ii-dev libfftw3-dev liblapack-dev libopenblas0-serial
          libmumps-dev libgtest-dev nlohmann-json3-dev)

install_missing_packages() {
  local missing=()
  for package in "${packages[@]}"; do
    dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed" \
      || missing+=("$package")
  done
  if [ ${#missing[@]} -gt 0 ]; then
    echo "Installing: ${missing[*]}"
    export DEBIAN_FRONTEND=noninteractive
    apt-get update -q
    apt-get install -y -q --no-install-recommends "${missing[@]}"
  fi
}

build() {
  local type=$1 directory=$2
  shift 2
  cmake -S . -B "$directory" -DCMAKE_BUILD_TYPE="$type" "$@"
  cmake --build "$directory" -j "$(nproc)"
}

case "${1:-}" in
  demo)
    install_missing_packages
    build Release build-release -DSOFT_ROBOT_BUILD_TESTS=OFF
    # The default scene is the 3D actuator; the 1D and 2D models follow.
    for scene in vertical_ds20_3d column_ds20_1d planar_ds20_2d; do
      build-release/soft-robot parameters/bellows/$scene.prm \
        --set 'Output/Existing output=replace'
      echo "Open output/$scene/solution.pvd in ParaView."
    done
    ;;
  test)
    # python3 for the check of doc/results.md, clang-format 14 for that of
    # the sources' format; doxygen, LaTeX and
    # Ghostscript for the annotated source (target doc); h5py for the
    # command-line tests that read the HDF5 output back, numpy and
    # matplotlib for those of the plot script.
    packages+=(python3 clang-format-14 doxygen texlive-latex-extra ghostscript python3-h5py
               python3-numpy python3-matplotlib)
    install_missing_packages
    build Debug build-debug -DSOFT_ROBOT_BUILD_TESTS=ON
    cmake --build build-debug --target doc
    cd build-debug
    ctest --output-on-failure -j "$(nproc)"
    ;;
  benchmark)
    packages+=(python3-numpy calculix-ccx openmpi-bin gmsh)
    install_missing_packages
    build Release build-release -DSOFT_ROBOT_BUILD_TESTS=OFF
    /usr/bin/python3 doc/performance/run_benchmarks.py build-release "${@:2}"
    ;;
  locking)
    packages+=(python3-numpy python3-matplotlib)
    install_missing_packages
    build Release build-release -DSOFT_ROBOT_BUILD_TESTS=OFF
    /usr/bin/python3 doc/locking/run_locking.py build-release "${@:2}"
    ;;
  stability|error-vs-runtime|twisting-column|damping|pneumatics|reference|protocol)
    packages+=(python3-numpy python3-matplotlib)
    install_missing_packages
    build Release build-release -DSOFT_ROBOT_BUILD_TESTS=OFF
    script=${1//-/_}
    /usr/bin/python3 "doc/$script/run_$script.py" build-release "${@:2}"
    ;;
  swing-reference|hex-reference|swing-hex-reference)
    # gmsh for the medium tetrahedral mesh with the cylindrical block
    packages+=(python3-numpy python3-matplotlib gmsh)
    install_missing_packages
    build Release build-release -DSOFT_ROBOT_BUILD_TESTS=OFF
    script=${1%-reference}
    /usr/bin/python3 "doc/reference/run_${script//-/_}_reference.py" build-release "${@:2}"
    ;;
  validate)
    packages+=(python3-matplotlib python3-numpy)
    install_missing_packages
    build Release build-release -DSOFT_ROBOT_BUILD_TESTS=OFF
    case ${2:-} in
      '') export SOFT_ROBOT_RESUME=0 ;;
      --resume) export SOFT_ROBOT_RESUME=1 ;;
      *) echo "validate: unknown option '$2' (allowed: --resume)" >&2; exit 2 ;;
    esac
    # What a scene's result depends on: the committed trees of the
    # program's sources, parameters and meshes. Uncommitted changes there
    # give "modified", which no later run counts as the same inputs.
    inputs=(source include parameters meshes CMakeLists.txt)
    if [ -n "$(git status --porcelain -- "${inputs[@]}" 2>/dev/null)" ]; then
      SOFT_ROBOT_INPUTS=modified
    else
      SOFT_ROBOT_INPUTS=$(for path in "${inputs[@]}"; do git rev-parse "HEAD:$path"; done |
                          sha1sum | cut -c1-12)
    fi
    SOFT_ROBOT_COMMIT=$(git rev-parse --short HEAD 2>/dev/null || echo unknown)
    SOFT_ROBOT_SET=$(date +%s)
    export SOFT_ROBOT_INPUTS SOFT_ROBOT_COMMIT SOFT_ROBOT_SET
    # One scene: its output, the program's log, the wall time and what it
    # ran from (run_info: commit, inputs, threads, jobs, the invocation of
    # validate) in output/<scene>/. A failed scene stops the report. With
    # --resume, a scene whose run_info names the same inputs is kept.
    run_scene() {
      local scene=$1 name
      name=$(basename "$scene" .prm)
      if [ "$SOFT_ROBOT_RESUME" = 1 ] && [ "$SOFT_ROBOT_INPUTS" != modified ] &&
         [ -f "output/$name/wall_seconds" ] &&
         grep -qx "inputs $SOFT_ROBOT_INPUTS" "output/$name/run_info" 2>/dev/null; then
        echo "$name: kept ($(cat "output/$name/wall_seconds") s, same inputs)"
        return 0
      fi
      # A result that is not complete must not look complete.
      rm -f "output/$name/wall_seconds" "output/$name/wall_interval" "output/$name/run_info"
      mkdir -p "output/$name"
      local start milliseconds
      start=$(date +%s%N)
      if ! build-release/soft-robot "$scene" --set 'Output/Existing output=replace' \
          > "output/$name/run.log" 2>&1; then
        echo "FAILED: $scene (see output/$name/run.log)" >&2
        return 1
      fi
      local end
      end=$(date +%s%N)
      milliseconds=$(((end - start) / 1000000))
      printf 'commit %s\ninputs %s\nthreads %s\njobs %s\nset %s\n' "$SOFT_ROBOT_COMMIT" \
        "$SOFT_ROBOT_INPUTS" "$DEAL_II_NUM_THREADS" "$SOFT_ROBOT_JOBS" "$SOFT_ROBOT_SET" \
        > "output/$name/run_info"
      # start and end, for the wall time of the whole set
      printf '%d.%09d %d.%09d\n' $((start / 1000000000)) $((start % 1000000000)) \
        $((end / 1000000000)) $((end % 1000000000)) > "output/$name/wall_interval"
      # written last: its presence marks a complete result
      printf '%d.%03d\n' $((milliseconds / 1000)) $((milliseconds % 1000)) \
        > "output/$name/wall_seconds"
      echo "$name: $(cat "output/$name/wall_seconds") s"
    }
    export -f run_scene
    export SOFT_ROBOT_JOBS=${SOFT_ROBOT_JOBS:-2}
    # The cores shared among the scenes that run at the same time.
    export DEAL_II_NUM_THREADS=${DEAL_II_NUM_THREADS:-$(( $(nproc) / SOFT_ROBOT_JOBS > 0 ? $(nproc) / SOFT_ROBOT_JOBS : 1 ))}
    # The scenes of the three experiments (the pneumatic scenes have a
    # study of their own, ./soft-robot.sh pneumatics), the costliest
    # first so that the last ones to start are short: the spherical
    # pendulum (full model), the planar one (half model), the vertical
    # oscillation (quarter model), then the reduced scenes.
    for kind in spherical planar vertical column; do
      ls parameters/bellows/${kind}_*.prm
    done | xargs -P "$SOFT_ROBOT_JOBS" -I {} bash -c 'run_scene {}'
    /usr/bin/python3 doc/validation_report.py output doc
    echo "Wrote doc/validation.md"
    ;;
  *)
    echo "Usage: $0 demo|test|validate|benchmark|stability|locking|error-vs-runtime|twisting-column|damping|pneumatics|reference|swing-reference|hex-reference|swing-hex-reference|protocol" >&2
    exit 2
    ;;
esac
