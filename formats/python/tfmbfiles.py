"""tfmbfiles: open and read tfmb files (formats/*.md) from the Python scripts, checks in one place.

    f = open_kind(path, "walldisp")              # h5py.File, identity and major version checked
    d = dataset(f, "walls/upper/displacement", shape=(None, 2))   # float64, finite, (n,2)
    p = attr(f, "conditions", "ambient_pressure")                 # float, finite
    names = sorted(group(f, "walls"))

Every problem raises BadInput, whose message is one line naming the file and the object in it,
"FILE: /object: what is wrong" ("FILE: what is wrong" when the file itself cannot be opened), as
the C++ readers word them; the scripts print it after their name and exit 3 (bad input). A file
whose HDF5 structures are damaged (flipped bytes, truncation) makes h5py raise OSError, KeyError,
RuntimeError, ... from any access; every function here turns that into BadInput naming the object
it was reading ("FILE: /object: damaged or unreadable (...)"), so no script shows a traceback.
"""
import os

import numpy as np

# Major format_version each kind's reader understands (formats/<kind>.md, first line). A table
# rather than parsing the specs at import time: the copy installed next to tfmb-plot has no
# formats/ directory to parse, so the table would be needed anyway, and one source cannot
# disagree with another. tests/workflows/test_tfmbfiles.py checks it against the spec headers.
MAJORS = {"model": 2, "flowmesh": 1, "solidmesh": 1, "flow": 1, "thermal": 1, "material-db": 1,
          "materials": 1, "loads": 1, "walldisp": 1, "structure": 1, "strain": 1}

_REQUIRED = object()


class BadInput(Exception):
    """A bad input file; str() is one located line."""

    @classmethod
    def at(cls, f, key, what):
        """BadInput for object `key` of file `f` (an h5py.File or a path)."""
        return cls(f"{getattr(f, 'filename', f)}: /{key.strip('/')}: {what}")

    @classmethod
    def damaged(cls, f, key, error):
        """BadInput for an h5py/numpy error met reading object `key` of `f` (a damaged file)."""
        detail = str(error).splitlines()[0] if str(error) else ""
        return cls.at(f, key, f"damaged or unreadable ({type(error).__name__}"
                      f"{': ' + detail[:160] if detail else ''})")


class _Guard:
    """`with guard(f, key):` turns any error but BadInput into BadInput.damaged(f, key, ...):
    for a script that reads an object of an open file directly (h5py) rather than through the
    functions below."""

    def __init__(self, f, key):
        self.f, self.key = f, key

    def __enter__(self):
        return self

    def __exit__(self, kind, error, trace):
        if kind is None or issubclass(kind, (BadInput, KeyboardInterrupt, SystemExit)):
            return False
        if issubclass(kind, Exception):
            raise BadInput.damaged(self.f, self.key, error) from None
        return False


guard = _Guard


def text(value):
    """An attribute's value as str: h5py gives bytes for fixed-length strings, str otherwise."""
    if isinstance(value, np.ndarray) and value.shape == ():
        value = value[()]
    return value.decode() if isinstance(value, bytes) else str(value)


def open_kind(path, kinds):
    """Opens `path` for reading after checking it is an HDF5 file whose root @format is
    tfmb/<kind> for one of `kinds` (a name or a list) with the major @format_version this module
    reads (minor versions only add optional content). Use as a context manager."""
    import h5py  # here, so that --help and usage errors do not wait for h5py
    kinds = [kinds] if isinstance(kinds, str) else list(kinds)
    if not os.path.isfile(path):
        raise BadInput(f"{path}: no such file")
    try:
        f = h5py.File(path, "r")
    except OSError:
        raise BadInput(f"{path}: not an HDF5 file") from None
    try:
        with _Guard(path, "/"):
            root = {k: f.attrs[k] for k in ("format", "format_version") if k in f.attrs}
        expected = " or ".join(f"'tfmb/{k}'" for k in kinds)
        if "format" not in root:
            raise BadInput.at(path, "/", f"missing attribute 'format' (expected {expected}): "
                              "not a tfmb file?")
        fmt = text(root["format"])
        kind = fmt[5:] if fmt.startswith("tfmb/") else None
        if kind not in kinds:
            raise BadInput.at(path, "/", f"attribute 'format' is '{fmt}', expected {expected}")
        if "format_version" not in root:
            raise BadInput.at(path, "/", "missing attribute 'format_version'")
        version = text(root["format_version"])
        major, dot, minor = version.partition(".")
        if not (dot and major.isdigit() and minor.isdigit()):
            raise BadInput.at(path, "/", f"attribute 'format_version' is '{version}', "
                              "expected 'major.minor'")
        if int(major) != MAJORS[kind]:
            raise BadInput.at(path, "/", f"unknown major format_version {version} (this build "
                              f"reads {MAJORS[kind]}.x); convert the file or update tfmb")
    except BaseException:
        f.close()
        raise
    return f


def group(f, key):
    """The group `key` of `f`, refusing a missing one."""
    import h5py
    with _Guard(f, key):
        if key.strip("/") and key not in f:
            raise BadInput.at(f, key, "missing group")
        g = f[key]
    if not isinstance(g, h5py.Group):
        raise BadInput.at(f, key, "is a dataset, expected a group")
    return g


def members(f, key):
    """The sorted names of the members of group `key` of `f`."""
    g = group(f, key)
    with _Guard(f, key):
        return sorted(g)


def _shape_text(shape):
    """(5,3) -> '(5,3)', (None,2) -> '(n,2)', (7,) -> '(7,)': the C++ readers' spelling."""
    parts = ["n" if n is None else str(n) for n in shape]
    return "(" + ",".join(parts) + ("," if len(parts) == 1 else "") + ")"


def dataset(f, key, dtype=float, shape=None, below=None, positive=False):
    """Dataset `key` of `f` as a numpy array of `dtype` (float: float64, int: int64), refusing a
    missing dataset, a dtype of another kind (integers for floats included: the specs say
    float64), a shape other than `shape`
    (a tuple; None matches any extent), for floats NaN or infinity and, with `below`, values
    outside [0, below) (indices into another dataset) and, with `positive`, values that are not
    above zero (absolute pressures and temperatures)."""
    import h5py
    with _Guard(f, key):
        if key not in f:
            raise BadInput.at(f, key, "missing dataset")
        d = f[key]
        if not isinstance(d, h5py.Dataset):
            raise BadInput.at(f, key, "is a group, expected a dataset")
        stored_dtype, stored_shape = d.dtype, d.shape
    want = np.dtype(np.float64 if dtype is float else np.int64 if dtype is int else dtype)
    # Floats stored as integers are refused, as the C++ readers do (the specs say float64): a
    # displacement written as int64 had lost its fractions, and tfmb-couple iterated on it.
    allowed = "iu" if want.kind in "iu" else want.kind
    if stored_dtype.kind not in allowed:
        raise BadInput.at(f, key, f"wrong dtype {stored_dtype}, expected {want}")
    if shape is not None and (len(stored_shape) != len(shape) or
                              any(n is not None and n != m for n, m in zip(shape, stored_shape))):
        raise BadInput.at(f, key, f"wrong shape {_shape_text(stored_shape)}, expected "
                          f"{_shape_text(shape)}")
    with _Guard(f, key):
        values = np.asarray(d[()], dtype=want)
    if want.kind == "f" and not np.all(np.isfinite(values)):
        i = int(np.flatnonzero(~np.isfinite(values))[0])
        where = f" (row {i // values.shape[1]}, column {i % values.shape[1]})" \
            if values.ndim == 2 and values.shape[1] else ""
        raise BadInput.at(f, key, f"non-finite value {values.flat[i]} at flat index {i}{where}")
    if positive and values.size and not np.all(values > 0):
        i = int(np.flatnonzero(~(values > 0))[0])
        raise BadInput.at(f, key, f"value {values.flat[i]} at flat index {i} is not positive")
    if below is not None and values.size and not (values.min() >= 0 and values.max() < below):
        i = int(np.flatnonzero((values < 0) | (values >= below))[0])
        raise BadInput.at(f, key, f"index {values.flat[i]} at flat index {i} out of range [0, {below})")
    return values


def attr(f, key, name, type=float, default=_REQUIRED):
    """Attribute `name` of object `key` ("/" for the root) as `type`: float (finite), int, bool
    (stored as an integer 0/1) or str. A missing attribute is refused unless `default` is given,
    which is then returned as it is."""
    with _Guard(f, key):
        if key.strip("/") and key not in f:
            raise BadInput.at(f, key, "missing group")
        attrs = f[key].attrs
        present = name in attrs
        value = attrs[name] if present else None
    if not present:
        if default is _REQUIRED:
            raise BadInput.at(f, key, f"missing attribute '{name}'")
        return default
    if type is str:
        return text(value)
    if np.ndim(value) != 0:
        raise BadInput.at(f, key, f"attribute '{name}' is not a scalar")
    value = value[()] if isinstance(value, np.ndarray) else value
    if isinstance(value, (bytes, str)) or not np.isreal(value):
        raise BadInput.at(f, key, f"attribute '{name}' is '{text(value)}', expected a number")
    if type is float:
        if not np.isfinite(value):
            raise BadInput.at(f, key, f"attribute '{name}' is not finite ({value})")
        return float(value)
    if not np.isfinite(value) or value != int(value):
        raise BadInput.at(f, key, f"attribute '{name}' is {value}, expected an integer")
    return bool(int(value)) if type is bool else type(int(value))


def throat_height(f):
    """Of an open model file: the smallest distance between the inner walls of the upper and the
    lower flaps [m] (the throat height per unit depth of a planar nozzle, the discharge
    coefficient's reference), or None when the model has no upper and lower flaps."""
    halves = {"upper": [], "lower": []}
    for name in members(f, "flaps") if "flaps" in f else []:
        half = attr(f, f"flaps/{name}", "half", str, default="")
        # inner_wall is required (model.md): a flap without it was left out, and the throat
        # (and so the discharge coefficient) silently came from the other flaps.
        if half in halves:
            halves[half].append(dataset(f, f"flaps/{name}/inner_wall", shape=(None, 2)))
    return _smallest_gap(halves["upper"], [(p[:-1], p[1:]) for p in halves["lower"]])


def flap_halves(model):
    """{flap name: its @half ("upper", "lower" or "")} of an open model file."""
    return {name: attr(model, f"flaps/{name}", "half", str, default="")
            for name in (members(model, "flaps") if "flaps" in model else [])}


def mesh_throat_height(model, mesh):
    """Of an open model file and an open file with its flow mesh (/mesh: flowmesh or flow): the
    smallest distance between the mesh's inner walls of the model's upper and lower flaps [m],
    i.e. the throat of the walls the flow sees, moved ones included (a two-way iterate's deformed
    mesh: the model's own walls would give the throat before the flaps moved). None when the
    mesh has no inner wall of an upper and of a lower flap."""
    halves = flap_halves(model)
    points = dataset(mesh, "mesh/points", shape=(None, 2))
    inner = []
    for name in members(mesh, "mesh/boundaries"):
        key = f"mesh/boundaries/{name}"
        if attr(mesh, key, "side", str, default="") != "inner":
            continue
        flap = attr(mesh, key, "flap", str)
        if flap not in halves:
            raise BadInput.at(mesh, key, f"flap '{flap}' is not a flap of {model.filename}")
        inner.append((flap, dataset(mesh, f"{key}/edges", int, shape=(None, 2), below=len(points))))
    return inner_wall_gap(points, inner, halves)


def inner_wall_gap(points, inner_walls, halves):
    """The throat of a mesh: the smallest distance between the inner walls of the upper and of the
    lower flaps. `inner_walls` lists (flap name, edge array (m,2) into `points` (n,2)), `halves`
    maps flap names to "upper" / "lower" (flap_halves). None when either half has no edge
    (mesh_throat_height and tfmb-convert import-flow)."""
    edges = {"upper": [], "lower": []}
    for flap, e in inner_walls:
        if halves.get(flap) in edges and len(e):
            edges[halves[flap]].append(np.asarray(e).reshape(-1, 2))
    uppers = [points[np.unique(e)] for e in edges["upper"]]
    lowers = [(points[e[:, 0]], points[e[:, 1]]) for e in edges["lower"]]
    return _smallest_gap(uppers, lowers)


def _smallest_gap(upper_points, lower_segments):
    """The smallest distance from a point of `upper_points` (arrays (n,2)) to a segment of
    `lower_segments` (pairs of arrays (m,2): the segments' starts and ends), or None when either
    list is empty."""
    if not upper_points or not lower_segments:
        return None
    best = np.inf
    for a, b in lower_segments:
        ab = b - a
        length2 = np.maximum((ab * ab).sum(axis=1), 1e-300)
        for points in upper_points:
            for point in points:
                t = np.clip(((point - a) * ab).sum(axis=1) / length2, 0.0, 1.0)
                d = np.hypot(*(a + t[:, None] * ab - point).T)
                best = min(best, float(d.min()))
    return best
