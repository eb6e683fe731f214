#!/usr/bin/python3
"""The XDMF sidecars as ParaView shows them (issue 22): Debian's ParaView (pvpython under
xvfb-run) opens the sidecars of a one-way run (flowmesh, flow with its wall grids, thermal, loads,
structure, strain) and a temporal collection over two iterates; every named array must exist with
the right number of components and a range equal to the HDF5 data read with h5py (the mixed-unit
structure fields as one scalar per component, e.g. `bending_moment [N m]`); the flow's pressure
rendered to a PNG must show the field (many colours over a good part of the picture, not a blank
view). Each boundary of flowmesh and thermal is its own polyline block named
after it. meshio must read the `.meshio.xdmf` variants of flowmesh, thermal, flow and structure.

  test_paraview_sidecars.py SOURCE_DIR BIN_DIR SCRATCH [--run RUN_DIR]

Without --run, the inputs come from `make -f Makefile.cases CASE=config1 SMOKE=1` up to strain.h5
with the flow stage swapped for tests/workflows/analytic-flow (seconds instead of a flow solve);
its flow.h5 then gets its sidecar from `tfmb-check --sidecar`, the writer every stage calls.
With --run, an existing run folder (e.g. a SMOKE run with tfmb-flow) is checked instead.
Exit 77 (skipped) with a message only when ParaView cannot start. About 20 s on 2 cores.
"""
import json
import os
import shutil
import subprocess
import sys
import time

import h5py
import numpy as np

SKIP = 77

# Components of the structure file's mixed-unit fields as the sidecar names them
# (formats/structure.md; order of model.md's section stiffness).
SPLIT = {
    "sectional_strain": ["axial_strain [1]", "shear_strain [1]", "shear_strain_out_of_plane [1]",
                         "twist [1/m]", "curvature_out_of_plane [1/m]", "curvature [1/m]"],
    "sectional_force": ["axial_force [N]", "shear_force [N]", "shear_force_out_of_plane [N]",
                        "torque [N m]", "bending_moment_out_of_plane [N m]", "bending_moment [N m]"],
}
LINES = {3, 4}  # VTK_LINE, VTK_POLY_LINE (an XDMF Polyline of two nodes)
failures = []


def fail(message):
    failures.append(message)
    print("FAIL:", message, file=sys.stderr)


def ranges(data):
    data = np.asarray(data, dtype=float)
    if data.ndim == 1:
        data = data[:, None]
    return [[float(data[:, c].min()), float(data[:, c].max())] for c in range(data.shape[1])]


def expect_array(where, seen, name, data):
    """`seen`: the arrays of ParaView's leaves (merged); `data`: the HDF5 values it must show."""
    if name not in seen:
        fail(f"{where}: no array '{name}' (ParaView has {sorted(seen)})")
        return
    data = np.asarray(data)
    components = 1 if data.ndim == 1 else data.shape[1]
    if seen[name]["components"] != components:
        fail(f"{where}: '{name}' has {seen[name]['components']} components, expected {components}")
        return
    # The same doubles read from the same file: equal, not close.
    if seen[name]["ranges"] != ranges(data):
        fail(f"{where}: '{name}' range {seen[name]['ranges']}, the HDF5 data {ranges(data)}")


def merged(leaves):
    """Arrays over several leaves (the flaps of a loads file): ranges of the union."""
    out = {}
    for leaf in leaves:
        for name, a in leaf["arrays"].items():
            if name not in out:
                out[name] = dict(a, ranges=[list(r) for r in a["ranges"]])
            else:
                out[name]["ranges"] = [[min(r0[0], r1[0]), max(r0[1], r1[1])]
                                       for r0, r1 in zip(out[name]["ranges"], a["ranges"])]
    return out


def stacked(h5, root, name):
    return np.concatenate([h5[f"{root}/{g}/{name}"][()] for g in h5[root] if name in h5[f"{root}/{g}"]])


def check_mesh_fields(where, leaf, h5):
    for group in ("/fields/point", "/fields/cell"):
        for name in h5.get(group, {}):
            expect_array(where, leaf["arrays"], name, h5[f"{group}/{name}"][()])



def run_under_xvfb(xvfb, command, timeout):
    """Runs command under xvfb-run on a free display. -noreset: by default Xvfb resets itself
    when its last client disconnects, and a client that connects during the reset is dropped
    before it is served, so its XOpenDisplay fails (ParaView: "bad X server connection"). pvpython
    opens the display more than once, and on a loaded machine the reset lasts long enough to
    hit: three attempts in a row failed so in a CI rehearsal (session 54). The same failure and
    fix in pyvista's CI: pyvista/pyvista pull request 9188. A connection refused all the same is
    tried up to three times, a few seconds apart."""
    for attempt in range(3):
        result = subprocess.run([xvfb, "-a", "-s", "-screen 0 1024x768x24 -noreset"] + command,
                                capture_output=True, text=True, timeout=timeout)
        x_failure = "bad X server connection" in result.stderr or "cannot open display" in result.stderr
        if result.returncode == 0 or not x_failure:
            return result
        print(f"note: the X server refused pvpython (attempt {attempt + 1} of 3); again", file=sys.stderr)
        time.sleep(3)
    return result

def main():
    source, bin_dir, scratch = (os.path.abspath(a) for a in sys.argv[1:4])
    run = os.path.abspath(sys.argv[5]) if len(sys.argv) > 5 and sys.argv[4] == "--run" else None
    pvpython, xvfb = shutil.which("pvpython"), shutil.which("xvfb-run")
    if not pvpython or not xvfb:
        print(f"SKIP: ParaView cannot start here: pvpython {pvpython or 'missing'}, xvfb-run "
              f"{xvfb or 'missing'} (apt-get install paraview python3-paraview xvfb xauth)")
        return SKIP
    shutil.rmtree(scratch, ignore_errors=True)
    os.makedirs(scratch)
    if run is None:
        run = os.path.join(scratch, "run")
        make = subprocess.run(
            ["make", "-f", "Makefile.cases", "--no-print-directory", "CASE=config1", "SMOKE=1",
             f"RUN={run}", f"BIN={bin_dir}", f"FLOW={source}/tests/workflows/analytic-flow",
             f"{run}/strain.h5", f"{run}/flowmesh.h5"],
            cwd=source, capture_output=True, text=True)
        if make.returncode != 0:
            print(make.stdout[-3000:], make.stderr[-3000:], file=sys.stderr)
            fail("make config1 SMOKE=1 up to strain.h5")
            return 1
        subprocess.run([f"{bin_dir}/tfmb-check", "--no-summary", "--sidecar", f"{run}/flow.h5"],
                       check=True)
    # Two iterates of a two-way run, as twoway's rule writes their temporal collection.
    series = os.path.join(scratch, "series")
    for k in (1, 2):
        os.makedirs(f"{series}/iter-00{k}")
        shutil.copy(f"{run}/flow.h5", f"{series}/iter-00{k}/flow.h5")
    subprocess.run([f"{bin_dir}/tfmb-check", "--no-summary", "--series", "-o",
                    f"{series}/flow-iterations.xdmf", f"{series}/iter-001/flow.h5",
                    f"{series}/iter-002/flow.h5"], check=True)

    kinds = ["flowmesh", "flow", "thermal", "loads", "structure", "strain"]
    sidecars = [f"{run}/{k}.xdmf" for k in kinds] + [f"{series}/flow-iterations.xdmf"]
    for sidecar in sidecars:
        if not os.path.exists(sidecar):
            fail(f"no sidecar {sidecar}")
    report_file, picture = f"{scratch}/paraview.json", f"{scratch}/flow-pressure.png"
    probe = run_under_xvfb(
        xvfb, [pvpython, os.path.join(source, "tests/formats/paraview_probe.py"), report_file,
               picture, f"{run}/flow.xdmf", "pressure"] + [s for s in sidecars if os.path.exists(s)],
        timeout=120)
    if probe.returncode != 0 or not os.path.exists(report_file):
        # Tell "ParaView cannot start here" (no display, no OpenGL) from a sidecar it cannot
        # read: the same command on a built-in source, rendered.
        trial = run_under_xvfb(
            xvfb, [pvpython, "-c",
                   "from paraview.simple import *; Show(Sphere()); "
                   f"SaveScreenshot('{scratch}/trial.png', GetActiveViewOrCreate('RenderView'))"],
            timeout=60)
        if trial.returncode != 0:
            print("SKIP: ParaView cannot start here (xvfb-run -a pvpython, rendering a sphere):",
                  (trial.stderr.strip().splitlines() or ["no message"])[0])
            return SKIP
        print(probe.stdout[-3000:], probe.stderr[:3000], file=sys.stderr)
        fail("pvpython could not open the sidecars")
        return 1
    report = json.load(open(report_file))

    def leaves_of(kind):
        return report.get(f"{run}/{kind}.xdmf", {}).get("leaves", [])

    # Mesh-bearing kinds: one grid of triangles and quads with the file's fields.
    for kind in ("flowmesh", "flow", "thermal"):
        with h5py.File(f"{run}/{kind}.h5") as h5:
            meshes = [l for l in leaves_of(kind) if not LINES & set(l["cell_types"])]
            if len(meshes) != 1:
                fail(f"{kind}.xdmf: {len(meshes)} mesh grids, expected 1")
                continue
            if meshes[0]["points"] != h5["/mesh/points"].shape[0]:
                fail(f"{kind}.xdmf: {meshes[0]['points']} points")
            check_mesh_fields(f"{kind}.xdmf", meshes[0], h5)
    # flowmesh and thermal: one polyline per mesh boundary, named after it (a flap's wall and
    # side, a far-field piece), through the boundary's own points; the names as ParaView's
    # Xdmf3ReaderT lists the blocks (the S reader makes unnamed pieces of them).
    for kind in ("flowmesh", "thermal"):
        with h5py.File(f"{run}/{kind}.h5") as h5:
            named = report.get(f"{run}/{kind}.xdmf", {}).get("named_leaves", [])
            lines = [l for l in named if set(l["cell_types"]) <= LINES]
            names = sorted(l["name"] or "" for l in lines)
            if names != sorted(h5["/mesh/boundaries"]):
                fail(f"{kind}.xdmf: boundary grids {names}, the file has "
                     f"{sorted(h5['/mesh/boundaries'])}")
            for leaf in lines:
                edges = h5.get(f"/mesh/boundaries/{leaf['name']}/edges")
                if edges is None:
                    continue
                used = np.unique(edges[()])
                if leaf["cells"] != edges.shape[0] or leaf["points"] != used.size:
                    fail(f"{kind}.xdmf {leaf['name']}: {leaf['cells']} cells, {leaf['points']} "
                         f"points; the boundary has {edges.shape[0]} edges on {used.size} points")
                    continue
                expect_array(f"{kind}.xdmf {leaf['name']}", leaf["arrays"], "node", used)
    # flow: one polyline grid per wall trace, with the trace's datasets.
    with h5py.File(f"{run}/flow.h5") as h5:
        walls = [l for l in leaves_of("flow") if set(l["cell_types"]) <= LINES]
        if len(walls) != len(h5["/walls"]):
            fail(f"flow.xdmf: {len(walls)} wall grids, the file has {len(h5['/walls'])} walls")
        seen = merged(walls)
        for name in ("pressure", "temperature", "wall_shear", "heat_flux", "s", "normal", "node"):
            if all(name in h5[f"/walls/{w}"] for w in h5["/walls"]):
                expect_array("flow.xdmf walls", seen, name, stacked(h5, "/walls", name))
        bounds = [min(l["bounds"][0] for l in walls), max(l["bounds"][1] for l in walls)] \
            if walls else None
        x = stacked(h5, "/walls", "x")
        if bounds != [float(x.min()), float(x.max())]:
            fail(f"flow.xdmf walls: x bounds {bounds}, traces {[x.min(), x.max()]}")
    # structure: the beam with each component of the mixed-unit fields its own scalar.
    with h5py.File(f"{run}/structure.h5") as h5:
        beam = leaves_of("structure")
        if len(beam) != 1:
            fail(f"structure.xdmf: {len(beam)} grids")
        else:
            seen = beam[0]["arrays"]
            for name in ("displacement", "rotation"):
                expect_array("structure.xdmf", seen, name, h5[f"/fields/point/{name}"][()])
            for dataset, names in SPLIT.items():
                values = h5[f"/fields/cell/{dataset}"][()]
                for k, name in enumerate(names):
                    expect_array("structure.xdmf", seen, name, values[:, k])
                if dataset in seen:
                    fail(f"structure.xdmf: the mixed-unit '{dataset}' is shown whole")
    # loads and strain: one polyline per flap through its positions.
    for kind, names in (("loads", ["s", "distributed_force", "nodal_force", "nodal_moment"]),
                        ("strain", ["s", "total_inner", "total_outer", "margin_total",
                                    "mechanical_inner", "allowable", "element"])):
        with h5py.File(f"{run}/{kind}.h5") as h5:
            flaps = leaves_of(kind)
            if len(flaps) != len(h5["/flaps"]):
                fail(f"{kind}.xdmf: {len(flaps)} grids, the file has {len(h5['/flaps'])} flaps")
            seen = merged(flaps)
            for name in names:
                expect_array(f"{kind}.xdmf", seen, name, stacked(h5, "/flaps", name))
    # The temporal collection: two time steps, each the flow with its walls.
    entry = report.get(f"{series}/flow-iterations.xdmf", {})
    if entry.get("times") != [1.0, 2.0]:
        fail(f"flow-iterations.xdmf: time steps {entry.get('times')}, expected [1, 2]")
    # pvpython's fetch hands back the current step or every step, each the flow with its walls.
    steps = len(entry.get("leaves", [])) / max(len(leaves_of("flow")), 1)
    if steps not in (1, 2):
        fail("flow-iterations.xdmf: a time step is not the flow with its walls")

    # The picture: the pressure field drawn, not a blank (white) view.
    import matplotlib.image
    image = matplotlib.image.imread(picture)[:, :, :3]
    drawn = np.any(np.abs(image - 1.0) > 0.02, axis=2)
    colours = len(np.unique((image[drawn] * 255).round().astype(int), axis=0))
    print(f"picture {picture}: {drawn.mean():.1%} of the pixels drawn, {colours} colours, "
          f"pixel standard deviation {image.std():.3f}")
    if drawn.mean() < 0.05 or colours < 50 or image.std() < 0.05:
        fail(f"{picture}: the pressure field is not drawn ({drawn.mean():.1%} of the pixels, "
             f"{colours} colours)")

    # meshio reads the .meshio.xdmf variants: the mesh or beam grid alone, fields as stored.
    import meshio
    for name in ("flowmesh.meshio.xdmf", "thermal.meshio.xdmf", "flow.meshio.xdmf",
                 "structure.meshio.xdmf"):
        try:
            mesh = meshio.read(f"{run}/{name}")
        except Exception as error:  # noqa: BLE001 - any failure of meshio is the finding
            fail(f"meshio cannot read {name}: {error!r}")
            continue
        kind = name.split(".")[0]
        with h5py.File(f"{run}/{kind}.h5") as h5:
            if len(mesh.points) != h5["/mesh/points" if "/mesh" in h5 else "/beam/points"].shape[0]:
                fail(f"meshio {name}: {len(mesh.points)} points")
            expected = set(h5.get("/fields/point", {}))
            if set(mesh.point_data) != expected:
                fail(f"meshio {name}: point data {sorted(mesh.point_data)}, expected {sorted(expected)}")
    if failures:
        print(f"{len(failures)} failures", file=sys.stderr)
        return 1
    print("ParaView and meshio read the sidecars")
    return 0


sys.exit(main())
