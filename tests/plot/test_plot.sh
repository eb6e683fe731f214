#!/usr/bin/env bash
# tfmb-plot draws every picture from valid files of each kind and refuses wrong inputs (exit 3,
# one line). Run twice: the copy in BIN (with tfmbfiles.py beside it) and the source tree's
# script (which finds formats/python/tfmbfiles.py), so that both ways of finding the reader work.
set -euo pipefail
bin="$1"; scratch="$2"
source_script="$(cd "$(dirname "$0")/../.." && pwd)/tools/tfmb-plot/tfmb-plot"
fail() { echo "FAIL: $*" >&2; exit 1; }
for plot in "$bin/tfmb-plot" "$source_script"; do
  rm -rf "$scratch"; mkdir -p "$scratch"; cd "$scratch"
  for kind in flow structure thermal strain; do "$bin/tfmb-check" --example $kind -o $kind.h5; done
  printf 'iteration,residual_norm,displacement_norm,measure,value,tolerance,acceleration,relaxation,iqn_columns,status,stage_times\n1,1e-2,1,relative,1e-2,1e-3,aitken,0.5,0,continue,\n2,1e-4,1,relative,1e-4,1e-3,aitken,0.7,0,converged,\n' > coupling.csv
  "$plot" wall-pressure flow.h5 -o wall.png
  "$plot" field flow.h5 --field mach -o mach.png
  "$plot" residuals flow.h5 -o residuals.png
  "$plot" deformed structure.h5 -o deformed.png
  "$plot" temperature thermal.h5 -o temperature.png
  "$plot" strain strain.h5 -o strain.png
  "$plot" convergence coupling.csv -o coupling.png
  for png in wall mach residuals deformed temperature strain coupling; do
    head -c 8 $png.png | od -An -c | grep -q 'P   N   G' || fail "$plot: $png.png is not a PNG"
  done
  set +e
  "$plot" strain flow.h5 -o x.png 2>/dev/null; [ $? -eq 3 ] || fail "$plot: wrong kind not exit 3"
  "$plot" field missing.h5 -o x.png 2>/dev/null; [ $? -eq 3 ] || fail "$plot: missing file not exit 3"
  "$plot" field flow.h5 --field nothing -o x.png 2>/dev/null; [ $? -eq 3 ] || fail "$plot: missing field not exit 3"
  "$plot" bogus 2>/dev/null; [ $? -eq 2 ] || fail "$plot: usage not exit 2"
  "$plot" deformed flow.h5 -o x.png 2> err.txt
  [ "$(wc -l < err.txt)" -eq 1 ] && grep -q "^tfmb-plot: error: flow.h5: /: attribute 'format'" err.txt ||
    fail "$plot: wrong kind: not one located line: $(cat err.txt)"
  [ ! -e x.png ] || fail "$plot: a failed plot left a file"
  set -e
done
echo "plot tests passed"
