#!/usr/bin/python3
"""workflows/stage keeps all a stage prints: its stdout (the tables) and stderr both in the
stage's log, in the order they came, while its own stdout and stderr carry what the command
printed on each, unchanged; exit code and times.txt. With stderr on a terminal, the tools'
progress lines are drawn on one updating line there and thinned in the log.
  test_stage_log.py SOURCE_DIR SCRATCH"""
import os
import pty
import shutil
import subprocess
import sys

src, scratch = sys.argv[1], sys.argv[2]
stage = os.path.join(src, "workflows", "stage")
shutil.rmtree(scratch, ignore_errors=True)
os.makedirs(scratch)
os.chdir(scratch)

# A stage that prints a table on stdout between lines on stderr, a C program's way (stdio,
# which buffers a pipe fully unless told otherwise) and a Python script's way; the pauses make
# the order of the two streams a fact the log must keep.
tool = """
printf 'tool: reading\\n' >&2; sleep 0.2
printf 'flap      Fx [N]\\nupper_1   12.5\\n'; sleep 0.2
printf 'tool: wrote out.h5\\n' >&2; sleep 0.2
/usr/bin/python3 -c 'print("python table row")'; sleep 0.2
awk 'BEGIN { printf "awk row\\n"; system("sleep 0.3"); printf "tool: done\\n" > "/dev/stderr" }'
exit 3
"""
r = subprocess.run([stage, "demo", "logs", "bash", "-c", tool], capture_output=True, text=True)
assert r.returncode == 3, r
assert r.stdout == "flap      Fx [N]\nupper_1   12.5\npython table row\nawk row\n", repr(r.stdout)
assert r.stderr == "tool: reading\ntool: wrote out.h5\ntool: done\n", repr(r.stderr)
log = open("logs/demo.log").read()
assert log == ("tool: reading\nflap      Fx [N]\nupper_1   12.5\ntool: wrote out.h5\n"
               "python table row\nawk row\ntool: done\n"), repr(log)
times = open("logs/times.txt").read().split()
assert times[0] == "demo" and float(times[1]) > 0.5 and times[2] == "3", times

# A command that cannot be run: exit 127 with one line, in the log too.
r = subprocess.run([stage, "missing", "logs", "./no-such-tool"], capture_output=True, text=True)
assert r.returncode == 127 and "no-such-tool" in r.stderr, r
assert "no-such-tool" in open("logs/missing.log").read()

# stderr on a terminal, make running one job: progress lines are asked for every half second and
# drawn in place ('\r' ... erase to the end of the line), other lines above them; the log keeps
# every other line and one progress line per 10 s (here the first).
tool = """
echo "interval $TFMB_PROGRESS_INTERVAL"
for i in 1 2 3; do echo "tfmb-x: progress: solve $i/3 iterations, 10/s, ETA <= 1 s" >&2; sleep 0.1; done
echo "iter     3  res(rho) 1.0e-03" >&2
echo "tfmb-x: wrote out.h5" >&2
"""
leader, follower = pty.openpty()
env = {k: v for k, v in os.environ.items() if k not in ("MAKEFLAGS", "TFMB_PROGRESS_INTERVAL")}
child = subprocess.Popen([stage, "live", "logs", "bash", "-c", tool], stdout=subprocess.PIPE,
                         stderr=follower, env=env)
os.close(follower)
terminal = b""
while True:
    try:
        chunk = os.read(leader, 4096)
    except OSError:  # EIO once the last writer is gone
        break
    if not chunk:
        break
    terminal += chunk
out = child.stdout.read().decode()
assert child.wait() == 0
assert out == "interval 0.5\n", repr(out)
assert b"\rtfmb-x: progress: solve 3/3 iterations, 10/s, ETA <= 1 s\x1b[K" in terminal, terminal
assert b"\r\x1b[Kiter     3  res(rho) 1.0e-03\r\n" in terminal, terminal
assert terminal.endswith(b"\r\x1b[K"), terminal  # the progress line erased at the end
log = open("logs/live.log").read()
assert log == ("interval 0.5\ntfmb-x: progress: solve 1/3 iterations, 10/s, ETA <= 1 s\n"
               "iter     3  res(rho) 1.0e-03\ntfmb-x: wrote out.h5\n"), repr(log)
print("stage log tests passed")
