#!/usr/bin/env bash
# Regenerate the charts the handouts show (PNG, with their CSV data) under handouts/images/.
# One line per chart; a lab adds its own lines. Uses the reference code (instructor tree).
#
#   tools/handout_charts.sh            every lab
#   tools/handout_charts.sh 01_rope    one lab
set -euo pipefail
cd "$(dirname "$0")/.."

chart() {  # chart LAB KIND SCENE [options]: writes handouts/images/LAB/SCENE-NAME/
  local lab="$1" kind="$2" scene="$3"
  shift 3
  [[ -n "${ONLY:-}" && "$ONLY" != "$lab" ]] && return 0
  ./springlab chart "$kind" "$scene" --reference --out "handouts/images/$lab/$(basename "${scene%.json}")" "$@"
}

ONLY="${1:-}"
chart 01_rope work-precision scenes/mass_on_spring.json --time 5
chart 01_rope stability scenes/mass_on_spring.json --no-map
chart 01_rope work-precision scenes/rope.json --time 0.5
chart 01_rope stability scenes/rope.json
chart 01_rope resolution scenes/rope.json --observable sag --tol 0.02
