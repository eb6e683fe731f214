#!/usr/bin/env bash
# Stage replacement: Makefile.cases runs config1 one-way (SMOKE) with the flow stage replaced by
# an external command (tests/workflows/analytic-flow writes flow.h5 from an analytic field), and
# the rest of the chain runs on it: every file passes tfmb-check, plots and summary are written.
# A flow.h5 dropped in place is taken as the flow stage's result (make does not rerun it).
set -euo pipefail
src="$1"; run="$2"; bin="$3"
cd "$src"
rm -rf "$run"
fail() { echo "FAIL: $*" >&2; exit 1; }
make -f Makefile.cases --no-print-directory CASE=config1 SMOKE=1 RUN="$run" BIN="$bin" \
  FLOW="$src/tests/workflows/analytic-flow" oneway > "$run.log" 2>&1 || { tail -40 "$run.log"; fail "oneway"; }
for f in model flowmesh solidmesh flow thermal materials loads structure strain; do
  "$bin/tfmb-check" --no-summary "$run/$f.h5" || fail "$f.h5 does not pass tfmb-check"
done
grep -q "analytic field" <(h5dump -a /convergence/criterion "$run/flow.h5") || fail "flow.h5 is not the swapped stage's"
for png in wall_pressure mach deformed temperature margins; do [ -s "$run/plots/$png.png" ] || fail "plot $png"; done
/usr/bin/python3 -c "import json,sys; s=json.load(open('$run/summary.json')); assert 'strain' in s and 'structure' in s, s.keys()"
# A dropped-in flow file (newer than its inputs and the flow's settings record) is taken: make
# reruns only what depends on it. (The same FLOW as the run's: another would change the flow's
# command, which reruns the flow stage; tests/workflows/test_settings_rerun.sh.)
cp "$run/flow.h5" "$run/flow-dropped.h5"; mv "$run/flow-dropped.h5" "$run/flow.h5"; touch "$run/flow.h5"
cp "$run/flow.h5" "$run.flow-dropped.h5"
make -f Makefile.cases --no-print-directory CASE=config1 SMOKE=1 RUN="$run" BIN="$bin" \
  FLOW="$src/tests/workflows/analytic-flow" "$run/strain.h5" > "$run.log2" 2>&1 || { tail -20 "$run.log2"; fail "make after the dropped file"; }
! grep -q "stage flow" "$run.log2" || fail "the dropped file was not taken (the flow stage ran)"
cmp -s "$run/flow.h5" "$run.flow-dropped.h5" || fail "the dropped flow.h5 was replaced"
grep -q "stage beam" "$run.log2" || fail "the stages after the dropped file were not rerun"
echo "stage swap test passed"
