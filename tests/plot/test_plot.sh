#!/usr/bin/env bash
# tfmb-plot draws every picture from valid files of each kind and refuses wrong inputs (exit 3).
set -euo pipefail
bin="$1"; scratch="$2"
rm -rf "$scratch"; mkdir -p "$scratch"; cd "$scratch"
fail() { echo "FAIL: $*" >&2; exit 1; }
for kind in flow structure thermal strain; do "$bin/tfmb-check" --example $kind -o $kind.h5; done
printf 'iteration,residual_norm,displacement_norm,measure,value,tolerance,acceleration,relaxation,iqn_columns,status,stage_times\n1,1e-2,1,relative,1e-2,1e-3,aitken,0.5,0,continue,\n2,1e-4,1,relative,1e-4,1e-3,aitken,0.7,0,converged,\n' > coupling.csv
"$bin/tfmb-plot" wall-pressure flow.h5 -o wall.png
"$bin/tfmb-plot" field flow.h5 --field mach -o mach.png
"$bin/tfmb-plot" residuals flow.h5 -o residuals.png
"$bin/tfmb-plot" deformed structure.h5 -o deformed.png
"$bin/tfmb-plot" temperature thermal.h5 -o temperature.png
"$bin/tfmb-plot" strain strain.h5 -o strain.png
"$bin/tfmb-plot" convergence coupling.csv -o coupling.png
for png in wall mach residuals deformed temperature strain coupling; do
  head -c 8 $png.png | od -An -c | grep -q 'P   N   G' || fail "$png.png is not a PNG"
done
set +e
"$bin/tfmb-plot" strain flow.h5 -o x.png 2>/dev/null; [ $? -eq 3 ] || fail "wrong kind not exit 3"
"$bin/tfmb-plot" field missing.h5 -o x.png 2>/dev/null; [ $? -eq 3 ] || fail "missing file not exit 3"
"$bin/tfmb-plot" field flow.h5 --field nothing -o x.png 2>/dev/null; [ $? -eq 3 ] || fail "missing field not exit 3"
"$bin/tfmb-plot" bogus 2>/dev/null; [ $? -eq 2 ] || fail "usage not exit 2"
[ ! -e x.png ] || fail "a failed plot left a file"
echo "plot tests passed"
