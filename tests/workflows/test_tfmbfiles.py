#!/usr/bin/python3
"""formats/python/tfmbfiles.py, the Python scripts' one reader of tfmb files: its table of major
versions agrees with the specs, it reads good files, and every bad file (missing, not HDF5, wrong
kind, wrong major version, missing dataset, wrong shape, NaN, ...) gives one BadInput line naming
the file and the object in it; the scripts built on it turn that into exit 3 and one line.
Arguments: source dir, scratch dir."""
import glob
import os
import re
import shutil
import subprocess
import sys

import h5py
import numpy as np

src, scratch = sys.argv[1], sys.argv[2]
sys.path.insert(0, os.path.join(src, "formats", "python"))
import tfmbfiles  # noqa: E402
from tfmbfiles import BadInput, attr, dataset, group, open_kind, text  # noqa: E402

shutil.rmtree(scratch, ignore_errors=True)
os.makedirs(scratch)
os.chdir(scratch)
failures = []

# The majors table against the first line of every spec: `# \`kind\` file (\`format = "tfmb/kind"\`, version X.Y)`.
specs = {}
for md in sorted(glob.glob(os.path.join(src, "formats", "*.md"))):
    m = re.match(r'# `([\w-]+)` file \(`format = "tfmb/\1"`, version (\d+)\.(\d+)\)', open(md).readline())
    if m:
        specs[m.group(1)] = int(m.group(2))
if specs != tfmbfiles.MAJORS:
    failures.append(f"MAJORS {tfmbfiles.MAJORS} differ from the spec headers {specs}")


def write(path, kind="walldisp", version="1.1", walls=None, **root):
    """A small walldisp-like file; `walls` maps wall names to displacement arrays."""
    with h5py.File(path, "w") as f:
        if kind is not None:
            f.attrs["format"] = f"tfmb/{kind}"
        if version is not None:
            f.attrs["format_version"] = version
        for key, value in root.items():
            f.attrs[key] = value
        for name, d in (walls if walls is not None else {"upper": np.zeros((3, 2))}).items():
            f[f"walls/{name}/displacement"] = d
            f[f"walls/{name}/node"] = np.arange(len(d), dtype=np.int64)
    return path


def expect_bad(label, call, *located):
    """`call` must raise BadInput whose message is one line containing every `located` text."""
    try:
        call()
    except BadInput as e:
        message = str(e)
        if "\n" in message or not all(t in message for t in located):
            failures.append(f"{label}: message {message!r} lacks {located} or is not one line")
        else:
            print(f"ok   {label}: {message}")
        return
    except Exception as e:  # anything else is a traceback in the scripts: exit 1, not 3
        failures.append(f"{label}: {type(e).__name__} instead of BadInput: {e}")
        return
    failures.append(f"{label}: accepted")


def read(path, kinds="walldisp", key="walls/upper/displacement", **options):
    with open_kind(path, kinds) as f:
        return dataset(f, key, **options)


# A good file reads; another minor version, a list of kinds and bytes attributes are fine.
good = write("good.h5", version="1.7", wall_source=np.bytes_(b"model"), count=np.int64(3),
             scale=2.5, flag=np.int64(1))
assert read(good, ["flow", "walldisp"], shape=(None, 2)).shape == (3, 2)
with open_kind(good, "walldisp") as f:
    assert text(f.attrs["wall_source"]) == "model" and attr(f, "/", "wall_source", str) == "model"
    assert attr(f, "/", "count", int) == 3 and attr(f, "/", "scale") == 2.5
    assert attr(f, "/", "flag", bool) is True and attr(f, "/", "absent", default=0.0) == 0.0
    assert sorted(group(f, "walls")) == ["upper"]
    assert dataset(f, "walls/upper/node", int).dtype == np.int64

expect_bad("missing file", lambda: read("absent.h5"), "absent.h5: no such file")
open("text.h5", "w").write("not HDF5\n")
expect_bad("not HDF5", lambda: read("text.h5"), "text.h5: not an HDF5 file")
expect_bad("no format", lambda: read(write("noformat.h5", kind=None)),
           "noformat.h5: /: missing attribute 'format'")
expect_bad("wrong format", lambda: read(write("flow.h5", kind="flow")),
           "flow.h5: /: attribute 'format' is 'tfmb/flow', expected 'tfmb/walldisp'")
expect_bad("wrong format among kinds", lambda: read(write("loads.h5", kind="loads"), ["flow", "thermal"]),
           "loads.h5: /: ", "expected 'tfmb/flow' or 'tfmb/thermal'")
expect_bad("no version", lambda: read(write("noversion.h5", version=None)),
           "noversion.h5: /: missing attribute 'format_version'")
expect_bad("malformed version", lambda: read(write("badversion.h5", version="one")),
           "badversion.h5: /: attribute 'format_version' is 'one'")
expect_bad("wrong major version", lambda: read(write("major.h5", version="2.0")),
           "major.h5: /: unknown major format_version 2.0 (this build reads 1.x)")
expect_bad("missing dataset", lambda: read(good, key="walls/lower/displacement"),
           "good.h5: /walls/lower/displacement: missing dataset")
expect_bad("group for a dataset", lambda: read(good, key="walls/upper"),
           "good.h5: /walls/upper: is a group, expected a dataset")
expect_bad("wrong shape", lambda: read(write("shape.h5", walls={"upper": np.zeros((3, 3))}), shape=(None, 2)),
           "shape.h5: /walls/upper/displacement: wrong shape (3,3), expected (n,2)")
expect_bad("wrong rank", lambda: read(write("rank.h5", walls={"upper": np.zeros(4)}), shape=(None, 2)),
           "rank.h5: /walls/upper/displacement: wrong shape (4,), expected (n,2)")
nan = np.zeros((3, 2))
nan[1, 1] = np.nan
expect_bad("NaN", lambda: read(write("nan.h5", walls={"upper": nan})),
           "nan.h5: /walls/upper/displacement: non-finite value nan at flat index 3 (row 1, column 1)")
expect_bad("infinity", lambda: read(write("inf.h5", walls={"upper": np.array([1.0, np.inf])})),
           "inf.h5: /walls/upper/displacement: non-finite value inf at flat index 1")
expect_bad("float for int", lambda: read(good, key="walls/upper/displacement", dtype=int),
           "good.h5: /walls/upper/displacement: wrong dtype float64, expected int64")
expect_bad("index out of range", lambda: read(good, key="walls/upper/node", dtype=int, below=2),
           "good.h5: /walls/upper/node: index 2 at flat index 2 out of range [0, 2)")
assert list(read(good, key="walls/upper/node", dtype=int, below=3)) == [0, 1, 2]
expect_bad("int for float", lambda: read(write("int.h5", walls={"upper": np.ones((3, 2), np.int64)})),
           "int.h5: /walls/upper/displacement: wrong dtype int64, expected float64")
expect_bad("zero for a positive", lambda: read(good, positive=True),
           "good.h5: /walls/upper/displacement: value 0.0 at flat index 0 is not positive")
assert read(write("ones.h5", walls={"upper": np.ones((3, 2))}), positive=True).shape == (3, 2)
strings = write("strings.h5", walls={"upper": np.array([b"a", b"b"])})
expect_bad("strings for floats", lambda: read(strings), "strings.h5: /walls/upper/displacement: wrong dtype")

# throat_height (flow-args' --throat-area): a flap of a half without its inner_wall is refused,
# not left out of the throat.
with h5py.File("throat.h5", "w") as f:
    f.attrs["format"], f.attrs["format_version"] = "tfmb/model", "2.7"
    for name, half, y in (("u", "upper", 1.0), ("l", "lower", -1.0)):
        f.create_group(f"flaps/{name}").attrs["half"] = half
        f[f"flaps/{name}/inner_wall"] = np.array([[0.0, y], [1.0, y]])
with open_kind("throat.h5", "model") as f:
    assert tfmbfiles.throat_height(f) == 2.0
with h5py.File("throat.h5", "r+") as f:
    del f["flaps/l/inner_wall"]


def inside_model(path, read_with):
    with open_kind(path, "model") as f:
        return read_with(f)


expect_bad("throat without an inner wall", lambda: inside_model("throat.h5", tfmbfiles.throat_height),
           "throat.h5: /flaps/l/inner_wall: missing dataset")


# mesh_throat_height (flow-args --mesh): the gap between the mesh's inner walls of the upper and
# lower flaps, wherever the walls now are (a two-way iterate's moved mesh), not the model's.
# Model: u at y = 1, l at y = -1 (gap 2). Mesh: u's inner wall moved up to y = 1.5 at one end
# (gap 2.25 at the other), an outer wall and an unnamed wall closer in that do not count.
def write_mesh(path, boundaries):
    with h5py.File(path, "w") as f:
        f.attrs["format"], f.attrs["format_version"] = "tfmb/flowmesh", "1.0"
        f["mesh/points"] = np.array([[0.0, 1.5], [0.5, 1.4], [1.0, 1.25], [0.0, -1.0], [1.0, -1.0],
                                     [0.5, 0.1], [0.5, -0.1]])
        for name, (edges, attrs) in boundaries.items():
            g = f.create_group(f"mesh/boundaries/{name}")
            g["edges"] = np.array(edges, dtype=np.int64)
            for k, v in attrs.items():
                g.attrs[k] = v


with h5py.File("throat.h5", "w") as f:
    f.attrs["format"], f.attrs["format_version"] = "tfmb/model", "2.7"
    for name, half, y in (("u", "upper", 1.0), ("l", "lower", -1.0)):
        f.create_group(f"flaps/{name}").attrs["half"] = half
        f[f"flaps/{name}/inner_wall"] = np.array([[0.0, y], [1.0, y]])
walls = {"u_inner": ([[0, 1], [1, 2]], {"kind": "wall", "flap": "u", "side": "inner"}),
         "l_inner": ([[3, 4]], {"kind": "wall", "flap": "l", "side": "inner"}),
         "u_outer": ([[5, 6]], {"kind": "wall", "flap": "u", "side": "outer"}),
         "plenum": ([[6, 5]], {"kind": "wall"})}
write_mesh("moved.h5", walls)


def mesh_throat(model, mesh):
    with open_kind(model, "model") as f, open_kind(mesh, ["flowmesh", "flow"]) as m:
        return tfmbfiles.mesh_throat_height(f, m)


assert abs(mesh_throat("throat.h5", "moved.h5") - 2.25) < 1e-12, mesh_throat("throat.h5", "moved.h5")
assert inside_model("throat.h5", tfmbfiles.throat_height) == 2.0
write_mesh("stranger.h5", {**walls, "x_inner": ([[5, 6]], {"kind": "wall", "flap": "x", "side": "inner"})})
expect_bad("mesh wall of a flap the model lacks", lambda: mesh_throat("throat.h5", "stranger.h5"),
           "stranger.h5: /mesh/boundaries/x_inner: flap 'x' is not a flap of throat.h5")
write_mesh("far.h5", {**walls, "l_inner": ([[3, 9]], {"kind": "wall", "flap": "l", "side": "inner"})})
expect_bad("mesh wall edge out of range", lambda: mesh_throat("throat.h5", "far.h5"),
           "far.h5: /mesh/boundaries/l_inner/edges: index 9 at flat index 1 out of range [0, 7)")


def read_attr(path, key, name, kind=float):
    with open_kind(path, "walldisp") as f:
        return attr(f, key, name, kind)


def inside(path, read_with):
    with open_kind(path, "walldisp") as f:
        return read_with(f)


bad_attrs = write("attrs.h5", wall_source=np.bytes_(b"model"), nan=np.nan, half=0.5, pair=np.ones(2))
expect_bad("missing group", lambda: read_attr(good, "conditions", "gamma"), "good.h5: /conditions: missing group")
expect_bad("missing group of a dataset", lambda: inside(good, lambda f: dataset(f, "x/y")),
           "good.h5: /x/y: missing dataset")
expect_bad("missing group (group)", lambda: inside(good, lambda f: group(f, "flaps")),
           "good.h5: /flaps: missing group")
expect_bad("missing attribute", lambda: read_attr(good, "/", "gamma"), "good.h5: /: missing attribute 'gamma'")
expect_bad("non-finite attribute", lambda: read_attr(bad_attrs, "/", "nan"),
           "attrs.h5: /: attribute 'nan' is not finite (nan)")
expect_bad("text for a number", lambda: read_attr(bad_attrs, "/", "wall_source"),
           "attrs.h5: /: attribute 'wall_source' is 'model', expected a number")
expect_bad("fraction for an integer", lambda: read_attr(bad_attrs, "/", "half", int),
           "attrs.h5: /: attribute 'half' is 0.5, expected an integer")
expect_bad("vector for a scalar", lambda: read_attr(bad_attrs, "/", "pair"),
           "attrs.h5: /: attribute 'pair' is not a scalar")

# The scripts: a bad input file is exit 3 and one line "<script>: error: FILE: ...".
run_dir = os.path.join(scratch, "run")
os.makedirs(run_dir)
write(os.path.join(run_dir, "flow.h5"), kind="flow", version="1.3")  # a flow file without /integrals
scripts = [
    ("flow-args missing", [f"{src}/workflows/flow-args", "/nonexistent.h5"], "/nonexistent.h5: no such file"),
    ("flow-args wrong kind", [f"{src}/workflows/flow-args", good], "good.h5: /: attribute 'format'"),
    ("flow-args wrong major", [f"{src}/workflows/flow-args", write("model1.h5", kind="model", version="1.0")],
     "model1.h5: /: unknown major"),
    ("flow-args --mesh wrong kind", [f"{src}/workflows/flow-args", "throat.h5", "--mesh", good],
     "good.h5: /: attribute 'format' is 'tfmb/walldisp', expected 'tfmb/flowmesh' or 'tfmb/flow'"),
    ("case-summary", [f"{src}/workflows/case-summary", run_dir], "flow.h5: /integrals: missing group"),
    ("tfmb-couple", [f"{src}/workflows/tfmb-couple", "--iteration", "1", "--raw", "nan.h5", "--state",
                     "s.npz", "--log", "l.csv"], "nan.h5: /walls/upper/displacement: non-finite"),
    ("tfmb-couple --model", [f"{src}/workflows/tfmb-couple", "--iteration", "1", "--raw", good, "--state",
                             "s.npz", "--log", "l.csv", "--model", good], "good.h5: /: attribute 'format'"),
    ("nodal-forces", [f"{src}/workflows/nodal-forces", "lump", "text.h5", "-o", "x.h5"],
     "text.h5: not an HDF5 file"),
    ("tfmb-plot (source)", [f"{src}/tools/tfmb-plot/tfmb-plot", "strain", good, "-o", "x.png"],
     "good.h5: /: attribute 'format' is 'tfmb/walldisp', expected 'tfmb/strain'"),
]
for label, command, located in scripts:
    r = subprocess.run(command, capture_output=True, text=True)
    name = os.path.basename(command[0])
    lines = r.stderr.splitlines()
    if r.returncode != 3 or len(lines) != 1 or not lines[0].startswith(f"{name}: error: ") \
            or located not in lines[0]:
        failures.append(f"{label}: exit {r.returncode}, stderr {r.stderr!r}; expected 3 and one line with {located!r}")
    else:
        print(f"ok   {label}: {lines[0]}")

# nodal-forces lump leaves no temporary file when an input turns out bad after the output was
# begun (a dangling link in place of nodal_force; the mutation suite found lumped.h5.tmp left).
with h5py.File("dangling-loads.h5", "w") as f:
    f.attrs["format"], f.attrs["format_version"] = "tfmb/loads", "1.2"
    f["flaps/a/s"] = np.array([0.0, 1.0])
    f["flaps/a/nodal_force"] = h5py.SoftLink("/no/such/dataset")
r = subprocess.run([f"{src}/workflows/nodal-forces", "lump", "dangling-loads.h5", "-o", "lumped.h5"],
                   capture_output=True, text=True)
left = [n for n in os.listdir(".") if n.startswith("lumped.h5")]
if r.returncode != 3 or left or "dangling-loads.h5: /flaps/a/nodal_force" not in r.stderr:
    failures.append(f"nodal-forces lump on a dangling link: exit {r.returncode}, left {left}, "
                    f"stderr {r.stderr!r}")
else:
    print("ok   nodal-forces lump on a dangling link: exit 3, nothing left")

# tfmb-couple checks the wall points beside the displacement: an empty displacement beside three
# x0 rows was iterated on as a wall of no points (the mutation suite).
with h5py.File("empty-displacement.h5", "w") as f:
    f.attrs["format"], f.attrs["format_version"] = "tfmb/walldisp", "1.1"
    f["walls/upper/displacement"] = np.zeros((0, 2))
    f["walls/upper/x0"] = np.zeros((3, 2))
r = subprocess.run([f"{src}/workflows/tfmb-couple", "--iteration", "1", "--raw", "empty-displacement.h5",
                    "--state", "s.npz", "--log", "l.csv", "-o", "next.h5"], capture_output=True, text=True)
if r.returncode != 3 or "empty-displacement.h5: /walls/upper/x0: wrong shape (3,2), expected (0,2)" \
        not in r.stderr or os.path.exists("next.h5") or os.path.exists("s.npz"):
    failures.append(f"tfmb-couple with x0 and displacement of other lengths: exit {r.returncode}, "
                    f"stderr {r.stderr!r}")
else:
    print("ok   tfmb-couple with x0 and displacement of other lengths: exit 3")

with h5py.File("no-points.h5", "w") as f:
    f.attrs["format"], f.attrs["format_version"] = "tfmb/walldisp", "1.1"
    f["walls/upper/displacement"] = np.zeros((0, 2))
    f["walls/upper/x0"] = np.zeros((0, 2))
r = subprocess.run([f"{src}/workflows/tfmb-couple", "--iteration", "1", "--raw", "no-points.h5",
                    "--state", "s.npz", "--log", "l.csv", "-o", "next.h5"], capture_output=True, text=True)
if r.returncode != 3 or "no-points.h5: /walls: no wall points" not in r.stderr:
    failures.append(f"tfmb-couple on a walldisp without points: exit {r.returncode}, stderr {r.stderr!r}")
else:
    print("ok   tfmb-couple on a walldisp without points: exit 3")

# ... and refuses a flap without distributed_force in one line (it was a KeyError traceback).
with h5py.File("no-distributed.h5", "w") as f:
    f.attrs["format"], f.attrs["format_version"] = "tfmb/loads", "1.2"
    f["flaps/a/s"] = np.array([0.0, 1.0])
    for key in ("nodal_force", "nodal_moment", "distributed_moment"):
        f[f"flaps/a/{key}"] = np.zeros((2, 3))
r = subprocess.run([f"{src}/workflows/nodal-forces", "lump", "no-distributed.h5", "-o", "lumped.h5"],
                   capture_output=True, text=True)
if r.returncode != 3 or "no-distributed.h5: /flaps/a/distributed_force: missing dataset" not in r.stderr \
        or os.listdir(".").count("lumped.h5.tmp"):
    failures.append(f"nodal-forces lump without distributed_force: exit {r.returncode}, stderr {r.stderr!r}")
else:
    print("ok   nodal-forces lump without distributed_force: exit 3")

if failures:
    print("\n".join(f"FAIL {f}" for f in failures))
    sys.exit(1)
print("tfmbfiles tests passed")
