#!/bin/bash
# SPDX-License-Identifier: LGPL-2.1-or-later
# Writes the bellows meshes meshes/bellows_<model>_<level>.msh from
# meshes/bellows.geo with gmsh (Debian: apt-get install gmsh; tested with 4.8.4)
# and prints their element and node counts.
#
#   bash meshes/generate_meshes.sh            all committed meshes
#   bash meshes/generate_meshes.sh quarter    the committed meshes of one model
#   bash meshes/generate_meshes.sh quarter ultrafine
#                                             one mesh (also one not committed)
#
# Levels:
#   coarse  close to the element counts of the reference study's meshes
#           (quarter 1,743, half 3,670, full 4,178 linear tetrahedra); the
#           section's own short edges set the mesh there, so the sizes differ
#           per model and the full model needs fewer nodes on small circles.
#   medium  element size 5 mm everywhere, a little over the wall thickness.
#   fine    element size 3 mm, the wall thickness.
#   extrafine  element size 2 mm, the quarter model only (the largest
#           committed mesh of the benchmark's refinement series).
#   coarse-curved, medium-curved  the quarter model's coarse and medium
#           cells as 10-node tetrahedra, their mid-edge nodes on the curved
#           surfaces (not committed; the reference study writes them). The
#           medium one uses the Frontal-Delaunay surface mesher, with which
#           gmsh untangles every curved tetrahedron (with Delaunay, one
#           stays inverted).
#   extrafine-frontal  the extrafine quarter mesh made with the
#           Frontal-Delaunay surface mesher instead of Delaunay: a second mesh
#           of the same size, for the scatter between meshes (not committed;
#           the reference study writes it).
#   medium-cylinder  the quarter and half models' medium meshes with the
#           tip block as the cylinder of the hexahedral mesh (BlockShape 1,
#           include/core/bellows_mesh.h) instead of the box (not committed;
#           the reference study writes them, to measure what the block's
#           shape changes).
#   ultrafine  element size 1 mm, the quarter model only, about 87,000
#           unknowns with linear elements: the benchmark's largest mesh. At
#           7 MB it is not committed; the benchmark writes it when missing.
# The surface mesher is fixed per mesh: which of gmsh's three leaves the
# fewest flat tetrahedra in the thin walls differs from mesh to mesh, and it
# was chosen once by the smallest quality gamma (see README.md).
#
# gmsh runs single-threaded with fixed options, so a run gives the same
# files byte for byte.
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
geo="$here/bellows.geo"

# model   Model  level   ElementSize  CircleNodes  SurfaceAlgorithm
#   [ElementOrder [BlockShape]]
meshes="
quarter 1 coarse 10.5 7 6
half    2 coarse  9.5 7 6
full    4 coarse 12   5 5
quarter 1 medium  5   7 5
half    2 medium  5   7 1
full    4 medium  5   7 1
quarter 1 fine    3   7 1
half    2 fine    3   7 5
full    4 fine    3   7 5
quarter 1 extrafine 2 7 5
quarter 1 extrafine-frontal 2 7 6
quarter 1 ultrafine 1 7 6
quarter 1 coarse-curved 10.5 7 6 2
quarter 1 medium-curved 5 7 6 2
quarter 1 medium-cylinder 5 7 5 1 1
half    2 medium-cylinder 5 7 1 1 1
"

only="${1:-}"
only_level="${2:-}"
printf "%-28s %10s %8s %10s\n" "mesh" "tets" "nodes" "triangles"
while read -r model quarters level size circle surface order shape; do
  [ -z "$model" ] && continue
  [ -n "$only" ] && [ "$only" != "$model" ] && continue
  [ -n "$only_level" ] && [ "$only_level" != "$level" ] && continue
  # The meshes that are not committed only when asked for by name.
  case "$level" in ultrafine | extrafine-frontal | *-curved | *-cylinder)
    [ "$only_level" != "$level" ] && continue ;;
  esac
  out="$here/bellows_${model}_${level}.msh"
  log="$(mktemp)"
  gmsh "$geo" -3 -nt 1 -format msh22 \
    -setnumber Model "$quarters" -setnumber ElementSize "$size" \
    -setnumber CircleNodes "$circle" -setnumber SurfaceAlgorithm "$surface" \
    -setnumber ElementOrder "${order:-1}" -setnumber BlockShape "${shape:-0}" \
    -o "$out" > "$log" 2>&1 || true
  # gmsh reports errors (including those raised by bellows.geo's own checks)
  # on its log but still exits with 0.
  # A curved mesh must leave no tetrahedron inverted ("jac. < 0" in the
  # last report of its volume mesh).
  if grep -q '^Error' "$log" || [ ! -s "$out" ] ||
     grep 'volume mesh: worst distortion' "$log" | tail -1 | grep -q 'jac. < 0'; then
    grep '^Error\|jac. < 0' "$log" >&2 || true
    echo "generate_meshes.sh: gmsh failed for $out" >&2
    rm -f "$log" "$out"
    exit 1
  fi
  rm -f "$log"
  # Element types 4 and 11 are the linear and 10-node tetrahedron, 2 and 9
  # the linear and 6-node triangle (MSH 2.2).
  counts=$(awk '/^\$Nodes/ {getline; nodes = $1}
                /^\$Elements/ {inside = 1; getline; next}
                /^\$EndElements/ {inside = 0}
                inside && ($2 == 4 || $2 == 11) {tets++}
                inside && ($2 == 2 || $2 == 9) {tris++}
                END {printf "%10d %8d %10d", tets, nodes, tris}' "$out")
  printf "%-28s %s\n" "$(basename "$out")" "$counts"
done <<< "$meshes"
