#!/usr/bin/env bash
# A two-way run killed anywhere resumes with `make twoway` to the result of an uninterrupted run,
# and a finished run is left as it is (issue 23).
#
# config4 (SMOKE, tfmb-flow, coupling tolerance 1e-2: three coupling iterations) is run once
# uninterrupted as the reference. Then the run is killed (SIGKILL to make's whole process group,
# tests/workflows/interrupt-at as STAGE, COUPLE and PLOT) at named points of iterations 1 and 2,
# in the order the reference ran their stages (flow, loads, heat, matmap, beam, loads-displace,
# strain, the coupling step; iteration 2 begins with mesh-deform), and at the start and the end
# of the report, and resumed with `make twoway`; the result must equal the reference's
# (tests/workflows/same-twoway-result: every dataset of every iterate bit for bit, coupling.csv
# and coupling-state.npz, summary.json, the pictures; no .tmp file left). Then `make twoway` on
# the finished run must run nothing and change no file (coupling.csv and summary.json byte for
# byte, every file's modification time), and with a strain option changed must rerun the strain
# stages and the coupling steps and no flow, to the same result.
#
#   test_twoway_resume.sh SOURCE_DIR SCRATCH_DIR BIN_DIR [chain|each [POINT...]]
#
# chain (default, ctest workflows.twoway_resume): one run killed in turn at the end of every
#   stage of iterations 1 and 2 (a kill at the start of a stage would find the same files), while
#   their flow runs, at the start of iteration 2's first stage and at the start and end of the
#   report (20 kills),
#   each kill resumed by the next `make twoway`, the last one to the end; 327 s measured by
#   ctest on 2 cores under a load average of 10-11 (78 s of CPU).
# each (Makefile.cases twoway-interruptions): for every point, at the start and at the end of
#   every stage (32), or for the POINTs given (e.g. iter-002/couple:end), a fresh run killed
#   there and resumed, each compared with the reference.
set -uo pipefail
src="$1"; scratch="$2"; bin="$3"; mode="${4:-chain}"; shift 4 2> /dev/null || shift $#
case "$mode" in chain|each) ;; *) echo "usage: test_twoway_resume.sh SOURCE_DIR SCRATCH_DIR BIN_DIR [chain|each [POINT...]]" >&2; exit 2;; esac
rm -rf "$scratch"; mkdir -p "$scratch"
run="$scratch/run"; ref="$scratch/reference"
fail() { echo "FAIL: $*" >&2; exit 1; }
trap 'kill -- $(jobs -p) 2> /dev/null' EXIT
started=$(date +%s)

# Every run of the test in the same folder with the same settings: the stages' records and
# provenance name the run folder, and the wrapper is the stage command of every run.
make_args=(-f "$src/Makefile.cases" --no-print-directory CASE=config4 SMOKE=1 RUN="$run" BIN="$bin"
  COUPLE_OPTS="--tolerance 1e-2 --max-iterations 4"
  STAGE="$src/tests/workflows/interrupt-at" COUPLE="$src/tests/workflows/interrupt-at"
  PLOT="$src/tests/workflows/interrupt-at --plot $bin/tfmb-plot")
mk() { make "${make_args[@]}" "$@"; }
# A run killed at $1: its make in a process group of its own, killed whole by interrupt-at.
killed_at() {
  local point="$1" log="$scratch/killed.log"
  TFMB_INTERRUPT_AT="$point" setsid make "${make_args[@]}" twoway > "$log" 2>&1 & local pid=$!
  local rc=0; { wait $pid; } 2> /dev/null || rc=$?  # (without bash's "Killed" line)
  for _ in $(seq 50); do pgrep -g $pid > /dev/null || break; sleep 0.1; done
  pgrep -g $pid > /dev/null && fail "$point: processes of the killed run still alive"
  grep -q "interrupt-at: killing the run at $point" "$log" ||
    { tail -20 "$log"; fail "$point: the run was not killed there (exit $rc): the point was never reached"; }
  [ $rc -ne 0 ] || fail "$point: the killed run exited 0"
}
resume() {  # resume WHAT [VARIABLE=VALUE...]
  local what="$1"; shift
  mk "$@" twoway > "$scratch/resume.log" 2>&1 || { tail -30 "$scratch/resume.log"; fail "$what: the resumed make twoway failed"; }
}
same() {
  "$src/tests/workflows/same-twoway-result" "$ref" "$run" > "$scratch/same.log" 2>&1 ||
    { head -30 "$scratch/same.log"; fail "$1: the result differs from the uninterrupted run's"; }
}

# The reference: uninterrupted.
t0=$(date +%s)
mk twoway > "$scratch/reference.log" 2>&1 || { tail -30 "$scratch/reference.log"; fail "the uninterrupted run"; }
[ "$(basename "$(cat "$run/last-iteration")")" = iter-003 ] || fail "the reference took $(cat "$run/last-iteration"), expected 3 iterations"
mv "$run" "$ref"
echo "reference: 3 coupling iterations in $(( $(date +%s) - t0 )) s"

# The kill points, in the order the reference ran its stages.
points=("$@")
if [ ${#points[@]} -eq 0 ]; then
  for k in 001 002; do
    for s in $(cut -d' ' -f1 "$ref/iter-$k/times.txt") couple; do
      # chain: a kill at the start of a stage finds the files a kill at the end of the stage
      # before it left; only iteration 2's first stage (after iteration 1's coupling.status
      # and last-iteration were written) is killed at its start too.
      [ "$mode" = chain ] && [ "iter-$k/$s" != iter-002/mesh-deform ] || points+=("iter-$k/$s:start")
      # (and the flow killed while it runs)
      [ "$mode" = chain ] && [ "$s" = flow ] && points+=("iter-$k/$s:during")
      points+=("iter-$k/$s:end")
    done
  done
  points+=("plot/report:start" "plot/report:end")
fi
echo "${#points[@]} kill points: ${points[*]}"

if [ "$mode" = chain ]; then
  t0=$(date +%s)
  for point in "${points[@]}"; do killed_at "$point"; done
  resume "after the last kill"
  same "killed at ${#points[@]} points in turn"
  echo "chain: killed at ${#points[@]} points in turn and resumed: same result as uninterrupted ($(( $(date +%s) - t0 )) s)"
else
  for point in "${points[@]}"; do
    t0=$(date +%s)
    rm -rf "$run"
    killed_at "$point"
    resume "$point"
    same "$point"
    echo "each: killed at $point, resumed: same result ($(( $(date +%s) - t0 )) s)"
  done
fi

# A finished run: nothing rerun, no file changed.
# (.run.lock aside: every run writes who holds the folder into it, workflows/run-lock; folders
# aside: a file made and removed again, e.g. summary.json.tmp, touches its folder)
snapshot() { (cd "$run" && find . -path ./.run.lock -prune -o ! -type d -printf '%p %T@ %s %l\n' | sort); }
before=$(snapshot); csv=$(md5sum < "$run/coupling.csv"); summary=$(md5sum < "$run/summary.json")
t0=$(date +%s%N)
resume "make twoway on the finished run"
ms=$(( ($(date +%s%N) - t0) / 1000000 ))
grep -q "workflows/stage\|interrupt-at [a-z]" "$scratch/resume.log" && { cat "$scratch/resume.log"; fail "the finished run ran a stage"; }
[ "$(md5sum < "$run/coupling.csv")" = "$csv" ] || fail "make twoway rewrote a finished run's coupling.csv"
[ "$(md5sum < "$run/summary.json")" = "$summary" ] || fail "make twoway rewrote a finished run's summary.json"
diff <(echo "$before") <(snapshot) > "$scratch/changed.txt" || { cat "$scratch/changed.txt"; fail "make twoway on the finished run changed the files above"; }
echo "finished run: make twoway ran nothing and changed no file ($ms ms)"

# A strain option changed in the finished run: the strain stages and the coupling steps rerun,
# each giving the same next displacement, which tfmb-couple leaves as it was: no flow reruns.
resume "make twoway with STRAIN_OPTS changed" STRAIN_OPTS=--quiet
stages=$(grep -o 'interrupt-at [a-z-]* [^ ]*/iter-[0-9]*' "$scratch/resume.log" | awk '{print $2}' | sort | uniq -c | tr -s ' ' | tr '\n' ';')
[ "$stages" = " 3 strain;" ] || fail "STRAIN_OPTS changed: expected the three strain stages alone to rerun, ran [$stages]"
same "STRAIN_OPTS changed"
echo "strain option changed: the three strain stages and coupling steps reran, no flow; same result"
echo "two-way resume test passed ($(( $(date +%s) - started )) s)"
