#!/bin/sh
# headless.sh XVFB COMMAND...: COMMAND on an Xvfb display of its own; exits with COMMAND's
# exit code. The product's way (`./springlab run`, function headless): Xvfb chooses a free
# display and names it (-displayfd), and this script stops it and removes its folder however
# the command ends. xvfb-run, used before, failed now and then while removing its own
# temporary folder and then exited 5, which a test read as the viewer's exit code.
set -u
xvfb=$1
shift
dir=$(mktemp -d "${TMPDIR:-/tmp}/springlab-viewer-test.XXXXXX")
server=""
cleanup() {
  if [ -n "$server" ]; then
    kill "$server" 2>/dev/null
    wait "$server" 2>/dev/null
  fi
  rm -rf "$dir"
}
trap cleanup EXIT
"$xvfb" -displayfd 3 -screen 0 1280x800x24 -nolisten tcp 3>"$dir/display" 2>"$dir/xvfb.log" &
server=$!
waited=0
while [ ! -s "$dir/display" ]; do
  if ! kill -0 "$server" 2>/dev/null || [ "$waited" -ge 100 ]; then
    cat "$dir/xvfb.log"
    echo "Xvfb did not start (its log is above)"
    exit 1
  fi
  sleep 0.1
  waited=$((waited + 1))
done
DISPLAY=":$(head -n 1 "$dir/display")" "$@"
