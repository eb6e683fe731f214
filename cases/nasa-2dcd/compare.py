#!/usr/bin/python3
"""compare.py FLOW.h5 [--reference CSV] [--json OUT.json]: the nasa-2dcd flow against NASA TP-1704.

Prints, from a tfmb/flow file of the nasa-2dcd case (nozzle B1, throat at x = 0):
- the upper-flap wall p/p0 at the experiment's stations x/l_e (l_e = 5.752 cm, README.md) against
  the measured centreline values (refdata/flow/mason_tp1704_B1_upper_flap_p_npr8p91.csv), when the
  run's nozzle pressure ratio is that of the data (8.91) or --reference is given;
- on the upper divergent inner wall: shock foot (the lowest wall pressure, if the pressure rises
  by more than 10 % downstream of it before the exit), separation and reattachment (sign changes of the
  streamwise wall shear; viscous runs only), as x/l_e;
- discharge coefficient (flow.h5 /integrals) and thrust ratio F/F_i, with F_i the ideal isentropic
  thrust of the computed mass flow fully expanded to the ambient pressure (TP-1704's thrust ratio).
Exit 3 with a located message on a file that lacks what is needed, 2 on usage errors."""
import argparse
import json
import math
import os
import sys

import h5py
import numpy as np

L_E = 0.05752  # throat-to-exit length [m] (README.md: straight flaps tangent to the throat arc)
HERE = os.path.dirname(os.path.abspath(__file__))
DEFAULT_REFERENCE = os.path.join(HERE, "..", "..", "refdata", "flow", "mason_tp1704_B1_upper_flap_p_npr8p91.csv")


def fail(message):
    print(f"compare.py: error: {message}", file=sys.stderr)
    sys.exit(3)


def wall(f, path, name):
    key = f"/walls/{name}"
    if key not in f:
        fail(f"{path}: {key}: missing (is this a nasa-2dcd flow file?)")
    g = f[key]
    out = {k: np.asarray(g[k][:], dtype=float) for k in ("x", "y", "pressure", "wall_shear")}
    for k, v in out.items():
        if not np.all(np.isfinite(v)):
            fail(f"{path}: {key}/{k}: not finite")
    return out


def upper_inner_wall(f, path):
    """Upper inner wall (convergent + divergent) ordered by x, with the streamwise (+x) wall shear."""
    parts = []
    for name in ("upper_convergent_inner", "upper_divergent_inner"):
        w = wall(f, path, name)
        # wall_shear is along increasing s; turn it into the +x component's sign
        direction = np.sign(np.gradient(w["x"])) if len(w["x"]) > 1 else np.ones(1)
        w["shear_x"] = w["wall_shear"] * direction
        w["divergent"] = np.full(len(w["x"]), name == "upper_divergent_inner")
        parts.append(w)
    merged = {k: np.concatenate([p[k] for p in parts]) for k in ("x", "pressure", "shear_x", "divergent")}
    order = np.argsort(merged["x"], kind="stable")
    merged = {k: v[order] for k, v in merged.items()}
    # the throat node belongs to both curves: keep one
    keep = np.concatenate([[True], np.diff(merged["x"]) > 1e-12])
    return {k: v[keep] for k, v in merged.items()}


# TP-1704's own yardstick for a computed wall pressure: within this much p/p_t of the band between
# the centreline and the 45 % half-span readings at each orifice, one orifice allowed to miss (the
# spanwise spread is the experiment's three-dimensionality, the 0.02 its reading and transcription
# scatter).
BAND_MARGIN = 0.02
BAND_MISSES_ALLOWED = 1


def read_reference(path):
    """Stations x/l_e, centreline p/p_t and, if the CSV has it, the 45 % half-span p/p_t (else
    the centreline again) of a refdata CSV (comment lines start with #)."""
    try:
        with open(path) as handle:
            lines = [line.strip() for line in handle if line.strip() and not line.startswith("#")]
    except OSError as err:
        fail(f"{path}: {err.strerror}")
    header = lines[0].split(",")
    for column in ("x_over_le", "p_over_ptj_centreline"):
        if column not in header:
            fail(f"{path}: header: no column {column}")
    ix, ip = header.index("x_over_le"), header.index("p_over_ptj_centreline")
    i45 = header.index("p_over_ptj_y_over_halfwidth_0p45") if "p_over_ptj_y_over_halfwidth_0p45" in header else ip
    try:
        rows = [[float(v) for v in line.split(",")] for line in lines[1:]]
    except ValueError:
        fail(f"{path}: a data line is not numeric")
    return (np.array([r[ix] for r in rows]), np.array([r[ip] for r in rows]),
            np.array([r[i45] for r in rows]))


def shock_and_separation(x, p_ratio, shear_x, viscous):
    result = {"shock_foot_x_over_le": None, "pre_shock_p_over_p0": None, "separation_x_over_le": None,
              "reattachment_x_over_le": None}
    if len(x) < 3:
        return result
    # The shock that an over-expanded nozzle holds in its divergent part: the pressure rises from
    # its lowest value on the wall (the foot) by more than 10 % before the exit. (The recompression
    # just downstream of B1's sharp throat, about 15 % at every NPR, lies upstream of that minimum.)
    interior = slice(0, len(x) - 1)  # the lip node sees the base flow: not part of the wall's rise
    foot = int(np.argmin(p_ratio[interior]))
    if foot + 1 < len(x) - 1:
        rise = p_ratio[foot + 1:len(x) - 1].max() / p_ratio[foot] - 1.0
        if rise > 0.1:
            result["shock_foot_x_over_le"] = float(x[foot] / L_E)
            result["pre_shock_p_over_p0"] = float(p_ratio[foot])
    if viscous:
        negative = shear_x < 0.0
        if negative.any():
            first = int(np.argmax(negative))
            if first > 0:  # interpolate the zero crossing
                x0, x1, t0, t1 = x[first - 1], x[first], shear_x[first - 1], shear_x[first]
                result["separation_x_over_le"] = float((x0 - t0 * (x1 - x0) / (t1 - t0)) / L_E)
            else:
                result["separation_x_over_le"] = float(x[0] / L_E)
            # reattached only if the shear turns positive again before the last wall node
            after = np.nonzero(~negative[first:-1])[0]
            if after.size:
                result["reattachment_x_over_le"] = float(x[first + after[0]] / L_E)
    return result


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("flow")
    parser.add_argument("--reference", help="CSV with x_over_le and p_over_ptj_centreline columns")
    parser.add_argument("--json", help="write the figures to this file")
    args = parser.parse_args()
    try:
        f = h5py.File(args.flow, "r")
    except OSError:
        fail(f"{args.flow}: not an HDF5 file")
    with f:
        if "conditions" not in f:
            fail(f"{args.flow}: /conditions: missing group")
        c = f["conditions"].attrs
        try:
            p0 = float(c["stagnation_pressure"])
            t0 = float(c["stagnation_temperature"])
            p_amb = float(c["ambient_pressure"])
            gamma = float(c["gamma"])
            gas_constant = float(c["gas_constant"])
        except KeyError as missing:
            fail(f"{args.flow}: /conditions: missing attribute {missing}")
        model = ("sa" if "fields/point/nu_tilde" in f
                 else "sst" if "fields/point/turbulent_kinetic_energy" in f else "euler or laminar")
        integ = f["integrals"].attrs if "integrals" in f else fail(f"{args.flow}: /integrals: missing group")
        mass_flow = float(integ["mass_flow"])
        thrust = float(integ["thrust_x"])
        cd = float(integ.get("discharge_coefficient", float("nan")))
        converged = int(f["convergence"].attrs.get("converged", 0)) if "convergence" in f else 0
        criterion = f["convergence"].attrs.get("criterion", b"") if "convergence" in f else b""
        criterion = criterion.decode() if isinstance(criterion, bytes) else str(criterion)
        iterations = int(f["convergence"].attrs.get("iterations", -1)) if "convergence" in f else -1
        w = upper_inner_wall(f, args.flow)
    npr = p0 / p_amb
    viscous = bool(np.any(w["shear_x"] != 0.0))
    p_ratio = w["pressure"] / p0
    # TP-1704's ideal thrust: the computed mass flow expanded isentropically to the ambient pressure
    v_ideal = math.sqrt(2.0 * gamma / (gamma - 1.0) * gas_constant * t0 * (1.0 - (1.0 / npr) ** ((gamma - 1.0) / gamma)))
    thrust_ratio = thrust / (mass_flow * v_ideal)
    figures = {"file": args.flow, "npr": npr, "model": model, "converged": converged, "criterion": criterion,
               "iterations": iterations, "discharge_coefficient": cd, "thrust_ratio": thrust_ratio,
               "mass_flow_kg_per_s_m": mass_flow}
    div = w["divergent"] & (w["x"] > 0.0)
    figures.update(shock_and_separation(w["x"][div], p_ratio[div], w["shear_x"][div], viscous))

    reference = args.reference or (DEFAULT_REFERENCE if abs(npr - 8.91) < 0.01 else None)
    print(f"nasa-2dcd NPR {npr:.3f} ({model}): converged {converged} ({criterion}, {iterations} iterations), "
          f"Cd {cd:.4f}, F/F_i {thrust_ratio:.4f}")
    for key in ("shock_foot_x_over_le", "pre_shock_p_over_p0", "separation_x_over_le", "reattachment_x_over_le"):
        value = figures[key]
        none = "- (separated to the exit)" if key == "reattachment_x_over_le" and figures["separation_x_over_le"] else "-"
        print(f"  {key:24s} {none if value is None else f'{value:.3f}'}")
    if reference:
        stations, measured, measured_45 = read_reference(reference)
        computed = np.interp(stations * L_E, w["x"], p_ratio)
        error = (computed - measured) / measured
        # outside the centreline-to-45 %-span band by how much (p/p_t; 0 inside it)
        low, high = np.minimum(measured, measured_45), np.maximum(measured, measured_45)
        outside = np.maximum(low - computed, 0.0) + np.maximum(computed - high, 0.0)
        misses = int(np.sum(outside > BAND_MARGIN))
        print(f"  upper-flap p/p0 against {os.path.basename(reference)}:")
        print("    x/l_e   measured  45 % span  computed  difference  outside band")
        for s, m, m45, cp, e, o in zip(stations, measured, measured_45, computed, error, outside):
            flag = "  MISS" if o > BAND_MARGIN else ""
            print(f"  {s:7.3f}   {m:8.4f}  {m45:9.4f}  {cp:8.4f}  {100 * e:+7.2f} %  {o:8.4f}{flag}")
        print(f"  largest |difference| {100 * np.abs(error).max():.2f} %, mean |difference| "
              f"{100 * np.abs(error).mean():.2f} %")
        verdict = "meets" if misses <= BAND_MISSES_ALLOWED else "misses"
        print(f"  TP-1704 yardstick (within {BAND_MARGIN} p/p_t of the centreline-to-45 % band, "
              f"{BAND_MISSES_ALLOWED} orifice may miss): {misses} outside, {verdict} it")
        figures["band_misses"] = misses
        figures["band_largest_outside"] = float(outside.max())
        figures["stations"] = [{"x_over_le": float(s), "measured": float(m), "measured_45": float(m45),
                                "computed": float(cp), "outside_band": float(o)}
                               for s, m, m45, cp, o in zip(stations, measured, measured_45, computed, outside)]
        figures["largest_relative_difference"] = float(np.abs(error).max())
    if args.json:
        with open(args.json, "w") as out:
            json.dump(figures, out, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
