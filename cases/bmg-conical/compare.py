#!/usr/bin/python3
"""compare.py FLOW.h5 [--reference CSV] [--json OUT.json]: bmg-conical wall p/pt against Back,
Massier and Gier (1965), refdata/flow/bmg_conical_nozzle_wall_p_gdtk.csv.

At each measured station x (inches from the throat) prints the computed wall p/pt (linear between
trace points), the difference in per cent of the measured value and, because the data were read
off a figure at a uniform 0.125 in (refdata/README.md), how far along x the computed curve is from
reaching the measured value (its nearest crossing): where p falls steeply that is the fairer
measure, as in tests/flow/test_bmg_nozzle.cpp. Summaries over 0.125 <= x <= 2.0 in (where an
attached-flow solution can be asked to agree) and 2.125 <= x <= 2.5 in (where the measured
pressure levels off, most likely separation at the experiment's back pressure, not modelled).
Exit 3 with a located message on a file that lacks what is needed, 2 on usage errors."""
import argparse
import json
import os
import sys

import h5py
import numpy as np

INCH = 0.0254
HERE = os.path.dirname(os.path.abspath(__file__))
DEFAULT_REFERENCE = os.path.join(HERE, "..", "..", "refdata", "flow", "bmg_conical_nozzle_wall_p_gdtk.csv")


def fail(message):
    print(f"compare.py: error: {message}", file=sys.stderr)
    sys.exit(3)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("flow")
    parser.add_argument("--reference", default=DEFAULT_REFERENCE)
    parser.add_argument("--json")
    args = parser.parse_args()
    try:
        f = h5py.File(args.flow, "r")
    except OSError as e:
        fail(f"{args.flow}: cannot open ({e})")
    with f:
        if f.attrs.get("geometry", b"") not in ("axisymmetric", b"axisymmetric"):
            fail(f"{args.flow}: /: geometry is not 'axisymmetric' (is this a bmg-conical flow file?)")
        if "/walls/wall" not in f:
            fail(f"{args.flow}: /walls/wall: missing (is this a bmg-conical flow file?)")
        g = f["/walls/wall"]
        x = np.asarray(g["x"][:], dtype=float)
        p = np.asarray(g["pressure"][:], dtype=float)
        if "/conditions" not in f or "stagnation_pressure" not in f["/conditions"].attrs:
            fail(f"{args.flow}: /conditions@stagnation_pressure: missing")
        p0 = float(f["/conditions"].attrs["stagnation_pressure"])
    if not (np.all(np.isfinite(x)) and np.all(np.isfinite(p)) and p0 > 0):
        fail(f"{args.flow}: /walls/wall: non-finite values")
    order = np.argsort(x)
    x, ratio = x[order], p[order] / p0
    # The file's '#' header lines hold commas, so it is read line by line, not by genfromtxt.
    x_ref, p_ref = [], []
    try:
        with open(args.reference) as ref:
            lines = [line.strip() for line in ref if line.strip() and not line.startswith("#")]
        columns = lines[0].split(",")
        ix, ip = columns.index("x_in_from_throat"), columns.index("p_over_pt")
        for number, line in enumerate(lines[1:], start=2):
            cells = line.split(",")
            x_ref.append(float(cells[ix]))
            p_ref.append(float(cells[ip]))
    except (OSError, ValueError, IndexError) as e:
        fail(f"{args.reference}: cannot read x_in_from_throat, p_over_pt ({e})")
    rows = []
    print("  x [in]   p/pt computed   measured   difference   computed reaches it [in]")
    for xi, pr in zip(x_ref, p_ref):
        xm = xi * INCH
        if xm < x[0] or xm > x[-1]:
            continue
        pc = float(np.interp(xm, x, ratio))
        d = ratio - pr
        shift = None
        for j in range(1, len(x)):
            if d[j - 1] * d[j] <= 0 and d[j - 1] != d[j]:
                xc = x[j - 1] + d[j - 1] / (d[j - 1] - d[j]) * (x[j] - x[j - 1])
                if shift is None or abs(xc - xm) < abs(shift):
                    shift = xc - xm
        shift_in = shift / INCH if shift is not None else float("nan")
        rows.append({"x_in": float(xi), "computed": pc, "measured": float(pr),
                     "difference_percent": 100.0 * (pc - pr) / pr, "shift_in": shift_in})
        print(f"  {xi:6.3f}   {pc:12.4f}   {pr:8.3f}   {100.0 * (pc - pr) / pr:+8.1f} %   {shift_in:+8.3f}")

    def summary(lo, hi):
        sel = [r for r in rows if lo - 1e-9 <= r["x_in"] <= hi + 1e-9]
        if not sel:
            return None
        worst = max(sel, key=lambda r: abs(r["difference_percent"]))
        far = max(sel, key=lambda r: abs(r["shift_in"]) if np.isfinite(r["shift_in"]) else 1e9)
        return {"from_in": lo, "to_in": hi, "largest_difference_percent": worst["difference_percent"],
                "at_in": worst["x_in"], "largest_shift_in": far["shift_in"], "shift_at_in": far["x_in"]}

    result = {"stations": rows, "attached_part": summary(0.125, 2.0), "plateau": summary(2.125, 2.5),
              "throat": summary(0.0, 0.0)}
    for key, label in (("throat", "x = 0"), ("attached_part", "0.125-2.0 in"), ("plateau", "2.125-2.5 in")):
        s = result[key]
        if s:
            print(f"{label}: largest difference {s['largest_difference_percent']:+.1f} % at {s['at_in']:.3f} in; "
                  f"computed curve within {abs(s['largest_shift_in']):.3f} in along x of every measured point "
                  f"(largest at {s['shift_at_in']:.3f} in)")
    if args.json:
        with open(args.json, "w") as out:
            json.dump(result, out, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
