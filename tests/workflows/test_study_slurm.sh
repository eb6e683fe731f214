#!/usr/bin/env bash
# workflows/study through the Slurm profile (workflows/slurm) on a real Slurm: a single-node
# cluster started here (munged, slurmctld and slurmd on localhost, as root, every file and socket
# in a fresh folder, free ports), a two-point study (config1 one-way, SMOKE, NPR 4 and 6) run with
# --profile; every point went through sbatch (the job-completion log names both jobs, completed,
# and each has its Slurm output file), the table holds both points with the thrust higher at the
# higher NPR; then the daemons started here are stopped (also on failure or interrupt).
# Skips (exit 77, saying why) only where Slurm cannot start: not root, Slurm or munge not
# installed and not installable, or the daemons do not come up.
#   test_study_slurm.sh SOURCE_DIR SCRATCH_DIR BIN_DIR
set -euo pipefail
src=$(cd "$1" && pwd) scratch=$2 bin=$(cd "$3" && pwd)
skip() { echo "SKIP: $*"; exit 77; }
fail() { echo "FAIL: $*" >&2; exit 1; }

[ "$(id -u)" -eq 0 ] || skip "a single-node Slurm runs its daemons as root; not root"
if ! command -v slurmctld > /dev/null || ! command -v slurmd > /dev/null || ! command -v munged > /dev/null \
   || ! command -v sbatch > /dev/null; then
  echo "test_study_slurm: installing slurm-wlm and munge (workflows/install-deps lists them)" >&2
  DEBIAN_FRONTEND=noninteractive timeout 600 apt-get install -y -qq --no-install-recommends \
    -o DPkg::Lock::Timeout=300 slurm-wlm munge > /dev/null 2>&1 \
    || skip "slurm-wlm and munge are not installed and could not be installed (apt-get install slurm-wlm munge)"
fi
command -v snakemake > /dev/null || fail "snakemake is not installed (workflows/install-deps installs it)"

mkdir -p "$scratch"
d=$(mktemp -d "$scratch/slurm.XXXXXX")
pids=()      # the daemons started here, in order
study_pid=  # a study run under way
watcher=    # the watcher that stops the daemons should this script be killed outright
# Cancel the jobs left on our own controller (SLURM_CONF: nobody else's) and give the node 30 s
# to end them, then stop the daemons started here, the last started first, and any job step
# daemon of this cluster still there (a slurmstepd whose environment names our slurm.conf).
stop_cluster() {
  if [ -f "$d/slurm.conf" ] && [ $# -gt 0 ]; then
    local jobs
    jobs=$(SLURM_CONF=$d/slurm.conf timeout 20 squeue --noheader --format=%i 2>/dev/null || true)
    if [ -n "$jobs" ]; then
      SLURM_CONF=$d/slurm.conf timeout 20 scancel $jobs 2>/dev/null || true
      for _ in $(seq 30); do
        [ -z "$(SLURM_CONF=$d/slurm.conf timeout 10 squeue --noheader --states=PENDING,RUNNING,COMPLETING --format=%i 2>/dev/null)" ] && break
        sleep 1
      done
    fi
  fi
  local all=("$@") i pid
  for ((i = ${#all[@]} - 1; i >= 0; i--)); do kill "${all[i]}" 2>/dev/null || true; done
  for pid in "$@"; do
    for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.2; done
    kill -9 "$pid" 2>/dev/null || true
  done
  for pid in $(pgrep -x slurmstepd || true); do
    if tr '\0' '\n' < "/proc/$pid/environ" 2>/dev/null | grep -qx "SLURM_CONF=$d/slurm.conf"; then
      kill -9 "$pid" 2>/dev/null || true
    fi
  done
}
stop_study() {  # stop_study PID: TERM (the study stops snakemake, which cancels its jobs), then KILL
  kill "$1" 2>/dev/null || true
  for _ in $(seq 60); do kill -0 "$1" 2>/dev/null || break; sleep 0.5; done
  kill -9 "$1" 2>/dev/null || true
}
cleanup() {
  local rc=$?
  [ -z "$watcher" ] || kill "$watcher" 2>/dev/null || true
  # A study under way first, while the controller still runs to cancel its jobs.
  [ -z "$study_pid" ] || stop_study "$study_pid"
  stop_cluster "${pids[@]}"
  if [ $rc -ne 0 ] && [ $rc -ne 77 ]; then
    for log in slurmctld slurmd munged; do
      [ -f "$d/$log.log" ] && { echo "--- $d/$log.log (end)"; tail -15 "$d/$log.log"; }
    done
  fi
  exit $rc
}
trap cleanup EXIT
trap 'exit 130' INT TERM

# Two free TCP ports on localhost (the controller's and the node daemon's).
read -r ctl_port node_port < <(/usr/bin/python3 -c '
import socket
s = [socket.socket() for _ in range(2)]
for x in s: x.bind(("127.0.0.1", 0))
print(*[x.getsockname()[1] for x in s])')
host=$(hostname -s)
cpus=$(nproc)
mem=$(awk '/MemTotal/ {print int($2 / 1024 / 2)}' /proc/meminfo)

# munge: a key of our own and a socket in the folder, so a munged of the machine is not touched.
mkdir -p "$d/state" "$d/spool"
dd if=/dev/urandom of="$d/munge.key" bs=1024 count=1 status=none
chmod 400 "$d/munge.key"
chmod 700 "$d"
munged --foreground --force --socket="$d/munge.sock" --key-file="$d/munge.key" \
  --pid-file="$d/munged.pid" --log-file="$d/munged.log" --seed-file="$d/munged.seed" 2>> "$d/munged.log" &
pids+=($!)

cat > "$d/slurm.conf" <<EOF
ClusterName=tfmbtest
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$ctl_port
SlurmdPort=$node_port
AuthType=auth/munge
AuthInfo=socket=$d/munge.sock
CredType=cred/munge
SlurmUser=root
SlurmdUser=root
StateSaveLocation=$d/state
SlurmdSpoolDir=$d/spool
SlurmctldPidFile=$d/slurmctld.pid
SlurmdPidFile=$d/slurmd.pid
SlurmctldLogFile=$d/slurmctld.log
SlurmdLogFile=$d/slurmd.log
PlugStackConfig=$d/plugstack.conf
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/filetxt
JobCompLoc=$d/jobcomp.log
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
MpiDefault=none
ReturnToService=2
SlurmctldTimeout=60
SlurmdTimeout=60
MinJobAge=600
NodeName=tfmbnode NodeAddr=127.0.0.1 NodeHostname=$host CPUs=$cpus RealMemory=$mem State=UNKNOWN
PartitionName=tfmb Nodes=tfmbnode Default=YES MaxTime=INFINITE State=UP
EOF
: > "$d/plugstack.conf"
export SLURM_CONF=$d/slurm.conf
for _ in $(seq 50); do [ -S "$d/munge.sock" ] && break; sleep 0.2; done
[ -S "$d/munge.sock" ] || skip "munged did not start ($(tail -1 "$d/munged.log" 2>/dev/null))"
slurmctld -D -i > "$d/slurmctld.out" 2>&1 &
pids+=($!)
slurmd -D -N tfmbnode > "$d/slurmd.out" 2>&1 &
pids+=($!)
state=
for _ in $(seq 60); do
  state=$(timeout 10 sinfo --noheader --nodes=tfmbnode --format=%T 2>/dev/null | head -n1 || true)
  case $state in idle*) break ;; esac
  sleep 1
done
case $state in
  idle*) ;;
  *) skip "the single-node Slurm did not come up in 60 s (node state '${state:-none}'; logs in $d)" ;;
esac
# Should this script be killed outright (a ctest timeout may send SIGKILL), a watcher stops a
# study under way (its pid in $d/study.pid) and the daemons once it is gone.
( while kill -0 $$ 2>/dev/null; do sleep 2; done
  [ ! -s "$d/study.pid" ] || stop_study "$(cat "$d/study.pid")"
  stop_cluster "${pids[@]}" ) > /dev/null 2>&1 &
watcher=$!
echo "ok: Slurm up (controller port $ctl_port, node port $node_port, $cpus CPUs, folder $d)"

# The study: two points, one CPU each (both run at once on the node).
cat > "$d/study.toml" <<'EOF'
[study]
case = "config1"
goal = "oneway"
threads = 1
mem_mb = 1000
runtime_minutes = 10
[settings]
SMOKE = 1
[parameters.npr]
set = "flow.nozzle_pressure_ratio"
values = [4.0, 6.0]
EOF
start=$(date +%s)
# In the background with wait, so that a signal to this script stops it at once (cleanup).
rc=0
timeout 900 "$src/workflows/study" run "$d/study.toml" --dir "$d/study" --bin "$bin" \
  --profile "$src/workflows/slurm" > "$d/study.log" 2>&1 &
study_pid=$!
echo $study_pid > "$d/study.pid"
wait $study_pid || rc=$?
study_pid=
rm -f "$d/study.pid"
[ $rc -eq 0 ] || { tail -40 "$d/study.log"; fail "study run --profile workflows/slurm: exit $rc"; }
echo "ok: study through Slurm in $(( $(date +%s) - start )) s"

# Both points went through sbatch: snakemake took their Slurm job ids, the job-completion log
# has both jobs completed under their rule names, and each wrote its Slurm output file.
for rule in p001 p002; do
  id=
  for j in $(sed -n "s/.*Submitted job .* with external jobid '\([0-9]*\)'.*/\1/p" "$d/study.log"); do
    if grep -q "^JobId=$j .*Name=tfmb-$rule " "$d/jobcomp.log"; then id=$j; fi
  done
  [ -n "$id" ] || fail "no Slurm job of rule $rule in the job-completion log $d/jobcomp.log"
  grep "JobId=$id " "$d/jobcomp.log" | grep -q "JobState=COMPLETED" || fail "Slurm job $id ($rule) did not complete: $(grep "JobId=$id " "$d/jobcomp.log")"
  [ -f "$d/study/slurm-logs/$rule-$id.out" ] || fail "no Slurm output $d/study/slurm-logs/$rule-$id.out"
  echo "ok: $rule ran as Slurm job $id (COMPLETED)"
done
# The table is complete.
/usr/bin/python3 - "$d/study/results.csv" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
assert len(rows) == 2, f"{sys.argv[1]}: {len(rows)} rows, expected 2"
for r in rows:
    for column in ("discharge_coefficient", "thrust_ratio", "thrust_x", "max_displacement", "worst_total_margin"):
        assert r[column] != "", f"{sys.argv[1]}: point {r['point']}: no {column}"
low, high = sorted(rows, key=lambda r: float(r["npr"]))
assert float(high["thrust_x"]) > float(low["thrust_x"]), f"thrust at NPR {high['npr']} not above NPR {low['npr']}"
print(f"ok: results.csv: thrust {float(low['thrust_x']):.5g} N/m at NPR {low['npr']}, "
      f"{float(high['thrust_x']):.5g} N/m at NPR {high['npr']}")
PY

# A point that fails (NPR 0.5: tfmb-input refuses it at once) is a failed Slurm job: the status
# script says so, the study exits 1 and the table marks the point failed.
sed -e 's/values = \[4.0, 6.0\]/values = [0.5]/' "$d/study.toml" > "$d/failing.toml"
rc=0
timeout 300 "$src/workflows/study" run "$d/failing.toml" --dir "$d/failing" --bin "$bin" \
  --profile "$src/workflows/slurm" > "$d/failing.log" 2>&1 &
study_pid=$!
echo $study_pid > "$d/study.pid"
wait $study_pid || rc=$?
study_pid=
rm -f "$d/study.pid"
[ $rc -eq 1 ] || { tail -30 "$d/failing.log"; fail "a failing point: study exited $rc, expected 1"; }
grep -q "^JobId=.*Name=tfmb-p001 JobState=FAILED" "$d/jobcomp.log" || fail "the failing point is no FAILED Slurm job in $d/jobcomp.log"
grep -q "^p001_npr-0.5,0.5,failed or unfinished (see logs/p001_npr-0.5.log)," "$d/failing/results.csv" \
  || fail "the failing point is not marked failed in $d/failing/results.csv"
echo "ok: a failing point fails its Slurm job and the study (exit 1), its row marked failed"
