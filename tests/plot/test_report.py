#!/usr/bin/python3
"""tfmb-plot on a small synthetic run folder (a two-way nozzle run of two iterations, written
here with h5py after formats/*.md): every picture kind draws; `report` writes one HTML page that
parses, embeds every picture as a PNG and shows the verdict of summary.json (written by
workflows/case-summary) and the provenance; the reference is drawn in its own coordinate (x/l_e)
and the computed curve mapped into it; the exact quasi-1D solution meets its exit pressure;
damaged and wrong inputs give exit 3 and one line, never a traceback.

  test_report.py SOURCE_DIR SCRATCH_DIR        (a few seconds)
"""
import base64
import contextlib
import html.parser
import importlib.machinery
import importlib.util
import io
import json
import os
import random
import shutil
import subprocess
import sys

import h5py
import numpy as np

src, scratch = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
plot = os.path.join(src, "tools", "tfmb-plot", "tfmb-plot")
tp1704 = os.path.join(src, "refdata", "flow", "mason_tp1704_B1_upper_flap_p_npr8p91.csv")
L_E = 0.05752  # cases/nasa-2dcd/README.md: throat-to-exit length [m], throat at x = 0
failures = []
shutil.rmtree(scratch, ignore_errors=True)
os.makedirs(scratch)


def check(condition, what):
    if not condition:
        failures.append(what)
        print(f"FAIL {what}", flush=True)
    return condition


def root(f, kind, version):
    f.attrs.update({"format": f"tfmb/{kind}", "format_version": version, "creator": "test_report",
                    "created": "not recorded", "geometry": "planar", "depth": 1.0})
    g = f.create_group("provenance")
    g.attrs["command_line"] = f"test_report writes {kind}"
    g.attrs["settings"] = 'model = "sa"\n'
    g["input_files"] = np.array([b"case.toml"], dtype=object)
    g["input_sha256"] = np.array([b"0" * 64], dtype=object)


def p_over_p0(xi):
    """A smooth made-up wall pressure as a function of x/l_e: what the test reads back at the
    reference's stations."""
    return 0.6 - 0.4 * np.tanh(3.0 * xi)


def write_flow(path, p0=9.0e5, deflect=0.0):
    with h5py.File(path, "w") as f:
        root(f, "flow", "1.4")
        c = f.create_group("conditions")
        c.attrs.update({"stagnation_pressure": p0, "stagnation_temperature": 294.0,
                        "ambient_pressure": 101330.0, "gamma": 1.4, "gas_constant": 287.05})
        conv = f.create_group("convergence")
        conv.attrs.update({"converged": 1, "iterations": 12, "criterion": "stationarity"})
        conv["residual_history"] = np.logspace(0, -6, 12)[:, None] * np.ones((1, 4))
        integrals = f.create_group("integrals")
        integrals.attrs.update({"thrust_x": 3.0e4 * (1 + deflect), "thrust_y": 10.0,
                                "thrust_angle": 0.02 + deflect, "mass_flow": 20.0,
                                "discharge_coefficient": 0.98})
        # A 3 x 3 node grid, 8 triangles, for the field picture.
        gx, gy = np.meshgrid(np.linspace(-0.06, 0.06, 3), np.linspace(-0.03, 0.03, 3))
        f["mesh/points"] = np.column_stack([gx.ravel(), gy.ravel()])
        tris = []
        for j in range(2):
            for i in range(2):
                a = 3 * j + i
                tris += [[a, a + 1, a + 4], [a, a + 4, a + 3]]
        f["mesh/cells/triangle"] = np.array(tris, dtype=np.int64)
        f["mesh/cells/quad"] = np.zeros((0, 4), dtype=np.int64)
        f["fields/point/mach"] = np.linspace(0.2, 2.0, 9)
        f["fields/point/mach"].attrs["units"] = "1"
        for half, sign in (("upper", 1.0), ("lower", -1.0)):
            for part, (a, b) in (("convergent", (-L_E, 0.0)), ("divergent", (0.0, L_E))):
                x = np.linspace(a, b, 21)
                w = f.create_group(f"walls/{half}_{part}_inner")
                w["x"] = x
                w["y"] = sign * (0.0137 + 0.1 * np.abs(x))
                w["s"] = x - a
                w["pressure"] = p0 * (p_over_p0(x / L_E) - deflect)
                w["wall_shear"] = np.full_like(x, 50.0)


def write_structure(path, scale=1.0):
    with h5py.File(path, "w") as f:
        root(f, "structure", "1.2")
        f.attrs.update({"analysis": "static", "converged": 1})
        x = np.linspace(0.0, 0.1, 6)
        points = np.concatenate([np.column_stack([x, 0.02 + 0 * x, 0 * x]),
                                 np.column_stack([x, -0.02 + 0 * x, 0 * x])])
        f["beam/points"] = points
        f["beam/segments"] = np.array([[i, i + 1] for i in range(5)] +
                                      [[i, i + 1] for i in range(6, 11)], dtype=np.int64)
        u = np.zeros_like(points)
        u[:6, 1], u[6:, 1] = 1e-3 * scale * x, -1e-3 * scale * x
        f["fields/point/displacement"] = u
        f["flaps/upper_flap/nodes"] = np.arange(6, dtype=np.int64)
        f["flaps/lower_flap/nodes"] = np.arange(6, 12, dtype=np.int64)


def write_strain(path):
    with h5py.File(path, "w") as f:
        root(f, "strain", "1.1")
        for flap, y in (("upper_flap", 0.02), ("lower_flap", -0.02)):
            s = np.linspace(0.005, 0.095, 10)
            g = f.create_group(f"flaps/{flap}")
            g["s"] = s
            g["position"] = np.column_stack([s, np.full_like(s, y)])
            total = 0.5 + 200.0 * s if flap == "lower_flap" else 0.5 + 300.0 * (s - 0.05) ** 2 * 100
            if flap == "upper_flap":
                total[4] = -0.4  # the negative margin the picture and the verdict must show
            g["margin_total"] = total
            g["margin_mechanical"] = total + 1.0
            g["margin_thermal"] = total + 2.0
            g["total_inner"] = np.full_like(s, 1e-3)
            g["total_outer"] = np.full_like(s, 2e-3)


def write_thermal(path):
    with h5py.File(path, "w") as f:
        root(f, "thermal", "1.1")
        for flap in ("upper_flap", "lower_flap"):
            f[f"beam/{flap}/mean_temperature"] = np.linspace(500.0, 600.0, 5)
            f[f"beam/{flap}/delta_temperature"] = np.full(5, 20.0)


def write_loads(path):
    with h5py.File(path, "w") as f:
        root(f, "loads", "1.1")
        for flap, sign in (("upper_flap", 1.0), ("lower_flap", -1.0)):
            g = f.create_group(f"flaps/{flap}")
            g.attrs["total_force"] = np.array([100.0, sign * 2000.0, 0.0])
            g.attrs["total_moment"] = np.array([0.0, 0.0, sign * 50.0])


def write_model(path):
    with h5py.File(path, "w") as f:
        root(f, "model", "2.5")
        f.attrs["title"] = "synthetic nozzle"


run = os.path.join(scratch, "run")
for k, deflect in ((1, 0.0), (2, 0.01)):
    d = os.path.join(run, f"iter-{k:03d}")
    os.makedirs(d)
    write_flow(os.path.join(d, "flow.h5"), deflect=deflect)
    write_structure(os.path.join(d, "structure.h5"), scale=1.0 + deflect * 10)
    write_strain(os.path.join(d, "strain.h5"))
    write_loads(os.path.join(d, "loads.h5"))
write_thermal(os.path.join(run, "iter-001", "thermal.h5"))
write_model(os.path.join(run, "model.h5"))
for name in ("flow", "structure", "strain", "loads"):
    os.symlink(f"iter-002/{name}.h5", os.path.join(run, f"{name}.h5"))
os.symlink("iter-001/thermal.h5", os.path.join(run, "thermal.h5"))
with open(os.path.join(run, "coupling.csv"), "w") as fh:
    fh.write("iteration,residual_norm,displacement_norm,measure,value,tolerance,acceleration,"
             "relaxation,iqn_columns,status,next_flow_tolerance,stage_times\n"
             "1,1e-2,1,relative,1e-2,1e-3,aitken,0.5,0,continue,1e-4,\n"
             "2,1e-4,1,relative,1e-4,1e-3,aitken,nan,0,converged,nan,\n")
with open(os.path.join(run, "strain-summary.json"), "w") as fh:
    worst = {"flap": "upper_flap", "segment": 4, "element": 2, "surface": "outer", "s": 0.045,
             "x": 0.045, "y": 0.02, "strain": 2e-3, "allowable": 1.2e-3, "margin": -0.4}
    json.dump({"worst": {"total": worst, "mechanical": worst, "thermal": worst},
               "flaps": {"upper_flap": {"min_margin_total": -0.4, "min_margin_mechanical": 0.6,
                                        "min_margin_thermal": 1.6, "max_abs_total_strain": 2e-3}},
               "lowest_total_margins": [worst]}, fh)
summary = subprocess.run([os.path.join(src, "workflows", "case-summary"), run],
                         capture_output=True, text=True)
check(summary.returncode == 0, f"case-summary on the synthetic run: {summary.stderr}")
with open(os.path.join(run, "summary.json"), "w") as fh:
    fh.write(summary.stdout)
verdict = json.loads(summary.stdout)["verdict"]
check(not verdict["ok"] and verdict["negative_margins"], "the synthetic run's verdict should "
      f"call out the negative margin: {verdict}")

reference = (f"{tp1704}:x_over_le:p_over_ptj_centreline:band=p_over_ptj_y_over_halfwidth_0p45:"
             "npr=8.91:label=TP-1704")
mapping = ["--x-origin", "0", "--x-length", str(L_E), "--x-label", "x / l_e"]


# tfmb-plot is run in this process (its main(), what the script runs): about 0.1 s a call where a
# new process, importing matplotlib and h5py each time, takes 0.8 s; a few calls below run the
# script itself to check its exit code and stderr as a process.
loader = importlib.machinery.SourceFileLoader("tfmb_plot", plot)
spec = importlib.util.spec_from_loader("tfmb_plot", loader)
tfmb_plot_module = importlib.util.module_from_spec(spec)
loader.exec_module(tfmb_plot_module)


class Result:
    def __init__(self, returncode, stderr):
        self.returncode, self.stderr = returncode, stderr


def tfmb_plot(*args):
    """main(args) with stderr captured; an exception escaping main is a traceback the user
    would see, reported as exit -1."""
    err = io.StringIO()
    cwd = os.getcwd()
    os.chdir(scratch)
    try:
        with contextlib.redirect_stderr(err):
            code = tfmb_plot_module.main(list(args))
    except BaseException as e:  # noqa: B036 - anything escaping main() is the failure sought
        code = -1
        err.write(f"Traceback (escaped main): {type(e).__name__}: {e}\n")
    finally:
        os.chdir(cwd)
    return Result(code, err.getvalue())


def tfmb_plot_process(*args):
    return subprocess.run([plot, *args], capture_output=True, text=True, cwd=scratch)


# --- every picture kind draws from the sample files
out = os.path.join(scratch, "pictures")
os.makedirs(out)
iter1, iter2 = os.path.join(run, "iter-001"), os.path.join(run, "iter-002")
kinds = {
    "wall-pressure": [f"{run}/flow.h5", "--reference", reference, *mapping],
    "skin-friction": [f"{run}/flow.h5"],
    "field": [f"{run}/flow.h5", "--field", "mach"],
    "residuals": [f"{run}/flow.h5"],
    "deformed": [f"{run}/structure.h5"],
    "temperature": [f"{run}/thermal.h5"],
    "strain": [f"{run}/strain.h5", "--kind", "total", "--kind", "thermal"],
    "convergence": [f"{run}/coupling.csv"],
    "coupling": [run],
    "coupling-walls": [run],
    "compare": [iter1, iter2],
}
series = {}
for kind, args in kinds.items():
    png, data = os.path.join(out, f"{kind}.png"), os.path.join(out, f"{kind}.json")
    r = tfmb_plot(kind, *args, "-o", png, "--data", data)
    if check(r.returncode == 0, f"{kind}: exit {r.returncode}: {r.stderr.strip()}"):
        with open(png, "rb") as fh:
            check(fh.read(8) == b"\x89PNG\r\n\x1a\n", f"{kind}: not a PNG")
        with open(data) as fh:
            series[kind] = json.load(fh)
        check(any(s["x"] for s in series[kind]), f"{kind}: no curve recorded")

# --- the reference in its own coordinate, the computed curve mapped into it
if "wall-pressure" in series:
    ref = [s for s in series["wall-pressure"] if s["role"] == "reference"]
    band = [s for s in series["wall-pressure"] if s["role"] == "reference-band"]
    computed = [s for s in series["wall-pressure"] if s["role"] == "computed"]
    check(len(ref) == 1 and len(band) == 1, f"one reference and its band expected: {len(ref)}, {len(band)}")
    if ref:
        # refdata's stations run from -0.209 to 0.89 (x/l_e)
        check(abs(min(ref[0]["x"]) + 0.209) < 1e-9 and abs(max(ref[0]["x"]) - 0.89) < 1e-9,
              f"reference x range {min(ref[0]['x'])}..{max(ref[0]['x'])}, expected -0.209..0.89")
    xs = np.concatenate([s["x"] for s in computed])
    # The walls run from -l_e to l_e: mapped, -1 to 1; in metres they would span 0.115.
    check(abs(xs.min() + 1.0) < 1e-9 and abs(xs.max() - 1.0) < 1e-9,
          f"computed x range {xs.min()}..{xs.max()}, expected -1..1 (x/l_e)")
    upper = sorted((x, y) for s in computed if s["label"].startswith("upper")
                   for x, y in zip(s["x"], s["y"]))
    ux, uy = np.array(upper).T
    at_stations = np.interp(ref[0]["x"], ux, uy)
    check(np.allclose(at_stations, p_over_p0(np.array(ref[0]["x"])), atol=0.02),
          "the computed p/p0 read at the reference's stations is not the wall's p/p0 there: "
          "the two are not in the same coordinate")
# A run at another NPR does not get the NPR 8.91 data drawn over it.
other = os.path.join(scratch, "npr5", "flow.h5")
os.makedirs(os.path.dirname(other))
write_flow(other, p0=5.0 * 101330.0)
r = tfmb_plot("wall-pressure", other, "--reference", reference, *mapping, "-o",
              os.path.join(out, "npr5.png"), "--data", os.path.join(out, "npr5.json"))
if check(r.returncode == 0, f"wall-pressure at NPR 5: {r.stderr}"):
    with open(os.path.join(out, "npr5.json")) as fh:
        check(not [s for s in json.load(fh) if s["role"] == "reference"],
              "the NPR 8.91 reference was drawn over a run at NPR 5")

# --- margins: the negative one is drawn and the lowest is the one written
if "strain" in series:
    lowest = [s for s in series["strain"] if s["role"] == "lowest_total"]
    check(len(lowest) == 1 and lowest[0]["label"] == "upper_flap" and lowest[0]["y"] == [-0.4],
          f"lowest total margin: {lowest}")

# --- exact quasi-1D: the NPARC CDV area law (refdata/flow/nparc_cdv_nozzle_definition.csv) at
# the three exit pressure ratios; the solution must end at the exit pressure it was given
# (a normal shock in the nozzle at 0.75) and be sonic at the throat when choked.
for pe, choked in ((0.89, False), (0.75, True), (0.16, True)):
    path = os.path.join(scratch, f"cdv-{pe}", "flow.h5")
    os.makedirs(os.path.dirname(path))
    write_flow(path)
    with h5py.File(path, "a") as f:
        del f["walls"]
        x = np.linspace(0.0, 10.0, 121)
        area = np.where(x < 5, 1.75 - 0.75 * np.cos((0.2 * x - 1) * np.pi),
                        1.25 - 0.25 * np.cos((0.2 * x - 1) * np.pi))
        w = f.create_group("walls/wall")
        w["x"], w["y"], w["s"] = x * 0.0254, area * 0.0254, x * 0.0254
        w["pressure"], w["wall_shear"] = np.full_like(x, 5e4), np.zeros_like(x)
        f["conditions"].attrs["stagnation_pressure"] = 101325.0
        f["conditions"].attrs["ambient_pressure"] = pe * 101325.0
    data = os.path.join(scratch, f"cdv-{pe}.json")
    r = tfmb_plot("wall-pressure", path, "--exact", "quasi1d", "--x-length", "0.0254", "-o",
                  os.path.join(scratch, f"cdv-{pe}.png"), "--data", data)
    if check(r.returncode == 0, f"exact {pe}: {r.stderr}"):
        with open(data) as fh:
            exact = [s for s in json.load(fh) if s["role"] == "exact"][0]
        ex, ey = np.array(exact["x"]), np.array(exact["y"])
        check(abs(ey[-1] - pe) < 2e-3, f"exact solution at pe {pe}: exit p/p0 {ey[-1]:.4f}")
        check(abs(ex[0]) < 1e-9 and abs(ex[-1] - 10.0) < 1e-9, f"exact x in inches: {ex[0]}..{ex[-1]}")
        throat = float(np.interp(5.0, ex, ey))
        if choked:  # p*/p0 = 0.5283 for gamma 1.4
            check(abs(throat - 0.5283) < 5e-3, f"exact at pe {pe}: throat p/p0 {throat:.4f}")
        check(("shock" in exact["label"]) == (pe == 0.75), f"shock at pe {pe}: {exact['label']}")

# --- the report
report = os.path.join(run, "report.html")
r = tfmb_plot("report", run, "--plots-dir", os.path.join(run, "plots"), "--reference", reference,
              *mapping)
check(r.returncode == 0 and os.path.isfile(report), f"report: exit {r.returncode}: {r.stderr}")

# --- progress: in a log, the pictures drawn against their number in libcommon's line format (a
# line at every picture at TFMB_PROGRESS_INTERVAL=0), the count reaching the total
p = subprocess.run([plot, "report", run, "-o", os.path.join(scratch, "report-progress.html")],
                   capture_output=True, text=True, cwd=scratch,
                   env=dict(os.environ, TFMB_PROGRESS_INTERVAL="0"))
lines = [l for l in p.stderr.splitlines() if l.startswith("tfmb-plot: progress: ")]
counts = [l.split()[3].split("/") for l in lines]
check(p.returncode == 0 and len(lines) >= 3 and counts[0][0] == "0"
      and counts[-1][0] == counts[-1][1] and all(c[1] == counts[0][1] for c in counts)
      and lines[0].endswith("pictures, ETA ?") and "ETA 0 s" in lines[-1],
      f"report progress lines: {p.returncode} {lines}")


class Page(html.parser.HTMLParser):
    """Collects the images and checks that every element opened is closed in order."""
    VOID = {"meta", "img", "br", "hr", "link", "input"}

    def __init__(self):
        super().__init__()
        self.stack, self.images, self.errors, self.text = [], [], [], []

    def handle_starttag(self, tag, attrs):
        if tag == "img":
            self.images.append(dict(attrs).get("src", ""))
        elif tag not in self.VOID:
            self.stack.append(tag)

    def handle_endtag(self, tag):
        if not self.stack or self.stack[-1] != tag:
            self.errors.append(f"</{tag}> closes <{self.stack[-1] if self.stack else ''}>")
        else:
            self.stack.pop()

    def handle_data(self, data):
        self.text.append(data)


if os.path.isfile(report):
    page = Page()
    with open(report, encoding="utf-8") as fh:
        page.feed(fh.read())
    page.close()
    check(not page.errors and not page.stack, f"report.html is not well formed: {page.errors[:3]} "
          f"unclosed {page.stack}")
    pngs = sorted(os.listdir(os.path.join(run, "plots")))
    check(len(page.images) == len(pngs) == 9, f"{len(page.images)} images embedded, {len(pngs)} "
          f"in plots/ ({pngs}); expected 9")
    for src_ in page.images:
        ok = src_.startswith("data:image/png;base64,")
        check(ok and base64.b64decode(src_.split(",", 1)[1])[:8] == b"\x89PNG\r\n\x1a\n",
              f"an image is not an embedded PNG: {src_[:40]}")
    text = " ".join(" ".join(page.text).split())
    check("ATTENTION" in text and all(p in text for p in verdict["problems"]),
          f"the verdict's problems {verdict['problems']} are not in the report")
    for line in verdict["lines"]:
        check(" ".join(line.split()) in text, f"verdict line missing from the report: {line}")
    check("test_report writes flow" in text, "the provenance command line is not in the report")
    check("synthetic nozzle" in text, "the case title is not in the report")

# --- wrong and damaged inputs: exit 3 and one line naming the file, never a traceback
bad_csv = os.path.join(scratch, "bad.csv")
with open(bad_csv, "w") as fh:
    fh.write("# comment\nx_over_le,p\n0.1,0.5\n0.2,abc\n")
cases = [
    ("text in a reference", ["wall-pressure", f"{run}/flow.h5", "--reference", f"{bad_csv}:x_over_le:p",
                             "-o", "x.png"], "bad.csv: line 4, column 'p': 'abc' is not a number"),
    ("missing column", ["wall-pressure", f"{run}/flow.h5", "--reference", f"{bad_csv}:x:p", "-o",
                        "x.png"], "bad.csv: line 2: no column 'x'"),
    ("wrong kind", ["strain", f"{run}/flow.h5", "-o", "x.png"], "flow.h5: /: attribute 'format'"),
    ("not a run folder", ["coupling", os.path.join(scratch, "pictures"), "-o", "x.png"], "coupling.csv: no such file"),
]
broken_summary = os.path.join(scratch, "broken-run")
shutil.copytree(run, broken_summary, symlinks=True)
with open(os.path.join(broken_summary, "summary.json"), "w") as fh:
    fh.write("{not json")
cases.append(("summary.json not JSON", ["report", broken_summary], "summary.json: not readable JSON"))
# Damaged HDF5: flipped bytes in the metadata, truncation (the corruption test's kinds, a few
# seeded copies here; tests/formats/test_corrupt_files.py runs many more).
rng = random.Random(22)
with open(os.path.join(iter2, "strain.h5"), "rb") as fh:
    original = fh.read()
for k in range(6):
    data = bytearray(original)
    if k % 3 == 2:
        data = data[:rng.randrange(100, len(data) - 1)]
    else:
        start = data.find(b"OHDR", rng.randrange(0, len(data) // 2))
        start = start if start >= 0 else rng.randrange(0, len(data))
        for _ in range(3):
            i = min(len(data) - 1, start + rng.randrange(0, 128))
            data[i] ^= rng.randrange(1, 256)
    path = os.path.join(scratch, f"damaged-{k}", "strain.h5")
    os.makedirs(os.path.dirname(path))
    with open(path, "wb") as fh:
        fh.write(bytes(data))
    cases.append((f"damaged strain.h5 #{k}", ["strain", path, "-o", "x.png"], None))
for label, args, expected in cases:
    if os.path.exists(os.path.join(scratch, "x.png")):
        os.remove(os.path.join(scratch, "x.png"))
    r = tfmb_plot(*args)
    lines = r.stderr.splitlines()
    if expected is None and r.returncode == 0:  # the damage hit values that still pass
        continue
    check(r.returncode == 3 and len(lines) == 1 and lines[0].startswith("tfmb-plot: error: ")
          and "Traceback" not in r.stderr and (expected is None or expected in lines[0]) and
          (expected is not None or "strain.h5" in lines[0]),
          f"{label}: exit {r.returncode}, stderr {r.stderr!r}; expected 3 and one line"
          + (f" with {expected!r}" if expected else " naming strain.h5"))
    check(not os.path.exists(os.path.join(scratch, "x.png")), f"{label}: a failed plot left x.png")

# The script as a process: a good picture exits 0, a damaged input 3 with one line.
r = tfmb_plot_process("strain", f"{run}/strain.h5", "-o", os.path.join(out, "process.png"))
check(r.returncode == 0 and os.path.isfile(os.path.join(out, "process.png")),
      f"tfmb-plot as a process: exit {r.returncode}: {r.stderr}")
r = tfmb_plot_process("wall-pressure", f"{run}/flow.h5", "--reference", f"{bad_csv}:x_over_le:p",
                      "-o", "x.png")
check(r.returncode == 3 and len(r.stderr.splitlines()) == 1 and "bad.csv: line 4" in r.stderr,
      f"tfmb-plot as a process on a bad reference: exit {r.returncode}, stderr {r.stderr!r}")

if failures:
    print(f"{len(failures)} failures")
    sys.exit(1)
print("tfmb-plot report tests passed")
