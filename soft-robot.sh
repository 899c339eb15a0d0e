#!/usr/bin/env bash
# The two commands of the README, for a fresh Debian 12 machine (as root):
#
#   ./soft-robot.sh demo   install what is missing, build in Release, run the
#                          default scene (parameters/bellows_release_quarter_3d.prm)
#                          and the 1D and 2D scenes
#   ./soft-robot.sh test   install what is missing, build in Debug (deal.II's
#                          internal checks on), run the whole test suite
#
# Build directories: build-release/ and build-debug/ beside this script.
set -euo pipefail
cd "$(dirname "$0")"

packages=(cmake make g++ libdeal.ii-dev libfftw3-dev libgtest-dev)

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
    for scene in bellows_release_quarter_3d column_1d plate_2d; do
      build-release/soft-robot parameters/$scene.prm
      echo "Open output/$scene/solution.pvd in ParaView."
    done
    ;;
  test)
    install_missing_packages
    build Debug build-debug -DSOFT_ROBOT_BUILD_TESTS=ON
    cd build-debug
    ctest --output-on-failure -j "$(nproc)"
    ;;
  *)
    echo "Usage: $0 demo|test" >&2
    exit 2
    ;;
esac
