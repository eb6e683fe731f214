#!/usr/bin/env bash
# One exit-code rule for a missing input file across the stages (DESIGN.md: 3, bad input): every
# tool, with the missing file in each input position the Makefile uses, exits 3 with one line
# naming that file and writes no output; every workflow script answers --help.
# Arguments: source dir, bin dir, scratch dir.
set -uo pipefail
src=$1 bin=$2 scratch=$3
db="$src/data/materials-db.h5"
rm -rf "$scratch" && mkdir -p "$scratch"
missing="$scratch/no-such-file.h5"
out="$scratch/out.h5"
failed=0
expect_missing() {  # label, command...
  local label=$1
  shift
  local rc=0
  "$@" > "$scratch/stdout" 2> "$scratch/stderr" || rc=$?
  if [ "$rc" -ne 3 ]; then
    echo "FAIL $label: exit $rc, expected 3: $(head -c 300 "$scratch/stderr")"
    failed=1
  elif ! grep -q "no-such-file" "$scratch/stderr" || [ "$(wc -l < "$scratch/stderr")" -gt 3 ]; then
    echo "FAIL $label: the message does not name the file in a line: $(cat "$scratch/stderr")"
    failed=1
  elif [ -e "$out" ]; then
    echo "FAIL $label: wrote $out"
    failed=1
  else
    echo "ok   $label"
  fi
  rm -f "$out"
}
expect_missing "tfmb-input case" "$bin/tfmb-input" "$scratch/no-such-file.toml" -o "$out"
expect_missing "tfmb-mesh flow" "$bin/tfmb-mesh" flow "$missing" -o "$out"
expect_missing "tfmb-mesh solid" "$bin/tfmb-mesh" solid "$missing" -o "$out"
expect_missing "tfmb-flow mesh" "$bin/tfmb-flow" "$missing" --p0 2e5 --T0 300 -o "$out"
expect_missing "tfmb-beam model" "$bin/tfmb-beam" "$missing" -o "$out"
expect_missing "tfmb-heat" "$bin/tfmb-heat" "$missing" "$missing" "$missing" --db "$db" -o "$out"
expect_missing "tfmb-heat --db" "$bin/tfmb-heat" "$missing" "$missing" "$missing" --db "$missing" -o "$out"
expect_missing "tfmb-matmap" "$bin/tfmb-matmap" "$missing" "$missing" --db "$db" -o "$out"
expect_missing "tfmb-loads forces" "$bin/tfmb-loads" forces "$missing" "$missing" -o "$out"
expect_missing "tfmb-strain" "$bin/tfmb-strain" "$missing" "$missing" -o "$out"
expect_missing "tfmb-check" "$bin/tfmb-check" "$missing"
# tfmb-flow's solver options out of their range are usage errors (2), named, with nothing written
for bad in "--limiter-rise-iterations -1" "--ilu-partitions 0" "--initial-state quasi" \
  "--node-ordering diagonal" "--turbulence-step-limit whole" "--inflow-ramp-hold-mach -0.5" \
  "--second-order-cfl-start 0" "--turbulence-update-limit 0" "--multigrid-levels 0" \
  "--multigrid-levels 9" "--multigrid-post-smoother gauss-seidel" "--gmres-restart -1" \
  "--newton-cfl-follows-drop maybe" "--line-search-halvings -1" "--line-search-rise 0" \
  "--inner-limiter lagged" "--inner-linear-tolerance -1"; do
  rc=0
  # shellcheck disable=SC2086 # the option and its value are two words
  "$bin/tfmb-flow" "$missing" --p0 2e5 --T0 300 $bad -o "$out" > /dev/null 2> "$scratch/stderr" || rc=$?
  if [ "$rc" -ne 2 ] || ! grep -q -- "${bad%% *}" "$scratch/stderr" || [ -e "$out" ]; then
    echo "FAIL tfmb-flow $bad: exit $rc, expected 2 naming the option: $(head -c 300 "$scratch/stderr")"
    failed=1
  else
    echo "ok   tfmb-flow $bad refused"
  fi
done
# every workflow script answers --help with exit 0 and some text; those that take arguments
# refuse none with 2 (usage). install-deps, flow-benchmarks and default-bin do their work without
# arguments.
for script in "$src"/workflows/* "$src"/workflows/adapters/*; do
  [ -f "$script" ] && [ -x "$script" ] || continue
  name=${script#"$src"/workflows/}
  rc=0; "$script" --help > "$scratch/help" 2>&1 || rc=$?
  [ "$rc" -eq 0 ] && [ -s "$scratch/help" ] || { echo "FAIL workflows/$name --help: exit $rc"; failed=1; }
  case $name in install-deps | flow-benchmarks | default-bin) continue ;; esac
  rc=0; "$script" > /dev/null 2>&1 || rc=$?
  [ "$rc" -eq 2 ] || { echo "FAIL workflows/$name without arguments: exit $rc, expected 2"; failed=1; }
done
expect_missing "workflows/case-summary" "$src/workflows/case-summary" "$scratch/no-such-file.h5"
expect_missing "workflows/adapters/calculix-beam" "$src/workflows/adapters/calculix-beam" "$missing" -o "$out"
expect_missing "workflows/adapters/compare-structure" "$src/workflows/adapters/compare-structure" "$missing" "$missing"
expect_missing "workflows/compare-runs" "$src/workflows/compare-runs" "$missing" "$missing"
# a run folder with a space (and a non-ASCII letter) works: make splits names at spaces, so
# Makefile.cases reaches it through a link without them (make had split it and created a stray
# folder named after its first word); the model lands in the folder itself
rc=0; make -s -C "$src" -f Makefile.cases RUN="$scratch/two words é" BIN="$bin" \
  TFMB_LINKS="$scratch/links" model > "$scratch/make" 2>&1 || rc=$?
if [ "$rc" -ne 0 ] || [ -e "$scratch/two" ] || [ ! -s "$scratch/two words é/model.h5" ] ||
  ! grep -q "has spaces: reached through $scratch/links/" "$scratch/make"; then
  echo "FAIL RUN with a space: exit $rc: $(head -c 300 "$scratch/make")"; failed=1
else
  echo "ok   RUN with a space runs in its folder"
fi
# a quote in it is refused before anything runs, with one line
rc=0; make -s -C "$src" -f Makefile.cases RUN="$scratch/it's here" BIN="$bin" \
  TFMB_LINKS="$scratch/links" model > "$scratch/make" 2>&1 || rc=$?
if [ "$rc" -ne 2 ] || [ -e "$scratch/it's here" ] || ! grep -q "quote or a backslash" "$scratch/make"; then
  echo "FAIL RUN with a quote: exit $rc: $(head -c 300 "$scratch/make")"; failed=1
else
  echo "ok   RUN with a quote refused"
fi
[ $failed -eq 0 ] && echo "missing inputs: every tool exits 3" || echo "missing inputs: some tools do not"
exit $failed
