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

# Bad inputs: exit 3 and a message naming the problem.
set +e
"$bin/tfmb-convert" import no-such.msh -o x.h5 2> err.txt; [ $? -eq 3 ] || fail "missing file not exit 3"
grep -q "no such file" err.txt || fail "missing file message"
echo "not a mesh" > junk.msh
"$bin/tfmb-convert" import junk.msh -o x.h5 2> err.txt; [ $? -eq 3 ] || fail "junk file not exit 3"
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
[ ! -e x.h5 ] && [ ! -e x.h5.tmp ] || fail "a failed import left a file"
echo "convert tests passed"
