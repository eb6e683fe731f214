#!/usr/bin/env bash
# One run at a time in a run folder (Makefile.cases, workflows/run-lock). The model stage of
# config1 (SMOKE) is made slow by a stand-in (INPUT=slow-input: sleeps, then runs tfmb-input) so
# that two makes really overlap:
#  1. two makes started at once: one runs, the other is refused at once with one line naming the
#     run that holds the folder; model.h5 is whole and made once;
#  2. `clean` meanwhile is refused too; RUN_LOCK=wait: the second waits, says so, and then finds
#     the model up to date;
#  3. a run killed with kill -9 (the whole run: make, stage, tool) leaves its .run.lock behind,
#     which does not block the next run;
#  4. the makes of a run killed with kill -9 while its stage still runs: the folder stays locked
#     while that stage is alive (it may still write) and is free once it ends.
set -uo pipefail
src="$1"; scratch="$2"; bin="$3"
rm -rf "$scratch"; mkdir -p "$scratch"
run="$scratch/run"
fail() { echo "FAIL: $*" >&2; exit 1; }
# A failure leaves no make of this test running into the next run of the test.
trap 'kill -- $(jobs -p) 2> /dev/null' EXIT

cat > "$scratch/slow-input" <<EOF
#!/usr/bin/env bash
sleep "\${SLOW_SECONDS:-3}"
exec "$bin/tfmb-input" "\$@"
EOF
chmod +x "$scratch/slow-input"

mk() {
  make -f "$src/Makefile.cases" --no-print-directory CASE=config1 SMOKE=1 RUN="$run" BIN="$bin" \
    INPUT="$scratch/slow-input" "$@"
}
# Until the run folder's lock is held by a make of the model (at most 30 s): its holder writes
# that into the lock file once it has the lock. (Probing with flock would take the lock for a
# moment and could make the run being waited for refuse.)
wait_held() {
  for _ in $(seq 300); do
    grep -qs "make CASE=config1 model" "$run/.run.lock" && return 0
    sleep 0.1
  done
  fail "the first run never took the lock"
}
stage_runs() { grep -c '^input ' "$run/logs/times.txt" 2>/dev/null || echo 0; }
check_model() {
  [ -s "$run/model.h5" ] || fail "$1: no model.h5"
  "$bin/tfmb-check" --no-summary "$run/model.h5" || fail "$1: model.h5 does not pass tfmb-check"
  ls "$run"/*.tmp > /dev/null 2>&1 && fail "$1: a .tmp file was left: $(ls "$run"/*.tmp)"
  return 0
}

# 1. Two makes at once.
# (the stand-in holds the folder 6 s: the later make must find it held even on a busy machine)
SLOW_SECONDS=6 mk model > "$scratch/a.log" 2>&1 & a=$!
SLOW_SECONDS=6 mk model > "$scratch/b.log" 2>&1 & b=$!
rc_a=0; wait $a || rc_a=$?
rc_b=0; wait $b || rc_b=$?
if [ $rc_a -eq 0 ] && [ $rc_b -ne 0 ]; then refused="$scratch/b.log"
elif [ $rc_b -eq 0 ] && [ $rc_a -ne 0 ]; then refused="$scratch/a.log"
else cat "$scratch/a.log" "$scratch/b.log"; fail "1: exit codes $rc_a and $rc_b: expected one run and one refusal"; fi
grep -q "is in use by another run (pid [0-9]* on .*make CASE=config1 model)" "$refused" ||
  { cat "$refused"; fail "1: the refusal does not name the run that holds the folder"; }
grep -q "Error 75" "$refused" || { cat "$refused"; fail "1: run-lock did not exit 75"; }
[ "$(grep -c 'run-lock:' "$refused")" -eq 1 ] || { cat "$refused"; fail "1: more than one line from run-lock"; }
grep -q "stage input" "$refused" && fail "1: the refused run ran a stage"
check_model 1
[ "$(stage_runs)" -eq 1 ] || fail "1: the input stage ran $(stage_runs) times"
echo "1. two runs at once: one ran, the other was refused: $(grep 'run-lock:' "$refused" | cut -c1-160)"

# 2. RUN_LOCK=wait.
mk clean > /dev/null 2>&1 || fail "2: clean"
[ -e "$run/model.h5" ] && fail "2: clean left model.h5"
SLOW_SECONDS=3 mk model > "$scratch/a.log" 2>&1 & a=$!
wait_held
# clean is a run in the folder too: refused while the model is being made
mk clean > "$scratch/clean.log" 2>&1 && fail "2: clean ran while the folder was in use"
grep -q "is in use by another run" "$scratch/clean.log" || { cat "$scratch/clean.log"; fail "2: clean"; }
grep -qs "make CASE=config1 model" "$run/.run.lock" || fail "2: the refused clean removed the run folder"
start=$(date +%s%N)
SLOW_SECONDS=3 mk RUN_LOCK=wait model > "$scratch/b.log" 2>&1 || { cat "$scratch/b.log"; fail "2: the waiting run failed"; }
waited=$(( ($(date +%s%N) - start) / 1000000 ))
wait $a || { cat "$scratch/a.log"; fail "2: the first run failed"; }
grep -q "waiting for it to end" "$scratch/b.log" || { cat "$scratch/b.log"; fail "2: the waiting run did not say so"; }
check_model 2
[ "$(stage_runs)" -eq 1 ] || fail "2: the input stage ran $(stage_runs) times (the waiting run redid it)"
echo "2. clean refused meanwhile; RUN_LOCK=wait: the second run waited ${waited} ms and found the model up to date"

# 3. The whole run killed with kill -9: the lock file stays and locks nothing.
mk clean > /dev/null 2>&1 || fail "3: clean"
SLOW_SECONDS=600 setsid make -f "$src/Makefile.cases" --no-print-directory \
  CASE=config1 SMOKE=1 RUN="$run" BIN="$bin" INPUT="$scratch/slow-input" model > "$scratch/a.log" 2>&1 & a=$!
disown $a  # killed on purpose: no job notice
wait_held
kill -9 -- -$a
for _ in $(seq 50); do pgrep -g $a > /dev/null || break; sleep 0.1; done
pgrep -g $a > /dev/null && fail "3: the killed run's processes are still alive"
[ -e "$run/.run.lock" ] || fail "3: expected the killed run's .run.lock left behind"
[ -e "$run/model.h5" ] && fail "3: the killed run left a model.h5"
start=$(date +%s%N)
SLOW_SECONDS=0 timeout 60 make -f "$src/Makefile.cases" --no-print-directory CASE=config1 SMOKE=1 \
  RUN="$run" BIN="$bin" INPUT="$scratch/slow-input" model > "$scratch/b.log" 2>&1 ||
  { cat "$scratch/b.log"; fail "3: the run after a kill -9 did not run"; }
check_model 3
echo "3. kill -9 of a whole run: the next run ran at once ($(( ($(date +%s%N) - start) / 1000000 )) ms)"

# 4. Only the makes killed: the stage they started still holds the folder until it ends.
mk clean > /dev/null 2>&1 || fail "4: clean"
SLOW_SECONDS=600 setsid make -f "$src/Makefile.cases" --no-print-directory \
  CASE=config1 SMOKE=1 RUN="$run" BIN="$bin" INPUT="$scratch/slow-input" model > "$scratch/a.log" 2>&1 & a=$!
disown $a
wait_held
# (the make starts the stage just after it takes the lock; on a loaded machine that can take seconds)
for _ in $(seq 600); do pgrep -g $a -f workflows/stage > /dev/null && break; sleep 0.1; done
pgrep -g $a -f workflows/stage > /dev/null || { kill -9 -- -$a; fail "4: the run's stage never started (60 s)"; }
makes=$(pgrep -g $a -x make) || fail "4: no make in the run"
kill -9 $makes
for _ in $(seq 50); do pgrep -g $a -x make > /dev/null || break; sleep 0.1; done
pgrep -g $a -f workflows/stage > /dev/null || fail "4: the stage did not outlive its makes"
mk model > "$scratch/b.log" 2>&1 && { kill -9 -- -$a; fail "4: a run started while the killed run's stage was alive"; }
grep -q "is in use by another run" "$scratch/b.log" || { kill -9 -- -$a; cat "$scratch/b.log"; fail "4: no refusal"; }
kill -9 -- -$a
for _ in $(seq 50); do pgrep -g $a > /dev/null || break; sleep 0.1; done
SLOW_SECONDS=0 timeout 60 make -f "$src/Makefile.cases" --no-print-directory CASE=config1 SMOKE=1 \
  RUN="$run" BIN="$bin" INPUT="$scratch/slow-input" model > "$scratch/b.log" 2>&1 ||
  { cat "$scratch/b.log"; fail "4: the run after the stage ended did not run"; }
check_model 4
echo "4. makes killed, stage alive: refused; stage gone: ran"
echo "run lock test passed"
