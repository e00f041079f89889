#!/usr/bin/env bash
# The browser build behind `./springlab web`: the viewer and the labs compiled with Emscripten
# (framework/web/) into a folder of static files, every scene of the built labs selectable.
#
# usage: tools/web_build.sh [--tree reference|student] [--out DIR] [--serve [PORT]] [SCENE|LAB]...
#   SCENE   a scene file: its lab is built and the page opens on it
#   LAB     rope, net or softbody: that lab is built (its scenes listed)
#   (none)  every lab; the page opens on scenes/rope.json
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
JOBS="$(nproc 2>/dev/null || echo 2)"
export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$ROOT}"
# Debian's emscripten runs its JavaScript tools (acorn, terser) from Debian's node modules.
[[ -d /usr/share/nodejs ]] && export NODE_PATH="${NODE_PATH:+$NODE_PATH:}/usr/share/nodejs"

say() { printf 'springlab web: %s\n' "$*" >&2; }
die() { say "$*"; exit 2; }

usage() { sed -n '2,8p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'; }

tree=""
out="$ROOT/out/web"
serve=""
targets=()
while [[ $# -gt 0 ]]; do
  case "$1" in
    --tree) tree="$2"; shift ;;
    --out) out="$2"; shift ;;
    --serve) serve=8000; [[ "${2:-}" =~ ^[0-9]+$ ]] && { serve="$2"; shift; } ;;
    -h|--help) usage; exit 0 ;;
    -*) die "unknown option $1 (see --help)" ;;
    *) targets+=("$1") ;;
  esac
  shift
done
if [[ -z "$tree" ]]; then
  tree=student
  [[ -d "$ROOT/solutions" ]] && tree=reference
fi
[[ "$tree" =~ ^(student|reference)$ ]] || die "--tree is student or reference, not '$tree'"
[[ "$tree" == student || -d "$ROOT/solutions" ]] || die "the reference needs solutions/, which this tree does not have"

# ---- Emscripten: installed, or offered as `setup` offers packages ---------------------------
# Debian's package brings its system libraries prebuilt (a frozen cache): nothing is built
# once per machine. With emsdk, Emscripten builds them once into its own cache.
if ! command -v emcc >/dev/null || ! command -v emcmake >/dev/null; then
  "$ROOT/tools/offer_package.sh" web emscripten \
    "install Emscripten (the emsdk from emscripten.org, or your distribution's emscripten package), then run this again"
fi

# ---- which labs, and the scene the page opens on ---------------------------------------------
# A scene's lab is its "lab" key; every lab of the manifests (tests/NN_<id>/) when none is named.
table="$(python3 "$ROOT/tools/lab_table.py")" || exit 2
all_labs=()
while read -r id _; do all_labs+=("$id"); done <<<"$table"
labs=()
default_scene=rope.json
for t in "${targets[@]}"; do
  if [[ " ${all_labs[*]} " == *" $t "* ]]; then
    labs+=("$t")
    continue
  fi
  [[ -f "$t" ]] || [[ ! -f "$ROOT/$t" ]] || t="$ROOT/$t"
  [[ -f "$t" ]] || die "no lab or scene file named '$t' (labs: ${all_labs[*]})"
  [[ "$(cd "$(dirname "$t")" && pwd)" == "$ROOT/scenes" ]] ||
    die "$t: the page runs the scenes of scenes/ (put the file there)"
  lab="$(python3 -c 'import json, sys; print(json.load(open(sys.argv[1])).get("lab", ""))' "$t")" ||
    die "$t: not a JSON scene"
  [[ " ${all_labs[*]} " == *" $lab "* ]] || die "$t: \"lab\" is '$lab', not one of ${all_labs[*]}"
  labs+=("$lab")
  default_scene="$(basename "$t")"
done
[[ ${#labs[@]} -gt 0 ]] || labs=("${all_labs[@]}")
mapfile -t labs < <(printf '%s\n' "${labs[@]}" | sort -u)
if [[ ${#targets[@]} -gt 0 && "$default_scene" == rope.json && " ${labs[*]} " != *" rope "* ]]; then
  default_scene=""  # a lab without a scene named: its first scene (below)
fi

# ---- configure and build --------------------------------------------------------------------
build="$ROOT/build-web-$tree"
config=(-DSPRINGLAB_WEB_TREE="$tree")
command -v ccache >/dev/null && config+=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
[[ "${SPRINGLAB_WARNINGS_AS_ERRORS:-}" =~ ^(ON|on|1|TRUE|true)$ ]] && config+=(-DSPRINGLAB_WARNINGS_AS_ERRORS=ON)
if [[ ! -f "$build/CMakeCache.txt" ]]; then
  say "configuring $build (log: $build/configure.log); the first build takes a few minutes"
  mkdir -p "$build"
  emcmake cmake -S "$ROOT/framework/web" -B "$build" "${config[@]}" >"$build/configure.log" 2>&1 ||
    { tail -20 "$build/configure.log" >&2; die "configure failed; the full log is $build/configure.log"; }
fi
programs=()
for lab in "${labs[@]}"; do programs+=("springlab-web-$lab"); done
say "building ${programs[*]} ($tree code)"
set +e
cmake --build "$build" -j "$JOBS" --target "${programs[@]}" 2>&1 |
  grep --line-buffered -v -E '^(\[ *[0-9]+%\] Built target|g?make)' >&2
statuses=("${PIPESTATUS[@]}")
set -e
[[ "${statuses[0]}" == 0 ]] || die "build failed (the compiler's messages are above)"

# ---- the page -------------------------------------------------------------------------------
mkdir -p "$out"
cp "$ROOT/framework/web/index.html" "$ROOT/framework/web/page.js" "$out/"
for p in "${programs[@]}"; do cp "$build/$p.js" "$build/$p.wasm" "$build/$p.data" "$out/"; done
# scenes.js: the scenes of the built labs (file, name, lab) and the one the page opens on.
python3 - "$ROOT/scenes" "$out/scenes.js" "$default_scene" "${labs[@]}" <<'PY'
import json, pathlib, sys
folder, target, default, labs = pathlib.Path(sys.argv[1]), sys.argv[2], sys.argv[3], sys.argv[4:]
scenes = []
for path in sorted(folder.glob("*.json")):
    scene = json.loads(path.read_text())
    if scene.get("lab") in labs:
        scenes.append({"file": path.name, "name": scene.get("name", path.stem), "lab": scene["lab"]})
default = default or scenes[0]["file"]
pathlib.Path(target).write_text(
    "// Written by tools/web_build.sh: the scenes this build runs, and the one the page opens on.\n"
    f"window.SPRINGLAB_SCENES = {json.dumps(scenes, indent=1)};\n"
    f"window.SPRINGLAB_DEFAULT_SCENE = {json.dumps(default)};\n")
PY
say "wrote ${out#"$ROOT"/}/ (index.html; the scenes load over HTTP, not from file://)"
if [[ -n "$serve" ]]; then
  say "serving it on http://localhost:$serve/ (Ctrl-C stops)"
  exec python3 -m http.server --bind 127.0.0.1 --directory "$out" "$serve"
fi
say "open it with: python3 -m http.server --bind 127.0.0.1 --directory ${out#"$ROOT"/} 8000, then http://localhost:8000/"
