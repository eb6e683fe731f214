#!/usr/bin/env bash
# An installed tree runs a case on its own: `cmake --install` into a fresh prefix, then config1
# one-way with SMOKE=1 from <prefix>/share/tfmb/Makefile.cases, in a clean environment, from a
# folder outside the source tree, with the source and build trees hidden (an empty tmpfs over
# each, in a mount namespace of its own; where none can be made, the run goes ahead with them in
# place and only the path check below guards). Checks that the run completes with its summary,
# that no file it wrote (logs, provenance inside the .h5 files, summary.json) names the source or
# build tree, and that the installed tfmb-matmap and tfmb-heat default to the installed database.
#   test_install.sh SOURCE_DIR BUILD_DIR
set -uo pipefail
src=$(realpath "$1"); build=$(realpath "$2")
scratch=$(mktemp -d "${TMPDIR:-/tmp}/tfmb-install-test.XXXXXX") || exit 1
fail() { echo "FAIL: $* (kept: $scratch)" >&2; exit 1; }
case "$scratch/" in "$src/"* | "$build/"*) fail "scratch $scratch lies inside the trees it hides" ;; esac
prefix="$scratch/prefix"

cmake --install "$build" --prefix "$prefix" > "$scratch/install.log" 2>&1 ||
  { tail -20 "$scratch/install.log"; fail "cmake --install"; }
for f in bin/tfmb-flow bin/tfmb-matmap bin/tfmb-plot share/tfmb/Makefile.cases share/tfmb/tfmb-install.mk \
         share/tfmb/workflows/stage share/tfmb/workflows/tfmb-couple share/tfmb/cases/config1/case.mk \
         share/tfmb/data/materials-db.h5 share/tfmb/formats/flow.md share/tfmb/formats/python/tfmbfiles.py; do
  [ -e "$prefix/$f" ] || fail "not installed: $f"
done

# The run, as a person would start it from a folder of their own. Inside a private mount
# namespace the trees are covered first; the script below runs either way.
work="$scratch/work"; mkdir -p "$work" "$scratch/home"
cat > "$scratch/run.sh" <<EOF
set -eo pipefail
cd "$work"
for tool in matmap heat; do
  "$prefix/bin/tfmb-\$tool" --help > help-\$tool.txt
  grep -q -- "$prefix/share/tfmb/data/materials-db.h5" help-\$tool.txt ||
    { echo "installed tfmb-\$tool: default --db is not the installed database:"; grep -A1 -- --db help-\$tool.txt; exit 1; }
done
make -f "$prefix/share/tfmb/Makefile.cases" --no-print-directory CASE=config1 SMOKE=1 \
  RUN=runs/config1 BIN="$prefix/bin" oneway
EOF
hidden="no"
runner=(bash "$scratch/run.sh")
cover="mount -t tmpfs tmpfs '$src' && { [ '$build' = '$src' ] || case '$build/' in '$src/'*) true ;; *) mount -t tmpfs tmpfs '$build' ;; esac; } && ls -A '$src' | wc -l | grep -qx 0"
for namespace in "unshare --mount --propagation private" "unshare --user --map-root-user --mount"; do
  if $namespace sh -c "$cover" > /dev/null 2>&1; then
    runner=($namespace sh -c "$cover && exec bash '$scratch/run.sh'")
    hidden="yes"
    break
  fi
done
start=$(date +%s)
# TFMB_PROGRESS_INTERVAL=0: a progress line at every iteration, so that the logs show them.
env -i PATH=/usr/local/bin:/usr/bin:/bin HOME="$scratch/home" LANG=C.UTF-8 TFMB_PROGRESS_INTERVAL=0 "${runner[@]}" \
  > "$scratch/run.log" 2>&1 || { tail -40 "$scratch/run.log"; fail "the case from the installed tree"; }
echo "config1 SMOKE one-way from the installed tree: $(( $(date +%s) - start )) s (source tree hidden: $hidden)"

run="$work/runs/config1"
[ -s "$run/summary.json" ] || fail "no summary.json"
[ -s "$run/strain.h5" ] || fail "no strain.h5"
# The run's own record: every file, the .h5 files byte by byte (their provenance lists the input
# files and command lines), must name the installed tree, never the source or build tree.
for tree in "$src" "$build"; do
  named=$(grep -rlaF -- "$tree" "$run" "$scratch/run.log")
  [ -z "$named" ] || fail "these name $tree: $named"
done
grep -qaF -- "$prefix/share/tfmb/cases/simple-nozzle/case.toml" "$run/model.h5" ||
  fail "model.h5 does not name the installed case.toml"
"$prefix/bin/tfmb-check" --no-summary "$run"/*.h5 > /dev/null || fail "tfmb-check on the run's files"

# Each stage's log holds what it printed on stdout (the tables) as well as on stderr, and the
# progress lines; the flow's residual lines keep their form; its closing line gives the planar
# case's mass flow and thrust per metre of depth.
logs="$run/logs"
grep -q "^tfmb-loads forces (" "$logs/loads.log" || fail "logs/loads.log lacks the force table (stdout)"
grep -q "^worst total margin:" "$logs/strain.log" || fail "logs/strain.log lacks the margins (stdout)"
grep -q "^tfmb-strain: " "$logs/strain.log" || fail "logs/strain.log lacks the stderr lines"
grep -Eq "^tfmb-flow: progress: (steady solve|first-order start|second order) [0-9]+/[0-9]+ iterations, .*ETA <= " \
  "$logs/flow.log" || fail "logs/flow.log has no progress line"
grep -Eq "^iter +[0-9]+  res\(rho\) [0-9.e+-]+  drop " "$logs/flow.log" || fail "logs/flow.log: no residual line"
grep -Eq "^tfmb-flow: wrote .*mass flow [0-9.e+-]+ kg/\(s m\), thrust [0-9.e+-]+ N/m, " "$logs/flow.log" ||
  fail "logs/flow.log: closing line without kg/(s m) and N/m"
grep -Eq "^tfmb-beam: progress: static [0-9]+/[0-9]+ load steps" "$logs/beam.log" || fail "logs/beam.log has no progress line"
rm -rf "$scratch"
echo "install test passed"
