#!/usr/bin/env bash
# tfmb-convert: a gmsh mixed triangle/quad mesh imports into a flowmesh that tfmb-check accepts,
# exports to VTU that meshio reads, and bad inputs exit 3 with a message.
set -euo pipefail
bin="$1"; data="$2"; scratch="$3"
rm -rf "$scratch"; mkdir -p "$scratch"; cd "$scratch"
fail() { echo "FAIL: $*" >&2; exit 1; }

gmsh -2 -format msh22 "$data/mixed_channel.geo" -o mixed.msh > gmsh.log 2>&1
"$bin/tfmb-convert" import mixed.msh -o flowmesh.h5
"$bin/tfmb-check" flowmesh.h5 > check.txt
grep -q "flowmesh 1.0" check.txt || fail "tfmb-check summary"
/usr/bin/python3 - <<'PY'
import h5py, meshio
with h5py.File("flowmesh.h5") as f:
    kinds = {n: f[f"/mesh/boundaries/{n}"].attrs["kind"] for n in f["/mesh/boundaries"]}
    assert kinds == {"inflow": "inflow", "outflow": "outflow", "lower_wall": "wall",
                     "upper_wall": "wall"}, kinds
    assert f["/mesh/cells/quad"].shape == (16, 4) and f["/mesh/cells/triangle"].shape[0] > 0
    pts = f["/mesh/points"][()]
    # every cell counter-clockwise
    for key in ("triangle", "quad"):
        for c in f[f"/mesh/cells/{key}"][()]:
            p = pts[c]
            area2 = sum(p[i,0]*p[(i+1)%len(c),1] - p[(i+1)%len(c),0]*p[i,1] for i in range(len(c)))
            assert area2 > 0, (key, c)
    # boundary edges ordered head to tail
    for n in f["/mesh/boundaries"]:
        e = f[f"/mesh/boundaries/{n}/edges"][()]
        assert all(e[i,1] == e[i+1,0] for i in range(len(e)-1)), n
m = meshio.read("flowmesh.xdmf")
assert len(m.points) > 0
PY
"$bin/tfmb-convert" export flowmesh.h5 -o flowmesh.vtu
/usr/bin/python3 -c "import meshio; m = meshio.read('flowmesh.vtu'); assert len(m.cells) == 2"

# A physical curve and the physical surface may share a tag number in gmsh: the lines take the
# curve's name (the surface's name was taken before: "boundary 'fluid': cannot infer its kind").
sed 's/Physical Curve("inflow")/Physical Curve("inflow", 1)/; s/Physical Surface("fluid")/Physical Surface("fluid", 1)/' \
  "$data/mixed_channel.geo" > clash.geo
gmsh -2 -format msh22 clash.geo -o clash.msh > /dev/null 2>&1
"$bin/tfmb-convert" import clash.msh -o clash.h5 2> err.txt || fail "shared physical tag: $(cat err.txt)"
/usr/bin/python3 -c "import h5py; assert sorted(h5py.File('clash.h5')['/mesh/boundaries']) == ['inflow', 'lower_wall', 'outflow', 'upper_wall']" \
  || fail "shared physical tag: boundary names"

# Export to .su2 and .msh keeps every boundary by name (SU2 marker, gmsh physical curve);
# importing the file back gives the same points, cells and boundaries (edges in the same order).
for ext in su2 msh; do
  "$bin/tfmb-convert" export flowmesh.h5 -o "back.$ext" 2> export.txt || fail "export to .$ext"
  "$bin/tfmb-convert" import "back.$ext" -o "back-$ext.h5" || fail "import of the exported .$ext"
  /usr/bin/python3 - "back-$ext.h5" <<'PY' || fail "round trip through .$ext"
import sys, h5py, numpy as np
with h5py.File("flowmesh.h5") as a, h5py.File(sys.argv[1]) as b:
    for key in ("points", "cells/triangle", "cells/quad"):
        assert np.array_equal(a[f"/mesh/{key}"][()], b[f"/mesh/{key}"][()]), key
    assert sorted(a["/mesh/boundaries"]) == sorted(b["/mesh/boundaries"])
    for n in a["/mesh/boundaries"]:
        assert np.array_equal(a[f"/mesh/boundaries/{n}/edges"][()], b[f"/mesh/boundaries/{n}/edges"][()]), n
        assert a[f"/mesh/boundaries/{n}"].attrs["kind"] == b[f"/mesh/boundaries/{n}"].attrs["kind"], n
PY
done
grep -q 'MARKER_TAG= lower_wall' back.su2 || fail ".su2 marker named by the boundary"
grep -q '"upper_wall"' back.msh || fail ".msh physical curve named by the boundary"
# gmsh itself reads the exported .msh with its physical names.
gmsh back.msh -0 -o regmsh.msh -format msh22 > gmsh-read.log 2>&1 || fail "gmsh cannot read the exported .msh"
grep -q '"inflow"' regmsh.msh || fail "gmsh lost the physical names"
# Boundaries come out with the domain on their left (tfmb-mesh's counter-clockwise loop) whatever
# the direction in the source file.
/usr/bin/python3 - <<'PY' || fail "domain on the left of every boundary"
import h5py, numpy as np
with h5py.File("flowmesh.h5") as f:
    cells = [f["/mesh/cells/triangle"][()], f["/mesh/cells/quad"][()]]
    left = {(int(c[i]), int(c[(i + 1) % len(c)])) for block in cells for c in block for i in range(len(c))}
    for n in f["/mesh/boundaries"]:
        for a, b in f[f"/mesh/boundaries/{n}/edges"][()]:
            assert (int(a), int(b)) in left, (n, a, b)
PY

# import-flow on the channel with a uniform flow (p 1.1e5 Pa, T 300 K, u 100 m/s; OpenFOAM's
# names) against a model whose domain is the channel: boundaries matched to the model's pieces,
# the upper wall a flap's inner wall; density and Mach derived; mass flow rho u H and thrust
# rho u^2 H + (p - p_amb) H through the outflow, exact to round-off; walls' normals leave the
# fluid. A model piece whose mesh edges come in two runs (here a piece that takes the middle of
# the lower wall) is refused with the gap's position.
/usr/bin/python3 - <<'PY'
import h5py, meshio, numpy as np
s = h5py.string_dtype()
def model(path, pieces):
    with h5py.File(path, "w") as f:
        for k, v in (("format", "tfmb/model"), ("format_version", "2.7"), ("geometry", "planar")):
            f.attrs.create(k, v, dtype=s)
        f.attrs["depth"] = 1.0
        for i, (name, (points, kind, flap, side)) in enumerate(pieces.items()):
            g = f.create_group(f"domain/boundaries/{name}")
            g["points"] = np.array(points, float)
            g.attrs.create("kind", kind, dtype=s)
            g.attrs["order"] = np.int64(i)
            if flap:
                g.attrs.create("flap", flap, dtype=s)
                g.attrs.create("side", side, dtype=s)
        f["domain"].attrs.create("kind", "channel", dtype=s)
        c = f.create_group("conditions")
        for k, v in dict(ambient_pressure=1e5, nozzle_pressure_ratio=2.0, exit_pressure_ratio=0.0,
                         stagnation_temperature=320.0, gamma=1.4, gas_constant=287.0).items():
            c.attrs[k] = v
channel = {"lower_wall": ([[0, 0], [2, 0]], "wall", "", ""),
           "outflow": ([[2, 0], [2, 1]], "outflow", "", ""),
           "upper_wall": ([[2, 1], [0, 1]], "wall", "f1", "inner"),
           "inflow": ([[0, 1], [0, 0]], "inflow", "", "")}
model("model.h5", channel)
model("model-gap.h5", dict(channel, a_patch=([[0.8, 0], [1.2, 0]], "wall", "", "")))
m = meshio.read("mixed.msh")
n = len(m.points)
cells = [c for c in m.cells if c.type in ("triangle", "quad")]
meshio.Mesh(m.points, cells, point_data={"p": np.full(n, 1.1e5), "T": np.full(n, 300.0),
                                         "U": np.tile([100.0, 0.0, 0.0], (n, 1))}).write("uniform.vtu")
PY
"$bin/tfmb-convert" import-flow uniform.vtu --model model.h5 -o uniform.h5 2> import-flow.txt \
  || { cat import-flow.txt; fail "import-flow of the uniform channel flow"; }
"$bin/tfmb-check" --no-summary uniform.h5 || fail "tfmb-check of the import"
grep -q "derived from the other fields: density, mach" import-flow.txt || fail "derived fields not said"
/usr/bin/python3 - <<'PY' || fail "uniform channel flow import"
import h5py, numpy as np
f = h5py.File("uniform.h5")
rho = 1.1e5 / (287.0 * 300.0)
i = f["/integrals"].attrs
assert abs(i["mass_flow"] - rho * 100.0) <= 1e-12 * rho * 100.0, i["mass_flow"]
thrust = rho * 100.0 ** 2 + 1e4
assert abs(i["thrust_x"] - thrust) <= 1e-12 * thrust and abs(i["thrust_y"]) <= 1e-9 * thrust
assert sorted(f["/walls"]) == ["lower_wall", "upper_wall"]
b = f["/mesh/boundaries/upper_wall"].attrs
assert (b["kind"], b["flap"], b["side"]) == ("wall", "f1", "inner")
assert "flap" not in f["/mesh/boundaries/lower_wall"].attrs
assert np.allclose(f["/walls/lower_wall/normal"][()], [0, -1]) and np.allclose(f["/walls/upper_wall/normal"][()], [0, 1])
x = f["/walls/lower_wall/x"][()]
assert x[0] == 0.0 and x[-1] == 2.0 and np.all(np.diff(x) > 0)  # domain on the left: +x
assert np.allclose(f["/fields/point/mach"][()], 100.0 / np.sqrt(1.4 * 287.0 * 300.0))
assert np.all(f["/walls/upper_wall/wall_shear"][()] == 0.0)
PY
# What a reader of flow.h5 refuses is not written: a non-positive pressure is refused naming the
# node (exit 3), a negative k (optional) is left out, said so.
/usr/bin/python3 -c "
import meshio, numpy as np
m = meshio.read('uniform.vtu'); n = len(m.points)
m.point_data['k'] = np.linspace(-1.0, 1.0, n); m.write('uniform-k.vtu')
m.point_data['p'][3] = -1.0; m.write('negative-p.vtu')"
"$bin/tfmb-convert" import-flow uniform-k.vtu --model model.h5 -o uniform-k.h5 2> err.txt || fail "import with a negative k"
grep -q "turbulent_kinetic_energy from 'k' not written: -1 at node 0" err.txt || fail "negative k not said: $(cat err.txt)"
/usr/bin/python3 -c "import h5py; assert 'turbulent_kinetic_energy' not in h5py.File('uniform-k.h5')['/fields/point']"
set +e
"$bin/tfmb-convert" import-flow negative-p.vtu --model model.h5 -o negative-p.h5 2> err.txt; rc=$?
[ $rc -eq 3 ] && grep -q "negative-p.vtu: pressure -1 <= 0 at node 3" err.txt || fail "negative pressure: exit $rc, $(cat err.txt)"
/usr/bin/python3 -c "
import meshio, numpy as np
m = meshio.read('uniform.vtu')
meshio.Mesh(m.points, [('polygon', np.array([[0, 1, 2, 3, 4]]))] + [(c.type, c.data) for c in m.cells],
            point_data=m.point_data).write('polygon.vtu')"
"$bin/tfmb-convert" import-flow polygon.vtu --model model.h5 -o polygon.h5 2> err.txt; rc=$?
[ $rc -eq 3 ] && grep -q "cell type 'polygon' is not supported" err.txt || fail "a polygon cell: exit $rc, $(cat err.txt)"
"$bin/tfmb-convert" import-flow uniform.vtu --model model-gap.h5 -o gap.h5 2> err.txt; rc=$?
set -e
[ $rc -eq 3 ] && grep -q "lower_wall form 2 separate runs (a gap at (1.25, 0) m)" err.txt \
  || fail "a wall in two runs: exit $rc, $(cat err.txt)"
[ ! -e gap.h5 ] || fail "a refused import-flow left a file"

# Identical runs give byte-identical files (no times stored: make's hash checks see no change).
for i in 1 2; do
  "$bin/tfmb-convert" import mixed.msh -o again.h5 && cp again.h5 "again-$i.h5"
  "$bin/tfmb-convert" import-flow uniform.vtu --model model.h5 -o again-flow.h5 2> /dev/null && cp again-flow.h5 "again-flow-$i.h5"
  sleep 1.1
done
cmp -s again-1.h5 again-2.h5 && cmp -s again-flow-1.h5 again-flow-2.h5 || fail "identical runs, different bytes"

# A write that fails (a file-size limit: write() fails with EFBIG, as on a full disk) ends with
# exit 4 and a last line naming the output and the system's reason, and leaves nothing behind:
# exports (staging folder) and HDF5 outputs (built in memory, written by the script: the HDF5
# library's own failed write crashed h5py).
/usr/bin/python3 - "$bin/tfmb-convert" <<'PY' || fail "failed writes"
import os, resource, signal, subprocess, sys
def limit():
    signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
    resource.setrlimit(resource.RLIMIT_FSIZE, (0, 0))
before = set(os.listdir("."))
for args, out in ((["export", "flowmesh.h5", "-o", "full.su2"], "full.su2"),
                  (["export", "flowmesh.h5", "-o", "full.msh"], "full.msh"),
                  (["export", "flowmesh.h5", "-o", "full.vtu"], "full.vtu"),
                  (["import", "mixed.msh", "-o", "full.h5"], "full.h5"),
                  (["import-flow", "uniform.vtu", "--model", "model.h5", "-o", "full-flow.h5"], "full-flow.h5")):
    done = subprocess.run([sys.argv[1]] + args, preexec_fn=limit, capture_output=True, text=True)
    last = done.stderr.strip().splitlines()[-1]
    assert done.returncode == 4 and last == f"tfmb-convert: error: {out}: File too large", (args, done.returncode, done.stderr)
    assert set(os.listdir(".")) == before, (args, set(os.listdir(".")) - before)
PY

# Bad inputs: exit 3 and a message naming the problem.
set +e
"$bin/tfmb-convert" import no-such.msh -o x.h5 2> err.txt; [ $? -eq 3 ] || fail "missing file not exit 3"
grep -q "no such file" err.txt || fail "missing file message"
echo "not a mesh" > junk.msh
"$bin/tfmb-convert" import junk.msh -o x.h5 > out.txt 2> err.txt; [ $? -eq 3 ] || fail "junk file not exit 3"
# meshio's own message (printed, then exit) becomes the one line; stdout stays clean
[ "$(wc -l < err.txt)" -eq 1 ] && [ ! -s out.txt ] && grep -q "junk.msh: cannot read mesh: Couldn't read" err.txt \
  || fail "junk file message: $(cat out.txt err.txt)"
sed 's/^Physical Curve.*//' "$data/mixed_channel.geo" > untagged.geo
gmsh -2 -format msh22 untagged.geo -o untagged.msh > /dev/null 2>&1
"$bin/tfmb-convert" import untagged.msh -o x.h5 2> err.txt; [ $? -eq 3 ] || fail "untagged not exit 3"
sed 's/"inflow"/"entry"/' "$data/mixed_channel.geo" > unknown.geo
gmsh -2 -format msh22 unknown.geo -o unknown.msh > /dev/null 2>&1
"$bin/tfmb-convert" import unknown.msh -o x.h5 2> err.txt; [ $? -eq 3 ] || fail "unknown kind not exit 3"
grep -q "entry" err.txt || fail "unknown kind message does not name the boundary"
"$bin/tfmb-convert" import unknown.msh -o mapped.h5 --map entry=inflow || fail "--map"
# Axisymmetric: the lower wall (y = 0) as the axis; without --geometry an axis is refused, and
# --geometry axisymmetric without an axis too.
"$bin/tfmb-convert" import mixed.msh -o axi.h5 --geometry axisymmetric --map lower_wall=axis || fail "axisymmetric import"
/usr/bin/python3 -c "import h5py; f = h5py.File('axi.h5'); assert f.attrs['geometry'] == 'axisymmetric'; assert f['/mesh/boundaries/lower_wall'].attrs['kind'] == 'axis'" || fail "axisymmetric header"
"$bin/tfmb-check" --no-summary axi.h5 || fail "tfmb-check of the axisymmetric import"
"$bin/tfmb-convert" import mixed.msh -o x.h5 --map lower_wall=axis 2> err.txt; [ $? -eq 3 ] || fail "planar axis not exit 3"
grep -q "geometry axisymmetric" err.txt || fail "planar axis message"
"$bin/tfmb-convert" import mixed.msh -o x.h5 --geometry axisymmetric 2> err.txt; [ $? -eq 3 ] || fail "axisymmetric without axis not exit 3"
grep -q "kind axis" err.txt || fail "axisymmetric without axis message"
"$bin/tfmb-convert" export x.h5 -o x.vtu 2> err.txt; [ $? -eq 3 ] || fail "export of missing file not exit 3"
"$bin/tfmb-convert" --bogus 2> /dev/null; [ $? -eq 2 ] || fail "usage error not exit 2"
"$bin/tfmb-convert" export flowmesh.h5 -o x.unknownext 2> err.txt; [ $? -eq 2 ] || fail "unknown extension not exit 2"
"$bin/tfmb-convert" export flowmesh.h5 -o no-such-dir/x.su2 2> err.txt; [ $? -eq 2 ] || fail "missing folder not exit 2"
# A file that breaks its spec: exit 3 naming the file and the object in it, nothing written.
/usr/bin/python3 -c "
import h5py, shutil; shutil.copy('flowmesh.h5', 'bad.h5')
with h5py.File('bad.h5', 'a') as f: f['/mesh/boundaries/inflow/edges'][0, 0] = 10**6"
"$bin/tfmb-convert" export bad.h5 -o x.su2 2> err.txt; [ $? -eq 3 ] || fail "out-of-range edge not exit 3"
grep -q "bad.h5: /mesh/boundaries/inflow/edges: index" err.txt || fail "out-of-range edge message: $(cat err.txt)"
# A failure while writing (an SU2 marker name cannot hold a space) leaves no partial file.
/usr/bin/python3 -c "
import h5py, shutil; shutil.copy('flowmesh.h5', 'spaced.h5')
with h5py.File('spaced.h5', 'a') as f: f.move('/mesh/boundaries/outflow', '/mesh/boundaries/out flow')"
"$bin/tfmb-convert" export spaced.h5 -o x.su2 2> err.txt; [ $? -eq 2 ] || fail "marker with a space not exit 2"
[ ! -e x.su2 ] && [ ! -e x.msh ] && [ ! -e x.unknownext ] || fail "a failed export left a file"
ls -a | grep -q '^\.tfmb-convert-' && fail "a failed export left its staging folder"
[ ! -e x.h5 ] && [ ! -e x.h5.tmp ] || fail "a failed import left a file"
echo "convert tests passed"
