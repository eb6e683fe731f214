#!/usr/bin/env bash
# Settings are prerequisites (Makefile.cases, $(RUN)/.settings/<stage>.cmd): config1 one-way
# (SMOKE) run to the end; then nothing is out of date (make -q succeeds, make -n shows no stage);
# a changed variable reruns exactly the stages whose command it changes and what depends on them
# (make -n for SET/EXTRA_SET, FLOW_OPTS, FLOW_MODEL, BEAM_OPTS, STRAIN_OPTS, FLOW); a flow setting
# and a beam setting changed for real rerun those stages and leave the others' files untouched;
# unchanged settings afterwards rerun nothing, and going back to the earlier settings reruns again;
# a file dropped in after `make flowmesh` is taken; a folder without records reruns every stage.
#   test_settings_rerun.sh SOURCE_DIR RUN_DIR BIN_DIR
set -euo pipefail
src="$1"; run="$2"; bin="$3"
cd "$src"
rm -rf "$run" "$run".log*
fail() { echo "FAIL: $*" >&2; exit 1; }
mk() { make -f Makefile.cases --no-print-directory CASE=config1 SMOKE=1 RUN="$run" BIN="$bin" "$@"; }
# The stages `make -n` would run, in one line, sorted.
planned() { mk -n "$@" "$run/strain.h5" > "$run.plan" 2>&1 || true
  { grep -o 'workflows/stage [a-z-]*' "$run.plan" || true; } | cut -d' ' -f2 | sort | tr '\n' ' ' | sed 's/ $//'; }
expect() {  # expect "what" "stages expected (sorted)" make-arguments...
  local what="$1" want="$2"; shift 2
  local got; got=$(planned "$@")
  [ "$got" = "$want" ] || fail "$what: make -n plans [$got], expected [$want]"
  echo "ok: $what -> [$got]"
}
stamp() { for f in model flowmesh solidmesh flow thermal materials loads structure strain; do
  echo "$f $(stat -c %Y.%y "$run/$f.h5")"; done; }
changed() { { diff <(echo "$1") <(echo "$2") || true; } | sed -n 's/^> \([a-z]*\) .*/\1/p' | sort | tr '\n' ' ' | sed 's/ $//'; }

mk oneway > "$run.log" 2>&1 || { tail -30 "$run.log"; fail "first oneway run"; }
for n in input mesh-flow mesh-solid flow heat matmap loads beam strain; do
  [ -s "$run/.settings/$n.cmd" ] || fail "no settings record $run/.settings/$n.cmd"
done
grep -q -- "--max-iterations 300" "$run/.settings/flow.cmd" || fail "flow.cmd lacks the flow's options: $(cat "$run/.settings/flow.cmd")"

# A finished run: nothing to do.
mk -q "$run/strain.h5" || fail "make -q: a finished run is out of date"
mk -n "$run/strain.h5" > "$run.plan" 2>&1
! grep -v 'is up to date' "$run.plan" || fail "make -n on a finished run plans the above"
mk -n oneway > "$run.plan" 2>&1
! grep 'workflows/stage' "$run.plan" || fail "make -n oneway on a finished run plans the above"

all="beam flow heat input loads matmap mesh-flow mesh-solid strain"
after_flow="beam flow heat loads matmap strain"
expect "EXTRA_SET (case overrides)" "$all" EXTRA_SET="--set flow.stagnation_temperature=700"
expect "SET (replaces case.mk's)" "$all" SET="--set mesh.scale=4"
expect "FLOW_OPTS" "$after_flow" FLOW_OPTS="--threads 1"
expect "FLOW_MODEL" "$after_flow" FLOW_MODEL=sst
expect "FLOW (another flow tool)" "$after_flow" FLOW="$src/tests/workflows/analytic-flow"
expect "BEAM_OPTS" "beam strain" BEAM_OPTS=--dead-loads
expect "STRAIN_OPTS" "strain" STRAIN_OPTS=--quiet
expect "LOADS_OPTS" "beam loads strain" LOADS_OPTS="--method linear"
expect "BIN spelled relative to the same folder" "" BIN="$(realpath --relative-to=. "$bin")"
# make -n writes no record: the run is still up to date.
mk -q "$run/strain.h5" || fail "make -n changed a record"

# A flow setting for real: the flow and what follows it rerun, the model and meshes do not.
before=$(stamp); sleep 1
mk FLOW_MAX_ITERATIONS=250 "$run/strain.h5" > "$run.log2" 2>&1 || { tail -30 "$run.log2"; fail "rerun with a flow setting"; }
got=$(changed "$before" "$(stamp)")
[ "$got" = "flow loads materials strain structure thermal" ] || fail "FLOW_MAX_ITERATIONS=250 rewrote [$got]"
grep -q "settings: flow changed" "$run.log2" || fail "the rerun does not say which settings changed"
grep -q -- "--max-iterations 250" "$run/.settings/flow.cmd" || fail "flow.cmd not updated"
expect "the same flow setting again" "" FLOW_MAX_ITERATIONS=250
mk -q FLOW_MAX_ITERATIONS=250 "$run/strain.h5" || fail "make -q after the rerun"

# A beam-only setting for real: the beam and strain rerun, nothing before them.
before=$(stamp); sleep 1
mk FLOW_MAX_ITERATIONS=250 BEAM_OPTS=--dead-loads "$run/strain.h5" > "$run.log3" 2>&1 || { tail -30 "$run.log3"; fail "rerun with a beam setting"; }
got=$(changed "$before" "$(stamp)")
[ "$got" = "strain structure" ] || fail "BEAM_OPTS=--dead-loads rewrote [$got]"
expect "the same beam setting again" "" FLOW_MAX_ITERATIONS=250 BEAM_OPTS=--dead-loads

# Back to the case's own settings: the changed stages rerun (a record follows the command).
expect "back to the case's settings" "$after_flow"

# A file dropped in: `make flowmesh` in a new folder writes every stage's record, so another
# code's flow.h5 put there afterwards is newer than its record and taken (only what follows it
# is planned). A folder without any record (made before they existed) reruns every stage.
drop="$run-drop"; rm -rf "$drop"
mk RUN="$drop" "$drop/flowmesh.h5" > "$run.log4" 2>&1 || { tail -30 "$run.log4"; fail "make flowmesh in a new folder"; }
[ -s "$drop/.settings/flow.cmd" ] || fail "make flowmesh wrote no flow record"
cp "$run/flow.h5" "$drop/flow.h5"
got=$(mk -n RUN="$drop" "$drop/loads.h5" 2>&1 | { grep -o 'workflows/stage [a-z-]*' || true; } | cut -d' ' -f2 | tr '\n' ' ' | sed 's/ $//')
[ "$got" = "loads" ] || fail "a flow.h5 dropped in: make -n plans [$got], expected [loads]"
echo "ok: a dropped-in flow.h5 is taken"
rm -r "$run/.settings"
expect "a folder without records" "$all" FLOW_MAX_ITERATIONS=250 BEAM_OPTS=--dead-loads
echo "settings rerun test passed"
