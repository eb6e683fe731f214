#!/usr/bin/python3
"""Semantic mutations of valid files: refused in one located line, or they change nothing (issue 23).

Where tests/formats/test_corrupt_files.py damages bytes, this suite changes meaning: it takes the
valid files of a real coarse chain (the sample runs' set-up, tests/samples/run_sample_runs.py:
simple-nozzle on a mesh 8x coarser, plus its strain.h5 and a two-way coupling step) and changes one
dataset, attribute or group at a time in a way no writer of the spec produces:

  file       empty file, a directory in its place, truncation, byte flips (test_corrupt_files)
  format     format or format_version missing, of another kind, unknown major, huge, a number
  removed    a dataset or a group removed
  nonfinite  NaN or Inf in one element (datasets and numeric attributes)
  huge       1e300 (float) or 2^62 (integer) in one element
  sign       zero or negative value of a quantity positive by definition (POSITIVE below:
             thickness, absolute temperature and pressure, moduli, density, gamma, ...)
  index      an integer index out of range (-1, one past the largest)
  cells      a degenerate (repeated node) or inverted (two nodes swapped) cell or edge
  dtype      float stored as integer (values truncated), integer as float, numbers as strings
  shape      one row fewer, one column more, empty (0 rows), 2^40 rows (allocated lazily)
  link       dangling soft link, external link to a missing file, soft link to another dataset
  units      units attribute removed or wrong
  attribute  a numeric attribute removed or given as a string

Every mutant is fed to every tool that reads its kind, in the position Makefile.cases gives it
(CONSUMERS), next to the unmutated other inputs, and each run is classified against the tool's
run on the unmutated file (the baseline, run twice: whatever differs between the two runs is
excluded from the comparison):

  crash              signal, exit 4 or an undocumented code, a Python traceback, timeout
  leftover           an output file left after an exit that is not a result (0, 1 and the
                     coupling step's 5 and 10 are results)
  unlocated          exit 3 whose last stderr line does not name the mutated file (naming
                     another input is fine when tfmb-check accepts the mutant on its own: the
                     files disagree, and either may be the wrong one)
  accepted-changed   a result, and it differs from the baseline's: exit code, or a number in
                     the outputs (every numeric dataset and attribute of an .h5 output outside
                     /provenance, every number of a JSON output, the last row of a CSV log,
                     the words of stdout for flow-args) by more than RTOL of the largest
                     magnitude of that baseline array; the mutated object itself copied into
                     the output (tfmb-heat copies the mesh, tfmb-couple the wall points) is not
                     compared: the next reader checks it again
  refused            exit 3, located, nothing left: fine
  accepted-unchanged a result equal to the baseline's: the mutated value is not used, fine

tfmb-check runs on every mutant too (and on mutants of `tfmb-check --example KIND`); for it an
exit 0 is "accepted" (it has no result to compare) and exit 3 must be located.

Prints the findings one per line, a table per kind and tool, and one summary line; writes
SCRATCH/findings.json; exits 1 if there is any finding. Deterministic for a given --seed; the
mutation classes are taken round-robin per kind so that a small --per-kind still covers them.

  mutation_suite.py SOURCE_DIR BIN_DIR SCRATCH_DIR [--seed N] [--per-kind N] [--per-example N]
                    [--jobs N] [--kinds K,...] [--known FILE] [--keep]

--keep keeps every run's folder (by default only those of findings stay, in SCRATCH/runs/).
--known FILE: findings not fixed yet (tests/formats/mutation-known.txt, what ctest
formats.mutation_suite tolerates at its small cap); they print as KNOWN and do not fail the run.
`make -f Makefile.cases fuzz` runs the full suite (25 mutants per kind, no known list).
"""
import argparse
import concurrent.futures
import csv
import json
import os
import pathlib
import random
import re
import shutil
import subprocess
import sys
import time
import zlib

import h5py
import numpy as np

HERE = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
sys.path.insert(0, str(HERE.parent / "samples"))
import test_corrupt_files as corrupt  # noqa: E402  byte-level damage, run(), outcome()
import run_sample_runs  # noqa: E402  the coarse chain's set-up

# Relative difference (to the largest magnitude of the baseline array) above round-off: the
# tools are deterministic at one thread, the baseline is run twice to find what is not.
RTOL = 1e-9
TIMEOUT = corrupt.TIMEOUT
# Names of quantities positive by definition (absolute temperature and pressure, lengths of a
# section, material moduli and densities, gas properties); zero or negative values are invalid.
POSITIVE = re.compile(r"(^|_)(thickness|width|depth|density|youngs_modulus|shear_modulus|"
                      r"conductivity|specific_heat|yield_strength|ultimate_strength|gamma|"
                      r"gas_constant|stagnation_pressure|stagnation_temperature|ambient_pressure|"
                      r"ambient_temperature|pressure|temperature|p0|T0|first_cell_height|area)$")
NOT_POSITIVE = re.compile(r"delta|difference|ratio|coefficient|reference")
# Integer datasets holding indices into another array.
INDEX = re.compile(r"(cells/|edges$|segments$|nodes$|node$|element|connectivity|(^|/)ids?$)")
CELLS = re.compile(r"(cells/(triangle|quad)$|edges$|segments$)")

# Chain files, by kind (the set-up's file names).
CHAIN_FILES = {"model": "model.h5", "flowmesh": "flowmesh.h5", "solidmesh": "solidmesh.h5",
               "flow": "flow.h5", "thermal": "thermal.h5", "material-db": "materials-db.h5",
               "materials": "materials.h5", "loads": "loads.h5", "walldisp": "walldisp.h5",
               "structure": "structure.h5", "strain": "strain.h5"}


def consumers(src, bin_dir, flow_args):
    """(kind, label, command) of every reader of every kind in its Makefile.cases position. In a
    command, "@name" is the mutated input (placed as mut-name), other .h5/.npz/.csv names are
    the chain's files; outputs are the names starting with "out"."""
    b = lambda tool: os.path.join(bin_dir, tool)  # noqa: E731
    wf = lambda tool: str(src / "workflows" / tool)  # noqa: E731
    plot = str(src / "tools" / "tfmb-plot" / "tfmb-plot")
    flow = [b("tfmb-flow"), "flowmesh.h5", *flow_args, "--max-iterations", "2", "--threads", "1",
            "--restart", "flow.h5", "--heat-transfer-dt", "0", "--restart-limiter", "frozen",
            "-o", "out.h5"]
    heat = [b("tfmb-heat"), "solidmesh.h5", "flow.h5", "model.h5", "--db", "materials-db.h5",
            "-o", "out.h5"]
    matmap = [b("tfmb-matmap"), "thermal.h5", "model.h5", "--db", "materials-db.h5", "-o", "out.h5"]
    forces = [b("tfmb-loads"), "forces", "flow.h5", "model.h5", "--method", "conservative",
              "-o", "out.h5"]
    forces_ref = forces[:-2] + ["--reference-mesh", "flowmesh.h5", "-o", "out.h5"]
    beam = [b("tfmb-beam"), "model.h5", "loads.h5", "materials.h5", "-o", "out.h5"]
    strain = [b("tfmb-strain"), "structure.h5", "materials.h5", "--summary", "out.json",
              "-o", "out.h5"]
    displace = [b("tfmb-loads"), "displace", "structure.h5", "model.h5", "--mesh", "flowmesh.h5",
                "-o", "out.h5"]
    deform = [b("tfmb-mesh"), "deform", "flowmesh.h5", "walldisp.h5", "-o", "out.h5"]
    couple1 = [wf("tfmb-couple"), "--iteration", "1", "--raw", "walldisp.h5", "--model", "model.h5",
               "--state", "out-state.npz", "--log", "out-log.csv", "-o", "out.h5"]
    couple2 = [wf("tfmb-couple"), "--iteration", "2", "--raw", "walldisp.h5", "--used",
               "walldisp.h5", "--model", "model.h5", "--state", "state.npz", "--log", "log.csv",
               "-o", "out.h5"]

    def at(command, name, nth=0):
        """command with its nth occurrence of name marked as the mutated input."""
        out, seen = list(command), 0
        for i, token in enumerate(out):
            if token == name:
                if seen == nth:
                    out[i] = "@" + name
                    return out
                seen += 1
        raise ValueError(f"{name} not in {command}")

    table = [
        ("model", "tfmb-mesh flow", [b("tfmb-mesh"), "flow", "@model.h5", "-o", "out.h5"]),
        ("model", "tfmb-mesh solid", [b("tfmb-mesh"), "solid", "@model.h5", "-o", "out.h5"]),
        ("model", "flow-args", [wf("flow-args"), "@model.h5", "--model", "sa"]),
        ("model", "tfmb-heat", at(heat, "model.h5")),
        ("model", "tfmb-matmap", at(matmap, "model.h5")),
        ("model", "tfmb-loads forces", at(forces, "model.h5")),
        ("model", "tfmb-beam", at(beam, "model.h5")),
        ("model", "tfmb-loads displace", at(displace, "model.h5")),
        ("model", "tfmb-couple", at(couple1, "model.h5")),
        ("flowmesh", "tfmb-flow", at(flow, "flowmesh.h5")),
        ("flowmesh", "tfmb-mesh deform", at(deform, "flowmesh.h5")),
        ("flowmesh", "tfmb-loads displace", at(displace, "flowmesh.h5")),
        ("flowmesh", "tfmb-loads forces --reference-mesh", at(forces_ref, "flowmesh.h5")),
        ("solidmesh", "tfmb-heat", at(heat, "solidmesh.h5")),
        ("flow", "tfmb-heat", at(heat, "flow.h5")),
        ("flow", "tfmb-loads forces", at(forces, "flow.h5")),
        ("flow", "tfmb-flow --restart", at(flow, "flow.h5")),
        ("flow", "tfmb-plot wall-pressure",
         [plot, "wall-pressure", "@flow.h5", "--data", "out.json", "-o", "out.png"]),
        ("thermal", "tfmb-matmap", at(matmap, "thermal.h5")),
        ("thermal", "tfmb-plot temperature",
         [plot, "temperature", "@thermal.h5", "--data", "out.json", "-o", "out.png"]),
        ("material-db", "tfmb-heat", at(heat, "materials-db.h5")),
        ("material-db", "tfmb-matmap", at(matmap, "materials-db.h5")),
        ("materials", "tfmb-beam", at(beam, "materials.h5")),
        ("materials", "tfmb-strain", at(strain, "materials.h5")),
        ("loads", "tfmb-beam", at(beam, "loads.h5")),
        ("loads", "nodal-forces lump",
         [wf("nodal-forces"), "lump", "@loads.h5", "--every", "5", "-o", "out.h5"]),
        ("structure", "tfmb-strain", at(strain, "structure.h5")),
        ("structure", "tfmb-loads displace", at(displace, "structure.h5")),
        ("structure", "tfmb-plot deformed",
         [plot, "deformed", "@structure.h5", "--data", "out.json", "-o", "out.png"]),
        ("structure", "nodal-forces compare",
         [wf("nodal-forces"), "compare", "structure.h5", "@structure.h5", "--json", "out.json"]),
        ("walldisp", "tfmb-mesh deform", at(deform, "walldisp.h5")),
        ("walldisp", "tfmb-couple --raw", at(couple1, "walldisp.h5")),
        ("walldisp", "tfmb-couple --used", at(couple2, "walldisp.h5", 1)),
        ("strain", "tfmb-plot strain",
         [plot, "strain", "@strain.h5", "--data", "out.json", "-o", "out.png"]),
    ]
    check = os.path.join(bin_dir, "tfmb-check")
    for kind, name in CHAIN_FILES.items():
        table.append((kind, "tfmb-check", [check, "--no-summary", "@" + name]))
    return table


# Exit codes that are results (a written output to compare): 0 ok, 1 flagged unconverged; the
# coupling step's 10 (continue, next displacement written) and 5 (diverged).
RESULT_CODES = {"tfmb-couple": {0, 1, 5, 10}}
DEFAULT_RESULT_CODES = {0, 1}


def tool_name(command):
    return os.path.basename(command[0])


# ---------------------------------------------------------------------------------------------
# Mutations: (class, label, apply) with apply(path) changing a copy of the valid file in place
# (or replacing it: a directory, an empty file).

def h5_edit(edit):
    def apply(path):
        with h5py.File(path, "r+") as f:
            edit(f)
    return apply


def bytes_edit(transform):
    def apply(path):
        data = pathlib.Path(path).read_bytes()
        pathlib.Path(path).write_bytes(transform(data))
    return apply


def replace_dataset(f, name, data, dtype=None, shape=None, chunks=None):
    """Replace dataset `name` by a new one (data or an unwritten shape), keeping its attributes."""
    attrs = {k: f[name].attrs[k] for k in f[name].attrs}
    del f[name]
    if shape is not None:
        d = f.create_dataset(name, shape=shape, dtype=dtype, chunks=chunks)
    else:
        d = f.create_dataset(name, data=data, dtype=dtype)
    for k, v in attrs.items():
        d.attrs[k] = v


def set_element(name, value):
    def edit(f):
        data = f[name][()]
        flat = data.reshape(-1)
        flat[len(flat) // 2] = value
        replace_dataset(f, name, data)
    return edit


def scale_all(name, factor):
    def edit(f):
        replace_dataset(f, name, f[name][()] * factor)
    return edit


def inventory(path):
    """(datasets, groups, numeric attributes) of a file: lists of (name, dtype, shape), names,
    (object name, attribute name, value)."""
    datasets, groups, attributes = [], [], []
    with h5py.File(path, "r") as f:
        def visit(name, obj):
            if name.startswith("provenance"):
                return
            if isinstance(obj, h5py.Dataset):
                datasets.append((name, obj.dtype, obj.shape))
            else:
                groups.append(name)
            for k in obj.attrs:
                v = obj.attrs[k]
                if isinstance(v, (int, float, np.integer, np.floating)):
                    attributes.append((name, k, v))
        f.visititems(visit)
        for k in f.attrs:
            v = f.attrs[k]
            if isinstance(v, (int, float, np.integer, np.floating)):
                attributes.append(("/", k, v))
    return datasets, groups, attributes


def is_positive_name(name):
    leaf = name.rsplit("/", 1)[-1]
    return bool(POSITIVE.search(leaf)) and not NOT_POSITIVE.search(leaf)


def candidates(path, kind, rng):
    """Every mutation of one file, by class: {class: [(label, apply)]}."""
    by_class = {}

    def add(cls, label, apply):
        by_class.setdefault(cls, []).append((label, apply))

    data = pathlib.Path(path).read_bytes()
    add("file", "empty file", bytes_edit(lambda d: b""))
    add("file", "a directory in its place", "directory")
    add("file", "truncated to half", bytes_edit(lambda d: d[:len(d) // 2]))
    for label, damaged in corrupt.mutations(data, 3, rng):
        add("file", label, bytes_edit(lambda d, damaged=damaged: damaged))

    def set_attr(obj, key, value):
        def edit(f):
            f[obj].attrs[key] = value
        return edit

    def del_attr(obj, key):
        def edit(f):
            del f[obj].attrs[key]
        return edit

    other_kind = "flow" if kind != "flow" else "thermal"
    add("format", "format removed", h5_edit(del_attr("/", "format")))
    add("format", f"format tfmb/{other_kind}", h5_edit(set_attr("/", "format", f"tfmb/{other_kind}")))
    add("format", "format a number", h5_edit(set_attr("/", "format", 1.0)))
    add("format", "format_version removed", h5_edit(del_attr("/", "format_version")))
    add("format", "format_version 99.0", h5_edit(set_attr("/", "format_version", "99.0")))
    add("format", "format_version 123456789012345678901234567890.0",
        h5_edit(set_attr("/", "format_version", "123456789012345678901234567890.0")))
    add("format", "format_version 1.x", h5_edit(set_attr("/", "format_version", "1.x")))
    add("format", "format_version a number", h5_edit(set_attr("/", "format_version", 1.0)))

    datasets, groups, attributes = inventory(path)
    numeric = [d for d in datasets if d[1].kind in "fiu" and np.prod(d[2], dtype=np.int64) > 0]
    for name, dtype, shape in datasets:
        add("removed", f"{name} removed", h5_edit(lambda f, name=name: f.__delitem__(name)))
        add("units", f"{name} units removed",
            h5_edit(lambda f, name=name: f[name].attrs.__delitem__("units")
                    if "units" in f[name].attrs else None))
        add("units", f"{name} units 'furlong'",
            h5_edit(lambda f, name=name: f[name].attrs.__setitem__("units", "furlong")))
        add("link", f"{name} a dangling soft link",
            h5_edit(lambda f, name=name: (f.__delitem__(name),
                                          f.__setitem__(name, h5py.SoftLink("/no/such/dataset")))))
        add("link", f"{name} an external link to a missing file",
            h5_edit(lambda f, name=name: (f.__delitem__(name), f.__setitem__(
                name, h5py.ExternalLink("no-such-file.h5", "/" + name)))))
        same = [d[0] for d in datasets if d[0] != name and d[2] == shape and d[1] == dtype]
        if same:
            target = rng.choice(same)
            add("link", f"{name} a soft link to {target}",
                h5_edit(lambda f, name=name, target=target: (
                    f.__delitem__(name), f.__setitem__(name, h5py.SoftLink("/" + target)))))
    for name in groups:
        if name.count("/") <= 2:
            add("removed", f"group {name} removed", h5_edit(lambda f, name=name: f.__delitem__(name)))
    for name, dtype, shape in numeric:
        rows = shape[0] if shape else 1
        if dtype.kind == "f":
            add("nonfinite", f"{name} one NaN", h5_edit(set_element(name, np.nan)))
            add("nonfinite", f"{name} one +Inf", h5_edit(set_element(name, np.inf)))
            add("huge", f"{name} one 1e300", h5_edit(set_element(name, 1e300)))
            add("dtype", f"{name} stored as int64",
                h5_edit(lambda f, name=name: replace_dataset(f, name, f[name][()], dtype="<i8")))
            if is_positive_name(name):
                add("sign", f"{name} one zero", h5_edit(set_element(name, 0.0)))
                add("sign", f"{name} negated", h5_edit(scale_all(name, -1.0)))
        else:
            add("huge", f"{name} one 2^62", h5_edit(set_element(name, 2 ** 62)))
            add("dtype", f"{name} stored as float64 (+0.5)",
                h5_edit(lambda f, name=name: replace_dataset(f, name, f[name][()] + 0.5)))
            if INDEX.search(name):
                add("index", f"{name} one -1", h5_edit(set_element(name, -1)))
                add("index", f"{name} one past the largest index",
                    h5_edit(lambda f, name=name: set_element(name, int(f[name][()].max()) + 1)(f)))
            if CELLS.search(name) and len(shape) == 2 and shape[1] >= 2:
                def degenerate(f, name=name):
                    data = f[name][()]
                    data[len(data) // 2, 1] = data[len(data) // 2, 0]
                    replace_dataset(f, name, data)

                def inverted(f, name=name):
                    data = f[name][()]
                    row = len(data) // 2
                    data[row, [0, 1]] = data[row, [1, 0]]
                    replace_dataset(f, name, data)
                add("cells", f"{name} a degenerate row (repeated node)", h5_edit(degenerate))
                add("cells", f"{name} an inverted row (nodes 0 and 1 swapped)", h5_edit(inverted))
        add("dtype", f"{name} as strings",
            h5_edit(lambda f, name=name: replace_dataset(
                f, name, np.array([str(v) for v in f[name][()].reshape(-1)], dtype=object)
                .reshape(f[name].shape), dtype=h5py.string_dtype())))
        if rows > 1:
            add("shape", f"{name} one row fewer",
                h5_edit(lambda f, name=name: replace_dataset(f, name, f[name][()][:-1])))
        if len(shape) == 2:
            add("shape", f"{name} one column more",
                h5_edit(lambda f, name=name: replace_dataset(
                    f, name, np.concatenate([f[name][()], f[name][()][:, :1]], axis=1))))
        if len(shape) >= 1:
            add("shape", f"{name} empty (0 rows)",
                h5_edit(lambda f, name=name, shape=shape, dtype=dtype: replace_dataset(
                    f, name, np.zeros((0,) + tuple(shape[1:]), dtype=dtype))))
            add("shape", f"{name} 2^40 rows (unwritten)",
                h5_edit(lambda f, name=name, shape=shape, dtype=dtype: replace_dataset(
                    f, name, None, dtype=dtype, shape=(2 ** 40,) + tuple(shape[1:]),
                    chunks=(1024,) + tuple(shape[1:]))))
    for obj, key, value in attributes:
        where = f"{obj}@{key}"
        add("attribute", f"{where} removed", h5_edit(del_attr(obj, key)))
        add("attribute", f"{where} as a string", h5_edit(set_attr(obj, key, "abc")))
        if isinstance(value, (float, np.floating)):
            add("nonfinite", f"{where} NaN", h5_edit(set_attr(obj, key, np.nan)))
            add("nonfinite", f"{where} Inf", h5_edit(set_attr(obj, key, np.inf)))
            add("huge", f"{where} 1e300", h5_edit(set_attr(obj, key, 1e300)))
        else:
            add("huge", f"{where} 2^62", h5_edit(set_attr(obj, key, np.int64(2 ** 62))))
        if is_positive_name(key) or (key == "gamma"):
            add("sign", f"{where} zero", h5_edit(set_attr(obj, key, type(value)(0))))
            add("sign", f"{where} negated", h5_edit(set_attr(obj, key, -value)))
        if key == "gamma":
            add("sign", f"{where} 1", h5_edit(set_attr(obj, key, 1.0)))
    return by_class


def choose(by_class, count, rng):
    """`count` mutations, the classes round-robin (in a seeded order), a random one of each."""
    pools = {c: list(v) for c, v in by_class.items() if v}
    order = sorted(pools)
    rng.shuffle(order)
    chosen = []
    while len(chosen) < count and any(pools.values()):
        for cls in order:
            if len(chosen) >= count:
                break
            if pools[cls]:
                label, apply = pools[cls].pop(rng.randrange(len(pools[cls])))
                chosen.append((cls, label, apply))
    return chosen


def make_mutant(valid, apply, target):
    """The mutant at target (a file, or a directory); None, or the error text if the mutation
    itself cannot be made (h5py refuses it)."""
    if apply == "directory":
        os.makedirs(target)
        return None
    shutil.copy(valid, target)
    try:
        apply(target)
    except Exception as e:  # noqa: BLE001  a mutation h5py cannot make is skipped, said so
        return f"{type(e).__name__}: {e}"
    return None


# ---------------------------------------------------------------------------------------------
# Results

def numbers_of_json(value, prefix, out):
    if isinstance(value, dict):
        for k, v in value.items():
            numbers_of_json(v, f"{prefix}/{k}", out)
    elif isinstance(value, list):
        if value and all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in value):
            out[prefix] = np.array(value, dtype=float)
        else:
            for i, v in enumerate(value):
                numbers_of_json(v, f"{prefix}[{i}]", out)
    elif isinstance(value, (int, float)) and not isinstance(value, bool):
        out[prefix] = np.array([value], dtype=float)
    elif isinstance(value, str):
        out[prefix] = value


def result_of(work, command, code, stdout):
    """What a run produced: {key: array or text}, with the exit code."""
    out = {"exit": code}
    for name in sorted(os.listdir(work)):
        path = os.path.join(work, name)
        if not name.startswith("out") or os.path.isdir(path):
            continue
        if name.endswith(".h5"):
            try:
                with h5py.File(path, "r") as f:
                    def visit(n, obj):
                        if n.startswith("provenance"):
                            return
                        if isinstance(obj, h5py.Dataset) and obj.dtype.kind in "fiub":
                            out[f"{name}:{n}"] = np.asarray(obj[()], dtype=float)
                        for k in obj.attrs:
                            v = obj.attrs[k]
                            if isinstance(v, (int, float, np.integer, np.floating)):
                                out[f"{name}:{n}@{k}"] = np.array([v], dtype=float)
                    f.visititems(visit)
            except OSError as e:
                out[f"{name}:unreadable"] = str(e)
        elif name.endswith(".json"):
            try:
                numbers_of_json(json.loads(pathlib.Path(path).read_text()), name, out)
            except ValueError as e:
                out[f"{name}:unreadable"] = str(e)
        elif name.endswith(".csv"):
            rows = list(csv.reader(pathlib.Path(path).read_text().splitlines()))
            if len(rows) >= 2:
                for k, v in zip(rows[0], rows[-1]):
                    if "time" in k or k.endswith("_s"):
                        continue
                    try:
                        out[f"{name}:{k}"] = np.array([float(v)])
                    except ValueError:
                        out[f"{name}:{k}"] = v
    if tool_name(command) == "flow-args":
        out["stdout"] = stdout
    return out


def differences(a, b, ignore):
    """Keys whose values differ beyond RTOL (or exist in one only)."""
    keys = (set(a) | set(b)) - ignore
    changed = []
    for k in sorted(keys):
        if k not in a or k not in b:
            changed.append(k)
            continue
        x, y = a[k], b[k]
        if isinstance(x, np.ndarray) and isinstance(y, np.ndarray):
            if x.shape != y.shape:
                changed.append(k)
                continue
            if x.size == 0:
                continue
            if not np.array_equal(np.isnan(x), np.isnan(y)):
                changed.append(k)
                continue
            finite = ~np.isnan(x)
            scale = np.max(np.abs(x[finite])) if finite.any() else 0.0
            if finite.any() and np.max(np.abs(x[finite] - y[finite])) > RTOL * scale + 1e-300:
                changed.append(k)
        elif not (isinstance(x, str) and isinstance(y, str) and x == y) and x != y:
            changed.append(k)
    return changed


# ---------------------------------------------------------------------------------------------
# Runs

def prepare(work, chain, command, mutant_source):
    """The run folder: the chain's inputs linked, the mutated input as mut-<name>; returns the
    command to run there."""
    os.makedirs(work, exist_ok=True)
    argv = []
    for token in command:
        if token.startswith("@"):
            name = "mut-" + token[1:]
            target = os.path.join(work, name)
            if os.path.isdir(mutant_source):
                os.makedirs(target, exist_ok=True)
            else:
                os.link(mutant_source, target)
            argv.append(name)
        else:
            if not token.startswith("out") and (chain / token).is_file() and "/" not in token:
                if token.endswith((".npz", ".csv")):
                    shutil.copy(chain / token, os.path.join(work, token))  # written by the run
                elif not os.path.exists(os.path.join(work, token)):
                    os.link(chain / token, os.path.join(work, token))
            argv.append(token)
    return argv


def run_one(work, argv, env):
    try:
        done = subprocess.run(argv, cwd=work, env=env, capture_output=True, timeout=TIMEOUT)
    except subprocess.TimeoutExpired as e:
        return None, "", (e.stderr or b"").decode(errors="replace"), True
    return (done.returncode, done.stdout.decode(errors="replace"),
            done.stderr.decode(errors="replace"), False)


def mutated_path(label):
    """The dataset, group or attribute (object@name) a mutation's label names, or None."""
    m = re.match(r"(?:group )?([^\s/@][^\s]*)", label)
    return m.group(1) if m and ("/" in m.group(1) or "@" in m.group(1)) else None


def passed_through(mutated, baseline, result):
    """Output keys of the mutated object itself that a tool copies from its input to its output
    (tfmb-heat the mesh, tfmb-couple the wall points): a copy, not a changed result; the next
    reader checks it again."""
    if not mutated:
        return set()
    return {k for k in set(baseline) | set(result) if ":" in k
            and re.fullmatch(re.escape(mutated) + r"([/@].*)?", k.split(":", 1)[1])}


def classify(tool, mutated_name, inputs, left, code, stderr, timed_out, result, baseline, ignore,
             valid_alone, mutated=None):
    """(class, detail) of one run; `mutated`: the object the mutation changed."""
    if timed_out:
        return "crash", f"timed out after {TIMEOUT} s"
    if code < 0 or code == 4 or code not in RESULT_CODES.get(tool, DEFAULT_RESULT_CODES) | {3}:
        return "crash", f"{corrupt.outcome(code, False)}: {stderr.strip()[-300:]}"
    if "Traceback (most recent call last)" in stderr:
        return "crash", f"a Python traceback: {stderr.strip()[-300:]}"
    if code == 3:
        lines = stderr.strip().splitlines()
        last = lines[-1] if lines else ""
        if mutated_name not in last:
            others = [i for i in inputs if i in last]
            if not (others and valid_alone()):
                return "unlocated", f"last line: {last[-300:]!r}"
        if left:
            return "leftover", f"exit 3 left {', '.join(left)}"
        return "refused", ""
    if tool == "tfmb-check":
        return "accepted", ""
    changed = differences(baseline, result, ignore | passed_through(mutated, baseline, result))
    if changed:
        detail = ", ".join(changed[:4]) + (f" (+{len(changed) - 4} more)" if len(changed) > 4 else "")
        if "exit" in changed:
            detail = f"exit {code}, baseline {baseline['exit']}; " + detail
        return "accepted-changed", detail
    return "accepted-unchanged", ""


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("source")
    parser.add_argument("bin")
    parser.add_argument("scratch")
    parser.add_argument("--seed", type=int, default=23)
    parser.add_argument("--per-kind", type=int, default=25,
                        help="mutants per kind of the chain's files, each run by every reader")
    parser.add_argument("--per-example", type=int, default=8,
                        help="mutants per kind of tfmb-check --example, run by tfmb-check")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--kinds", help="comma-separated kinds (default: all)")
    parser.add_argument("--keep", action="store_true", help="keep every run's folder")
    parser.add_argument("--known", help="file of findings known and not fixed yet, one per line "
                        "as printed after FINDING (finding: kind origin #k (mutation) -> reader); "
                        "they are reported as KNOWN and do not fail the run")
    args = parser.parse_args()
    start = time.monotonic()
    src = pathlib.Path(args.source).resolve()
    bin_dir = os.path.abspath(args.bin)
    scratch = pathlib.Path(args.scratch).resolve()
    shutil.rmtree(scratch, ignore_errors=True)
    scratch.mkdir(parents=True)
    env = dict(os.environ, OMP_WAIT_POLICY="passive", OMP_NUM_THREADS="1")

    # The coarse chain, its strain.h5 and a first coupling step's history (for --used).
    try:
        chain, _ = run_sample_runs.setup_case(src, pathlib.Path(bin_dir), scratch,
                                              run_sample_runs.DEFAULT_CASE, env)
    except run_sample_runs.SetupError as e:
        print(f"mutation suite: the chain's set-up failed: {e}", file=sys.stderr)
        return 2
    flow_args = subprocess.run([str(src / "workflows" / "flow-args"), "model.h5", "--model", "sa"],
                               cwd=chain, capture_output=True, text=True, check=True).stdout.split()
    for command in ([os.path.join(bin_dir, "tfmb-strain"), "structure.h5", "materials.h5",
                     "-o", "strain.h5"],
                    [str(src / "workflows" / "tfmb-couple"), "--iteration", "1", "--raw",
                     "walldisp.h5", "--model", "model.h5", "--state", "state.npz", "--log",
                     "log.csv", "-o", "walldisp-next.h5"]):
        done = subprocess.run(command, cwd=chain, env=env, capture_output=True, text=True)
        if done.returncode not in (0, 10):
            print(f"mutation suite: set-up {' '.join(command)} exited {done.returncode}: "
                  f"{done.stderr.strip()[-300:]}", file=sys.stderr)
            return 2

    table = consumers(src, bin_dir, flow_args)
    kinds = list(CHAIN_FILES)
    if args.kinds:
        kinds = [k for k in args.kinds.split(",") if k in CHAIN_FILES]
    check = os.path.join(bin_dir, "tfmb-check")

    # Mutants: the chain's files and tfmb-check's examples.
    mutant_dir = scratch / "mutants"
    mutant_dir.mkdir()
    mutants = []  # (kind, source, index, class, label, path)
    skipped = 0
    for kind in kinds:
        sources = [("chain", chain / CHAIN_FILES[kind], args.per_kind)]
        example = scratch / "examples" / f"{kind}.h5"
        example.parent.mkdir(exist_ok=True)
        subprocess.run([check, "--example", kind, "-o", str(example)], check=True,
                       capture_output=True)
        if args.per_example > 0:
            sources.append(("example", example, args.per_example))
        for origin, valid, count in sources:
            rng = random.Random(args.seed * 1000003 + zlib.crc32(f"{origin} {kind}".encode()))
            for k, (cls, label, apply) in enumerate(choose(candidates(valid, kind, rng), count, rng)):
                path = mutant_dir / f"{origin}-{kind}-{k:03d}" / CHAIN_FILES[kind]
                path.parent.mkdir()
                error = make_mutant(valid, apply, path)
                if error:
                    skipped += 1
                    print(f"skipped {origin} {kind} #{k} ({label}): {error}", flush=True)
                    continue
                mutants.append((kind, origin, k, cls, label, path))

    # Baselines: every reader on the unmutated file, twice; what differs between the two is
    # not compared.
    def run_baseline(job):
        i, rep = job
        kind, label, command = table[i]
        work = scratch / "baseline" / f"{i:02d}-{rep}"
        marked = next(t for t in command if t.startswith("@"))
        argv = prepare(work, chain, command, chain / marked[1:])
        code, stdout, stderr, timed_out = run_one(work, argv, env)
        return i, code, stderr, timed_out, (None if timed_out else
                                            result_of(work, command, code, stdout))

    baselines = {}
    baseline_jobs = [(i, rep) for i, (kind, _, _) in enumerate(table) if kind in kinds
                     for rep in range(2)]
    results = {}
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        for i, code, stderr, timed_out, result in pool.map(run_baseline, baseline_jobs):
            kind, label, command = table[i]
            expected = RESULT_CODES.get(tool_name(command), DEFAULT_RESULT_CODES)
            if timed_out or code not in expected:
                print(f"mutation suite: baseline {label} ({kind}) exited "
                      f"{corrupt.outcome(code, timed_out)}: {stderr.strip()[-300:]}",
                      file=sys.stderr)
                return 2
            results.setdefault(i, []).append(result)
    for i, (first, second) in sorted(results.items()):
        kind, label, _ = table[i]
        ignore = set(differences(first, second, set()))
        baselines[i] = (first, ignore)
        print(f"baseline {kind:12s} {label}: exit {first['exit']}"
              + (f", {len(ignore)} values differ between two runs, not compared" if ignore else ""),
              flush=True)

    valid_alone_cache = {}

    def valid_alone(path):
        if path not in valid_alone_cache:
            valid_alone_cache[path] = subprocess.run(
                [check, "--no-summary", str(path)], capture_output=True).returncode == 0
        return valid_alone_cache[path]

    jobs = []
    for kind, origin, k, cls, mlabel, path in mutants:
        for i, (ckind, label, command) in enumerate(table):
            if ckind != kind or (origin == "example" and tool_name(command) != "tfmb-check"):
                continue
            jobs.append((kind, origin, k, cls, mlabel, path, i, label, command))

    def execute(job):
        kind, origin, k, cls, mlabel, path, i, label, command = job
        work = scratch / "runs" / f"{origin}-{kind}-{k:03d}-{i:02d}"
        argv = prepare(work, chain, command, path)
        code, stdout, stderr, timed_out = run_one(work, argv, env)
        result = result_of(work, command, code, stdout) if not timed_out else {}
        mutated = "mut-" + path.name
        inputs = [t for t in argv if t.endswith((".h5", ".npz")) and not t.startswith("out")
                  and t != mutated]
        baseline, ignore = baselines[i]
        left = sorted(n for n in os.listdir(work) if n.startswith("out"))
        verdict, detail = classify(tool_name(command), mutated, inputs, left, code, stderr, timed_out,
                                   result, baseline, ignore, lambda: valid_alone(path),
                                   mutated_path(mlabel))
        if verdict in ("refused", "accepted", "accepted-unchanged") and not args.keep:
            shutil.rmtree(work, ignore_errors=True)
        return job, verdict, detail, code

    print(f"{len(mutants)} mutants ({skipped} could not be made), {len(jobs)} runs, "
          f"{args.jobs} at a time", flush=True)
    known = set()
    if args.known:
        for line in pathlib.Path(args.known).read_text().splitlines():
            if line.strip() and not line.startswith("#"):
                known.add(line.strip())
    counts = {}
    findings = []
    known_found = set()
    finding_classes = ("crash", "leftover", "unlocated", "accepted-changed")
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        for job, verdict, detail, code in pool.map(execute, jobs):
            kind, origin, k, cls, mlabel, path, i, label, command = job
            row = counts.setdefault((kind, label), {})
            row[verdict] = row.get(verdict, 0) + 1
            if verdict in finding_classes:
                key = f"{verdict}: {kind} {origin} #{k} ({mlabel}) -> {label}"
                if key in known:
                    known_found.add(key)
                    print(f"KNOWN {key}: {detail}", flush=True)
                    continue
                findings.append({"finding": verdict, "kind": kind, "tool": label, "origin": origin,
                                 "mutant": k, "class": cls, "mutation": mlabel, "exit": code,
                                 "detail": detail, "file": str(path),
                                 "run": str(scratch / "runs" / f"{origin}-{kind}-{k:03d}-{i:02d}")})
                print(f"FINDING {key}: {detail}", flush=True)

    columns = ["refused", "accepted", "accepted-unchanged", "accepted-changed", "unlocated",
               "leftover", "crash"]
    print()
    print(f"{'kind':12s} {'reader':36s} {'runs':>5s} " + " ".join(f"{c:>9.9s}" for c in columns))
    for (kind, label), row in sorted(counts.items()):
        print(f"{kind:12s} {label:36s} {sum(row.values()):5d} "
              + " ".join(f"{row.get(c, 0):9d}" for c in columns))
    total = {c: sum(r.get(c, 0) for r in counts.values()) for c in columns}
    (scratch / "findings.json").write_text(json.dumps(findings, indent=1) + "\n")
    print(f"mutation suite: {len(mutants)} mutants of {len(kinds)} kinds, {len(jobs)} runs in "
          f"{time.monotonic() - start:.0f} s: {total['crash']} crashes, {total['leftover']} "
          f"leftovers, {total['unlocated']} unlocated rejections, {total['accepted-changed']} "
          f"accepted that change a result ({total['refused']} refused, "
          f"{total['accepted-unchanged']} accepted unchanged, {total['accepted']} accepted by "
          f"tfmb-check); findings in {scratch / 'findings.json'}")
    for key in sorted(known - known_found):
        print(f"known finding not seen this time (fixed? then remove it from {args.known}): {key}")
    if known:
        print(f"mutation suite: {len(known_found)} known findings of {args.known} seen, not counted")
    return 1 if findings else 0


if __name__ == "__main__":
    sys.exit(main())
