#!/usr/bin/env bash
# Two-way coupling plumbing: config4 (SMOKE) with the flow stage swapped for an analytic field
# runs iterations in runs/.../iter-NNN (deform -> flow -> loads -> beam -> displace -> couple)
# until tfmb-couple says converged, keeps every iterate, and writes the coupling log and plot.
# Then: `make twoway` again on the finished run keeps its history (it emptied coupling.csv), and
# a run interrupted inside iteration 2 resumes (it failed: "holds 0 iterations, expected 1").
set -euo pipefail
src="$1"; run="$2"; bin="$3"
cd "$src"
rm -rf "$run"
fail() { echo "FAIL: $*" >&2; exit 1; }
make -f Makefile.cases --no-print-directory CASE=config4 SMOKE=1 RUN="$run" BIN="$bin" \
  FLOW="$src/tests/workflows/analytic-flow" COUPLE_OPTS="--max-iterations 8 --tolerance 1e-4" \
  twoway > "$run.log" 2>&1 || { tail -40 "$run.log"; fail "twoway"; }
[ -d "$run/iter-002" ] || fail "no second iteration"
"$bin/tfmb-check" --no-summary "$run/iter-002/flowmesh.h5" "$run/iter-002/walldisp.h5" || fail "iterate files"
last=$(cat "$run/last-iteration")
[ "$(cat "$last/coupling.status")" = converged ] || fail "not converged"
[ -s "$run/plots/coupling.png" ] || fail "no coupling plot"
/usr/bin/python3 -c "import json; s=json.load(open('$run/summary.json')); assert s['coupling']['status']=='converged', s['coupling']"

iterations() { tail -n +2 "$run/coupling.csv" | cut -d, -f1 | tr '\n' ' '; }
history=$(iterations)
[ -n "$history" ] || fail "empty coupling.csv"
again() {
  make -f Makefile.cases --no-print-directory CASE=config4 SMOKE=1 RUN="$run" BIN="$bin" \
    FLOW="$src/tests/workflows/analytic-flow" COUPLE_OPTS="--max-iterations 8 --tolerance 1e-4" \
    twoway > "$run.log" 2>&1 || { tail -40 "$run.log"; fail "twoway $1"; }
  [ "$(iterations)" = "$history" ] || fail "$1: coupling.csv iterations '$(iterations)', expected '$history'"
  /usr/bin/python3 -c "import json; s=json.load(open('$run/summary.json')); assert s['coupling']['status']=='converged', s"
}
again "rerun of a finished run"
grep -q "iter-002/flow.h5\|stage flow" "$run.log" && fail "the rerun of a finished run redid a stage"
# interrupted after iteration 2's beam: its coupling step and what follows are redone
rm -f "$run/iter-002/coupling.status" "$run/iter-002/walldisp-raw.h5"
again "resume inside iteration 2"
echo "twoway smoke test passed"
