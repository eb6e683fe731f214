#!/usr/bin/python3
"""workflows/case-summary's verdict: a negative margin, an unconverged flow or coupling make it
not ok and are named; --strict turns that into exit 1 with summary.json written all the same.
Arguments: the source dir, a scratch dir."""
import importlib.machinery
import importlib.util
import json
import os
import shutil
import subprocess
import sys

src, scratch = sys.argv[1], sys.argv[2]
script = os.path.join(src, "workflows", "case-summary")
loader = importlib.machinery.SourceFileLoader("case_summary", script)
spec = importlib.util.spec_from_loader("case_summary", loader)
case_summary = importlib.util.module_from_spec(spec)
loader.exec_module(case_summary)


def spot(margin, segment=0):
    return {"flap": "upper_1", "segment": segment, "element": 0, "surface": "inner", "s": 0.01,
            "x": 0.01, "y": 0.25, "strain": 0.006, "allowable": 0.0057, "margin": margin}


def strain(*margins):
    spots = sorted((spot(m, k) for k, m in enumerate(margins)), key=lambda w: w["margin"])
    return {"worst": {"total": spots[0]}, "lowest_total_margins": spots}


failures = []


def check(condition, what):
    if not condition:
        failures.append(what)


good = {"flow": {"converged": True, "iterations": 100, "thrust_x": 1e5, "thrust_angle": 0.1,
                 "discharge_coefficient": 0.98},
        "structure": {"converged": True, "max_displacement": 0.01},
        "strain": strain(0.3, 0.5)}
v = case_summary.verdict(good)
check(v["ok"] and not v["problems"], f"a sound run is ok: {v}")
check(any("thrust 100000 N/m" in line and "Cd 0.9800" in line for line in v["lines"]), v["lines"])

bad = dict(good, strain=strain(-0.1, -0.05, 0.2))
v = case_summary.verdict(bad)
check(not v["ok"], "a negative margin is not ok")
check(len(v["negative_margins"]) == 2, f"both negative margins called out: {v['negative_margins']}")
check(sum(line.startswith("NEGATIVE MARGIN") for line in v["lines"]) == 2, v["lines"])

v = case_summary.verdict(dict(good, flow=dict(good["flow"], converged=False)))
check(not v["ok"] and "flow not converged" in v["problems"], v)
v = case_summary.verdict(dict(good, coupling={"status": "max-iterations", "iterations": 20,
                                              "measure": "relative", "final_value": 0.1,
                                              "tolerance": 1e-3}))
check(not v["ok"] and "coupling max-iterations" in v["problems"], v)
# The dynamic exchange (EXCHANGE=dynamic, tfmb-couple --lenient) runs a fixed number of
# exchanges of beam dynamics: reaching the last one is its end, not an unconverged coupling.
dynamic = dict(good, structure=dict(good["structure"], analysis="dynamic"),
               coupling={"status": "max-iterations", "iterations": 7, "measure": "relative",
                         "final_value": 0.68, "tolerance": 2e-3})
v = case_summary.verdict(dynamic)
check(v["ok"] and not v["problems"], f"seven dynamic exchanges done are ok: {v}")
check(any("fixed number of exchanges is done" in line for line in v["lines"]), v["lines"])

# the command: --strict exits 1 on a negative margin and still prints the summary
shutil.rmtree(scratch, ignore_errors=True)
os.makedirs(scratch)
with open(os.path.join(scratch, "strain-summary.json"), "w") as f:
    json.dump(strain(-0.1), f)
for strict, expected in ((False, 0), (True, 1)):
    r = subprocess.run([script, scratch] + (["--strict"] if strict else []), capture_output=True,
                       text=True)
    check(r.returncode == expected, f"--strict={strict}: exit {r.returncode}, expected {expected}")
    check(json.loads(r.stdout)["verdict"]["ok"] is False, "verdict in the JSON")
    check("ATTENTION: 1 negative total-strain margin" in r.stderr, r.stderr)

for f in failures:
    print("FAIL", f)
print("verdict:", "ok" if not failures else f"{len(failures)} failures")
sys.exit(1 if failures else 0)
