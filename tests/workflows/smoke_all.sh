#!/usr/bin/env bash
# Every case end to end with SMOKE=1 (coarse meshes, few iterations and steps), one run directory
# per case under RUN_ROOT: the coupled configurations and nasa-2dcd with FLOW as the flow stage
# (tfmb-flow in CI; tests/workflows/analytic-flow to exercise the rest of a chain alone), the
# channel and flat-plate flow cases with tfmb-flow itself, the structure-only cases with tfmb-beam. Checks that each run exits 0,
# writes summary.json and report.html, and that every .h5 it wrote passes tfmb-check; prints the time per case.
# A case whose model uses something a tool refuses as "not supported by this ... version" (the
# flexible joints of tfmb-beam, issue 7) is reported as blocked, not failed.
#   smoke_all.sh SOURCE_DIR RUN_ROOT BIN_DIR FLOW
set -uo pipefail
src="$1"; root="$2"; bin="$3"; flow="$4"
cd "$src"
case "$flow" in /*) ;; *) flow="$src/$flow" ;; esac
mkdir -p "$root"
failed=0
run_case() {  # name target [make variables...]
  local name="$1" target="$2"; shift 2
  local run="$root/$name" start end rc
  rm -rf "$run"
  start=$(date +%s.%N)
  make -f Makefile.cases --no-print-directory SMOKE=1 RUN="$run" BIN="$bin" "$@" $target \
    > "$run.log" 2>&1
  rc=$?
  end=$(date +%s.%N)
  local secs; secs=$(awk -v a="$start" -v b="$end" 'BEGIN { printf "%.1f", b - a }')
  if [ $rc -ne 0 ]; then
    if grep -q "is not supported by this tfmb-.* version" "$run.log"; then
      echo "BLOCKED $name ($secs s): $(grep -m1 "not supported" "$run.log")"
      return
    fi
    echo "FAIL    $name ($secs s): exit $rc; last lines of $run.log:"; tail -15 "$run.log"
    failed=1; return
  fi
  if [ ! -s "$run/summary.json" ]; then echo "FAIL    $name: no summary.json"; failed=1; return; fi
  if [ ! -s "$run/report.html" ]; then echo "FAIL    $name: no report.html"; failed=1; return; fi
  local bad=0 f
  while IFS= read -r f; do
    "$bin/tfmb-check" --no-summary "$f" > /dev/null 2>> "$run.check" || bad=1
  done < <(find "$run" -name '*.h5' ! -type l)
  if [ $bad -ne 0 ]; then echo "FAIL    $name: files fail tfmb-check:"; cat "$run.check"; failed=1; return; fi
  echo "ok      $name ($secs s)"
}
run_case config1 oneway CASE=config1 FLOW="$flow"
# config1 also writes the seed's nodal-force comparison.
[ -s "$root/config1/nodal-forces.json" ] && [ -s "$root/config1/plots/nodal_forces.png" ] ||
  { echo "FAIL    config1: no nodal-forces.json or plots/nodal_forces.png"; failed=1; }
run_case config2 twoway CASE=config2 FLOW="$flow"
run_case config2-dynamic twoway CASE=config2 EXCHANGE=dynamic FLOW="$flow"
run_case config3 oneway CASE=config3 FLOW="$flow"
run_case config4 twoway CASE=config4 FLOW="$flow"
run_case config5 twoway CASE=config5 FLOW="$flow"
run_case nparc-cdv "flow summary report" CASE=nparc-cdv
# NASA B1 at NPR 8.91, second-order SA (case.mk): converges on the SMOKE mesh (124 iterations);
# a smoke run would accept a stop at SMOKE's iteration limit (exit 1) and checks the files.
run_case nasa-2dcd "flow summary report" CASE=nasa-2dcd FLOW="$flow"
# Back-Massier-Gier, axisymmetric second-order SA on the SMOKE mesh (case.mk).
run_case bmg-conical "flow summary report" CASE=bmg-conical
run_case tmr-flatplate "flow summary report" CASE=tmr-flatplate
run_case beam-revolute "structure summary report" CASE=beam-revolute
run_case flexible-joint "structure summary report" CASE=flexible-joint
[ $failed -eq 0 ] && echo "smoke: every case ran" || echo "smoke: some cases failed"
exit $failed
