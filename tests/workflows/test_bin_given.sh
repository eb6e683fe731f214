#!/usr/bin/env bash
# BIN given means prebuilt executables: `make -f Makefile.cases all BIN=...` (and demo, the
# benchmarks; BIN from the command line or the environment) compiles nothing and creates no build
# folder; it runs the cases on BIN's executables (here one structure case, SMOKE). A BIN without
# the executables fails at once, naming the missing one. Without BIN, `all` still builds first.
#   test_bin_given.sh SOURCE_DIR SCRATCH_DIR BIN_DIR
set -euo pipefail
src="$1"; scratch="$2"; bin="$3"
rm -rf "$scratch"; mkdir -p "$scratch/empty-bin"; cd "$scratch"
fail() { echo "FAIL: $*" >&2; exit 1; }
mk() { make -f "$src/Makefile.cases" --no-print-directory BUILD="$scratch/no-build" "$@"; }
only_structure=(CASES_ONEWAY= CASES_TWOWAY= CASES_FLOW= CASES_STRUCTURE=beam-revolute DEMO_CASES=structure-beam-revolute SMOKE=1)

# Dry runs: no compile step planned with BIN on the command line or in the environment.
# (The plans go through files: grep -q ending a pipe early would fail it under pipefail.)
for target in all demo bench-openfoam flow-benchmarks; do
  mk -n "$target" BIN="$bin" "${only_structure[@]}" > plan.txt 2>&1 || true
  ! grep -q "cmake" plan.txt || fail "make -n $target BIN=... plans a build: $(grep cmake plan.txt)"
  BIN="$bin" mk -n "$target" "${only_structure[@]}" > plan.txt 2>&1 || true
  ! grep -q "cmake" plan.txt || fail "BIN=... make -n $target plans a build: $(grep cmake plan.txt)"
done
# Without BIN, all builds first (the default is this tree's build).
mk -n all "${only_structure[@]}" > plan.txt 2>&1 || true
grep -q "cmake --build $scratch/no-build" plan.txt || fail "make -n all without BIN plans no build"

# For real: the case runs on BIN's executables, nothing is built.
mk all BIN="$bin" "${only_structure[@]}" > all.log 2>&1 || { tail -30 all.log; fail "make all BIN=..."; }
[ ! -e "$scratch/no-build" ] || fail "make all BIN=... created the build folder"
! grep -q cmake all.log || fail "make all BIN=... ran cmake"
[ -s runs/beam-revolute/structure-only.h5 ] || fail "make all BIN=... did not run the case"
grep -q "$bin/tfmb-beam" all.log || fail "the case did not run BIN's tfmb-beam"

# A BIN without the executables: exit 2 naming the missing one, nothing built or run.
rc=0; mk all BIN="$scratch/empty-bin" "${only_structure[@]}" > empty.log 2>&1 || rc=$?
[ $rc -ne 0 ] || fail "make all with an empty BIN succeeded"
grep -q "bin-check: no executable $scratch/empty-bin/tfmb-input" empty.log || fail "no message naming the missing executable: $(cat empty.log)"
[ ! -e "$scratch/no-build" ] || fail "make all with an empty BIN created the build folder"
echo "BIN-given test passed"
