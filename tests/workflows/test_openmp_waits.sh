#!/usr/bin/env bash
# Makefile.cases's OpenMP waits (tools/tfmb-flow/PERFORMANCE-LOG.md, session 52): one job at a
# time the runtime's default spin (GOMP_SPINCOUNT=300000), make -jN with N > 1 and the test
# targets' ctest -jN no spin (0, as OMP_WAIT_POLICY=passive), and a caller's own setting kept.
# Argument: source dir.
set -euo pipefail
src=$1
clean=(env -u GOMP_SPINCOUNT -u OMP_WAIT_POLICY -u MAKEFLAGS -u MAKELEVEL)
waits() {  # [VAR=value ...] [make option ...]: the two variables as a recipe of Makefile.cases sees them
  local vars=() opts=()
  for a in "$@"; do case $a in *=*) vars+=("$a") ;; *) opts+=("$a") ;; esac; done
  "${clean[@]}" "${vars[@]}" make -s "${opts[@]}" -f "$src/Makefile.cases" \
    --eval 'show-waits: ; @echo "spin=$${GOMP_SPINCOUNT-unset} policy=$${OMP_WAIT_POLICY-unset}"' show-waits
}
check() {  # expected, then waits' arguments
  local expected=$1 got
  shift
  got=$(waits "$@")
  [ "$got" = "$expected" ] || { echo "openmp waits: '$*' gave '$got', expected '$expected'" >&2; exit 1; }
}
check "spin=300000 policy=unset"
check "spin=300000 policy=unset" -j1
check "spin=0 policy=unset" -j2
check "spin=5 policy=unset" GOMP_SPINCOUNT=5
check "spin=unset policy=passive" OMP_WAIT_POLICY=passive
# the test targets' ctest -j$(JOBS): no spin unless JOBS=1. make -n prints their recipes and runs
# only the probe's (+), a prerequisite added to them, which sees their variables.
probe=(--eval 'show-waits: ; +@echo "spin=$${GOMP_SPINCOUNT-unset}"' --eval 'test test-asan: show-waits')
for target in test test-asan; do
  for jobs in 2 1; do
    expected=$([ "$jobs" = 1 ] && echo 300000 || echo 0)
    got=$("${clean[@]}" make -n -s -f "$src/Makefile.cases" "${probe[@]}" JOBS=$jobs "$target" | grep '^spin=')
    [ "$got" = "spin=$expected" ] || {
      echo "openmp waits: $target with JOBS=$jobs sees '$got', expected 'spin=$expected'" >&2; exit 1; }
  done
done
echo "openmp waits: as documented"
