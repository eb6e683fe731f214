#!/usr/bin/python3
"""tfmb-couple on fixed-point problems with known answers: x = H(x) with H linear and
contractive (and one that is not). Checks that every acceleration finds the fixed point, that
IQN-ILS solves an n-dimensional linear problem in at most n + 2 iterations (a secant method's
finite termination), that Aitken beats constant relaxation, and the exit codes."""
import os
import shutil
import subprocess
import sys

import h5py
import numpy as np

couple, scratch = sys.argv[1], sys.argv[2]
shutil.rmtree(scratch, ignore_errors=True)
os.makedirs(scratch)
os.chdir(scratch)
rng = np.random.default_rng(7)
n_points = 4
n = 2 * n_points
A = rng.normal(size=(n, n))
A = 0.8 * A / np.max(np.abs(np.linalg.eigvals(A)))  # spectral radius 0.8: plain iteration converges slowly
b = rng.normal(size=n) * 1e-3
x_star = np.linalg.solve(np.eye(n) - A, b)


def write(path, x):
    with h5py.File(path, "w") as f:
        f.attrs["format"] = "tfmb/walldisp"
        f.attrs["format_version"] = "1.0"
        for i, wall in enumerate(("lower", "upper")):
            # wall points 10 m long, 0.2 m apart (tfmb-couple refuses a displacement of more than
            # twice the walls' extent)
            f[f"walls/{wall}/x0"] = np.column_stack([np.linspace(0.0, 10.0, n_points // 2),
                                                     np.full(n_points // 2, 0.2 * i - 0.1)])
            f[f"walls/{wall}/displacement"] = x[i * n // 2:(i + 1) * n // 2].reshape(-1, 2)


def read(path):
    with h5py.File(path) as f:
        return np.concatenate([f[f"walls/{w}/displacement"][()].ravel() for w in ("lower", "upper")])


def solve(acceleration, H, max_iterations=60, extra=()):
    x = np.zeros(n)
    for k in range(1, max_iterations + 1):
        write(f"raw-{k}.h5", H(x))
        args = [couple, "--iteration", str(k), "--raw", f"raw-{k}.h5", "--state", "state.npz",
                "--log", f"log-{acceleration}.csv", "-o", f"used-{k + 1}.h5",
                "--acceleration", acceleration, "--measure", "absolute", "--tolerance", "1e-10",
                "--max-iterations", str(max_iterations), *extra]
        if k > 1:
            args += ["--used", f"used-{k}.h5"]
        code = subprocess.run(args, capture_output=True).returncode
        if code != 10:
            return code, k, x
        x = read(f"used-{k + 1}.h5")
    return None, max_iterations, x


H = lambda x: A @ x + b
results = {}
for acceleration in ("constant", "aitken", "iqn-ils"):
    code, iterations, x = solve(acceleration, H)
    results[acceleration] = iterations
    assert code == 0, (acceleration, code, iterations)
    assert np.linalg.norm(x - x_star) < 1e-8, (acceleration, np.linalg.norm(x - x_star))
    print(f"{acceleration}: converged in {iterations} iterations")
assert results["iqn-ils"] <= n + 2, results
assert results["aitken"] < results["constant"], results

# Strict by default: reaching the limit unconverged exits 1; --lenient exits 0.
code, k, _ = solve("constant", H, max_iterations=3)
assert (code, k) == (1, 3), (code, k)
code, k, _ = solve("constant", H, max_iterations=3, extra=["--lenient"])
assert (code, k) == (0, 3), (code, k)
# Divergence stop: a non-contractive map with w = 1 grows the residual.
code, k, _ = solve("constant", lambda x: 3.0 * x + b, extra=["--relaxation", "1.0"])
assert code == 5, (code, k)
# Bad input: a file of another kind.
with h5py.File("bad.h5", "w") as f:
    f.attrs["format"] = "tfmb/flow"
code = subprocess.run([couple, "--iteration", "1", "--raw", "bad.h5", "--state", "s.npz",
                       "--log", "l.csv"], capture_output=True).returncode
assert code == 3, code
# Bad input: a displacement no supported wall can have (more than twice the walls' extent, here
# 2 x 10.002 m): refused in one line, not iterated on as "diverged".
huge = np.zeros(n)
huge[3] = 1e300
write("huge.h5", huge)
r = subprocess.run([couple, "--iteration", "1", "--raw", "huge.h5", "--state", "s.npz",
                    "--log", "l.csv"], capture_output=True, text=True)
assert r.returncode == 3, (r.returncode, r.stderr)
assert "huge.h5: /walls/lower/displacement: row 1: 1e+300 m, more than twice the walls' extent" \
    in r.stderr, r.stderr
code = subprocess.run([couple, "--iteration", "0", "--raw", "raw-1.h5", "--state", "s.npz",
                       "--log", "l.csv"], capture_output=True).returncode
assert code == 2, code
lines = open("log-iqn-ils.csv").read().splitlines()
assert lines[0].startswith("iteration,residual_norm") and len(lines) == results["iqn-ils"] + 1
# Inner tolerance: the next flow tolerance is 1e-3 x the relative residual ||r|| / ||H(x)||,
# within --flow-tolerance-range (default 1e-6 .. 1e-4); written with 3 significant digits.
def next_tolerance(k, x_used, extra=()):
    write(f"tol-raw-{k}.h5", H(x_used))
    write(f"tol-used-{k}.h5", x_used)
    args = [couple, "--iteration", str(k), "--raw", f"tol-raw-{k}.h5", "--state", "tol.npz",
            "--log", "tol.csv", "-o", f"tol-next-{k}.h5", "--tolerance", "1e-12",
            "--flow-tolerance", "flow-tolerance", *extra]
    if k > 1:
        args += ["--used", f"tol-used-{k}.h5"]
    assert subprocess.run(args, capture_output=True).returncode == 10
    return float(open("flow-tolerance").read())
def expected(x_used, lo=1e-6, hi=1e-4):
    relative = np.linalg.norm(H(x_used) - x_used) / np.linalg.norm(H(x_used))
    return min(hi, max(lo, 1e-3 * relative))
for k, (x_used, extra) in enumerate([(np.zeros(n), ()),                       # relative 1: capped
                                     (0.99 * x_star, ()),                     # about 1e-5 x
                                     (0.99999 * x_star, ()),                  # below the floor
                                     (0.99999 * x_star, ("--flow-tolerance-range", "1e-9", "1e-4"))], 1):
    lo = float(extra[1]) if extra else 1e-6
    got, want = next_tolerance(k, x_used, extra), expected(x_used, lo)
    assert abs(got - want) <= 5e-3 * want, (k, got, want)  # 3 significant digits
assert "next_flow_tolerance" in open("tol.csv").readline()
# Progress of a continuing step: iterations against the limit, the time an iteration takes from
# the stage times in the log (the iterations after the first, which restart the flow), and the
# time left at most. Iteration 1 took 100 s, 2 and 3 took 30 s: 17 left at 30 s each.
def step_with_times(k, seconds):
    write(f"p-raw-{k}.h5", H(np.zeros(n)) * k)
    with open(f"p-times-{k}.txt", "w") as f:
        f.write(f"flow {seconds - 1:.3f} 0\nbeam 1.000 0\n")
    args = [couple, "--iteration", str(k), "--raw", f"p-raw-{k}.h5", "--state", "p.npz",
            "--log", "p.csv", "-o", f"p-used-{k + 1}.h5", "--tolerance", "1e-12",
            "--max-iterations", "20", "--stage-times", f"p-times-{k}.txt"]
    if k > 1:
        args += ["--used", f"p-used-{k}.h5"]
    r = subprocess.run(args, capture_output=True, text=True)
    assert r.returncode == 10, r.stderr
    return r.stderr.splitlines()[-1]
assert step_with_times(1, 100.0) == \
    "tfmb-couple: progress: coupling 1/20 iterations, 1 min 40 s each, ETA <= 31 min 40 s"
step_with_times(2, 30.0)
line = step_with_times(3, 30.0)
assert line == "tfmb-couple: progress: coupling 3/20 iterations, 30 s each, ETA <= 8 min 30 s", line
print("coupling tests passed:", results)
