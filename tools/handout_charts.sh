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
  local out="handouts/images/$lab/$(basename "${scene%.json}")"
  ./springlab chart "$kind" "$scene" --reference --out "$out" "$@"
  # The facts name the scene by its path in this tree, not on this machine.
  sed -i "s|\"$PWD/|\"|g" "$out"/*.json
}

ONLY="${1:-}"
chart 01_rope work-precision scenes/mass_on_spring.json --time 5
chart 01_rope stability scenes/mass_on_spring.json --no-map
chart 01_rope work-precision scenes/rope.json --time 0.5
chart 01_rope stability scenes/rope.json
chart 01_rope resolution scenes/rope.json --observable sag --tol 0.02

# Lab 2: the 32 x 32 hanging cloth with only springs and gravity at work (stretch limiting
# off: it is a position correction that hides instability).
CLOTH=(--set net.resolution=32 --set net.stretch_limit.enabled=false)
chart 02_net stability scenes/net_hanging.json "${CLOTH[@]}" --no-map
# From dt = 10 ms (about the 1/120 s step of the fabric): XPBD and projective dynamics are
# stable there, every explicit method is not (handout 02, section 7.d).
chart 02_net work-precision scenes/net_hanging.json "${CLOTH[@]}" --time 0.2 --levels 8 --largest-dt 0.01 --repeats 1
chart 02_net resolution scenes/net_hanging.json --observable drape_height --tol 0.02 --time 1 --resolutions 8,16,32

# Lab 3: the bouncing ball. Work-precision over 0.8 s: the fall, the landing (0.45 s), the
# squash and the lift-off (0.73 s), so that the floor's contact switches on and off in it.
chart 03_softbody stability scenes/softbody_ball.json --no-map
chart 03_softbody work-precision scenes/softbody_ball.json --time 0.8 --levels 6 --repeats 1
chart 03_softbody resolution scenes/softbody_ball.json --observable volume --tol 0.02 --time 0.5 --resolutions 1,2,3
