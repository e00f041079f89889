#!/bin/sh
# run_viewer.sh XVFB APP SCENE PNG EXPECTED_EXIT PYTHON CHECK_SNAPSHOT "CHECK_ARGS"
# Opens APP's viewer on SCENE for 90 frames on a display of its own (headless.sh), expects its
# exit code, the panel with every label whole, then checks the PNG (check_snapshot.py
# CHECK_ARGS, split on spaces).
set -u
xvfb=$1 app=$2 scene=$3 png=$4 expected=$5 python=$6 check=$7 check_args=$8
rm -f "$png"
sh "$(dirname "$0")/headless.sh" "$xvfb" "$app" view "$scene" --frames 90 --snapshot "$png" >"$png.log" 2>&1
code=$?
cat "$png.log"
if [ "$code" -ne "$expected" ]; then
  echo "viewer exit code $code, expected $expected"
  exit 1
fi
grep -q "the panel's labels fit" "$png.log" || { echo "the control panel cuts labels"; exit 1; }
# CHECK_ARGS is a list of options: split on purpose.
"$python" "$check" "$png" $check_args
