#!/usr/bin/python3
"""A write that fails (a full disk, a file-size limit) ends a tool with exit 4 and one line naming
the file and the system's reason, leaves neither the file nor its temporary, and never crashes
(issue 23: the HDF5 library's clean-up at exit crashed after a failed write).

Every kind's example (`tfmb-check --example KIND -o FILE`) is written
  - under a file-size limit (RLIMIT_FSIZE, SIGXFSZ ignored: write() fails with EFBIG) of 0 bytes,
    4 KiB and one byte less than the file: runs anywhere;
  - on a 64 KiB tmpfs nearly filled beforehand (write() fails with ENOSPC), in a mount namespace
    of its own (`unshare`): skipped, saying so, where namespaces or mounts are not permitted.

  test_write_failure.py BIN_DIR SCRATCH_DIR
"""
import os
import resource
import shutil
import signal
import subprocess
import sys

bin_dir, scratch = sys.argv[1], os.path.abspath(sys.argv[2])
check = os.path.join(bin_dir, "tfmb-check")
shutil.rmtree(scratch, ignore_errors=True)
os.makedirs(scratch)
failures = []


def judge(label, done, output, reason):
    """Failure texts of one run that had to fail writing `output` for `reason`."""
    problems = []
    lines = done.stderr.strip().splitlines()
    if done.returncode != 4:
        what = (f"signal {signal.Signals(-done.returncode).name}" if done.returncode < 0
                else f"exit {done.returncode}")
        problems.append(f"{what}, expected 4")
    if len(lines) != 1 or os.path.basename(output) not in lines[0] or reason not in lines[0]:
        problems.append(f"expected one line naming {os.path.basename(output)} and '{reason}'")
    left = [f for f in (output, output + ".tmp") if os.path.exists(f)]
    if left:
        problems.append("left " + ", ".join(os.path.basename(f) for f in left))
    for p in problems:
        failures.append(f"{label}: {p}: {done.stderr.strip()[-300:]}")
        print(f"FAIL {label}: {p}: {done.stderr.strip()[-300:]}")
    if not problems:
        print(f"ok   {label}: {lines[0]}")


kinds = [line.split()[0] for line in
         subprocess.run([check, "--list"], capture_output=True, text=True, check=True)
         .stdout.splitlines() if line.strip()]
sizes = {}
for kind in kinds:
    path = os.path.join(scratch, f"{kind}.h5")
    subprocess.run([check, "--example", kind, "-o", path], check=True)
    sizes[kind] = os.path.getsize(path)
    for f in os.listdir(scratch):
        os.remove(os.path.join(scratch, f))


def limited(limit):
    def set_limit():
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)  # write() fails with EFBIG instead
        resource.setrlimit(resource.RLIMIT_FSIZE, (limit, limit))
    return set_limit


for kind in kinds:
    for limit in (0, 4096, sizes[kind] - 1):
        output = os.path.join(scratch, f"{kind}-{limit}.h5")
        done = subprocess.run([check, "--example", kind, "-o", output], capture_output=True,
                              text=True, preexec_fn=limited(limit))
        judge(f"{kind} under a {limit}-byte file-size limit", done, output, "File too large")

# A real full disk, where a private mount namespace can be had: as an unprivileged user with a
# user namespace, or as root.
script = r"""
mount -t tmpfs -o size=64k tmpfs "$1" || exit 125
head -c $((64 * 1024 - $2)) /dev/zero > "$1/fill"
disk=$1 report=$3
shift 3
"$@" 2> "$report/stderr"
echo $? > "$report/code"
ls "$disk" > "$report/left"
"""
mount_point = os.path.join(scratch, "small")
os.makedirs(mount_point)
namespace = None
for prefix in (["unshare", "--user", "--map-root-user", "--mount"], ["unshare", "--mount"]):
    if shutil.which("unshare") and subprocess.run(
            prefix + ["sh", "-c", f"mount -t tmpfs -o size=64k tmpfs {mount_point}"],
            capture_output=True).returncode == 0:
        namespace = prefix
        break
if namespace is None:
    print("skipped: no mount namespace with a tmpfs can be made here (unshare/mount not "
          "permitted); the file-size limit runs above cover the same write failures")
else:
    for kind in ("flow", "structure", "model"):
        for free in (0, 8 * 1024):
            output = os.path.join(mount_point, f"{kind}.h5")
            report = os.path.join(scratch, "report")
            shutil.rmtree(report, ignore_errors=True)
            os.makedirs(report)
            subprocess.run(namespace + ["sh", "-c", script, "sh", mount_point, str(free), report,
                                        check, "--example", kind, "-o", output])
            with open(os.path.join(report, "code")) as f:
                code = int(f.read())
            if code > 128:  # the shell's way of saying "killed by signal code - 128"
                code = -(code - 128)
            with open(os.path.join(report, "stderr")) as f:
                done = subprocess.CompletedProcess([], code, "", f.read())
            with open(os.path.join(report, "left")) as f:
                left = [name for name in f.read().split() if name != "fill"]
            # The tmpfs went with the namespace: what the tool left there was listed by `ls`.
            judge(f"{kind} on a 64 KiB tmpfs with {free // 1024} KiB free", done,
                  os.path.join(report, f"{kind}.h5"), "No space left on device")
            if left:
                failures.append(f"{kind} on a full tmpfs: left {', '.join(left)}")
                print(f"FAIL {kind} on a full tmpfs: left {', '.join(left)}")

print(f"write failures: {len(failures)} problems")
sys.exit(1 if failures else 0)
