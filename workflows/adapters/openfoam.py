"""openfoam: OpenFOAM 1912 (Debian package openfoam) on a tfmb flow mesh, shared by
workflows/bench-openfoam (the speed benchmark, issue 5) and workflows/adapters/openfoam-flow (the
flow stage by OpenFOAM, issue 21).

    mesh = read_flowmesh("flowmesh.h5"); cond = read_conditions("model.h5")
    inner, upper = wall_groups(mesh, cond["flap_half"])
    setup_case(case, mesh, cond, inner, upper, TEMPLATES, options)    # gmshToFoam, patches, checkMesh
    state = run_solver(case, faces, options, label)                   # rhoPimpleFoam + wall-p monitor
    vtu = foam_to_vtk(case)                                           # the last time as VTU

The set-up is the anchor's (refdata/openfoam: rhoPimpleFoam, transonic PIMPLE with local time
stepping, inviscid) from the templates in cases/nasa-2dcd/openfoam (README there); the monitor's
criterion is the anchor's too: the inner-wall pressure changes by less than a relative tolerance
over a window of iterations. Errors are Failure(message, exit code): 3 bad input (a missing or
wrong file, OpenFOAM not installed), 4 a tool failed (its log is named).
"""
import glob
import json
import os
import re
import shutil
import signal
import subprocess
import sys
import time
import warnings

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
TEMPLATES = os.path.join(ROOT, "cases", "nasa-2dcd", "openfoam")
OPENFOAM_DIR = "/usr/share/openfoam"       # Debian package: binaries in /usr/bin
# OpenFOAM's universal gas constant [J/(kmol K)] (1e3 N_A k_B in its constants), to turn the
# model's specific gas constant into the molWeight OpenFOAM wants.
OPENFOAM_RR = 8314.47


class Failure(Exception):
    """One-line error with the exit code to leave with."""

    def __init__(self, message, code):
        super().__init__(message)
        self.code = code


def bad_input(message):
    return Failure(message, 3)


def tool_failed(message):
    return Failure(message, 4)


def text(value):
    return value.decode() if isinstance(value, bytes) else str(value)


# ------------------------------------------------------------------------------------------
# Reading the tfmb files

def open_h5(path, kind):
    import h5py
    if not os.path.isfile(path):
        raise bad_input(f"{path}: no such file")
    try:
        f = h5py.File(path, "r")
    except OSError:
        raise bad_input(f"{path}: not an HDF5 file")
    fmt = text(f.attrs.get("format", ""))
    if fmt != f"tfmb/{kind}":
        f.close()
        raise bad_input(f"{path}: format is '{fmt}', expected tfmb/{kind}")
    return f


def read_flowmesh(path):
    """points (N,2), triangles, quads, boundaries {name: {kind, flap, side, edges}}, depth."""
    with open_h5(path, "flowmesh") as f:
        if text(f.attrs.get("geometry", "planar")) != "planar":
            raise bad_input(f"{path}: geometry is {text(f.attrs['geometry'])}; the benchmark is planar only")
        mesh = {"points": f["mesh/points"][:], "depth": float(f.attrs["depth"]),
                "triangle": f["mesh/cells/triangle"][:] if "mesh/cells/triangle" in f else np.zeros((0, 3), int),
                "quad": f["mesh/cells/quad"][:] if "mesh/cells/quad" in f else np.zeros((0, 4), int),
                "boundaries": {}}
        for name, group in f["mesh/boundaries"].items():
            mesh["boundaries"][name] = {
                "kind": text(group.attrs["kind"]), "flap": text(group.attrs.get("flap", "")),
                "side": text(group.attrs.get("side", "")), "edges": group["edges"][:]}
    if not mesh["boundaries"]:
        raise bad_input(f"{path}: /mesh/boundaries: no boundary")
    if mesh["depth"] <= 0:
        raise bad_input(f"{path}: @depth {mesh['depth']} is not positive")
    return mesh


def read_conditions(path):
    """The flow conditions of model.h5 as tfmb-flow gets them (workflows/flow-args)."""
    with open_h5(path, "model") as f:
        if "conditions" not in f:
            raise bad_input(f"{path}: /conditions: missing group")
        c = f["conditions"].attrs
        try:
            p_amb = float(c["ambient_pressure"])
            cond = {"p_amb": p_amb, "p0": float(c["nozzle_pressure_ratio"]) * p_amb,
                    "npr": float(c["nozzle_pressure_ratio"]),
                    "T0": float(c["stagnation_temperature"]), "T_amb": float(c["ambient_temperature"]),
                    "gamma": float(c["gamma"]), "R": float(c["gas_constant"])}
        except KeyError as missing:
            raise bad_input(f"{path}: /conditions: missing attribute {missing}")
        if float(c.get("ambient_mach", 0.0)) > 0:
            raise bad_input(f"{path}: /conditions@ambient_mach > 0; the OpenFOAM set-up is for air at rest outside")
        if float(c.get("exit_pressure_ratio", 0.0)) > 0:
            raise bad_input(f"{path}: /conditions@exit_pressure_ratio set; the OpenFOAM set-up has ambient pressure outside")
        halves = {}
        for name, flap in f.get("flaps", {}).items():
            halves[name] = text(flap.attrs.get("half", ""))
        cond["flap_half"] = halves
    return cond


def wall_groups(mesh, halves):
    """Boundary names of the inner walls (the monitor's) and of the upper flaps' inner walls."""
    inner = [n for n, b in mesh["boundaries"].items()
             if b["kind"] in ("wall", "slip_wall") and b["side"] == "inner"]
    upper = [n for n in inner if halves.get(mesh["boundaries"][n]["flap"]) == "upper"]
    if not inner:
        raise bad_input("flowmesh: no wall boundary with side = inner (the nozzle's inner walls)")
    if not upper:
        raise bad_input("flowmesh: no inner wall of an upper flap (model.h5 /flaps/*@half = upper)")
    return inner, upper


# ------------------------------------------------------------------------------------------
# Mesh conversion: flowmesh.h5 -> gmsh 2.2, one cell deep

def write_gmsh(mesh, out):
    """Extrude the 2D mesh by its depth: triangles -> prisms, quads -> hexahedra; every boundary
    edge -> a quad in the physical surface named after its boundary; the two planes -> the
    physical surface frontAndBack (OpenFOAM's empty patches). Returns the physical names."""
    pts = mesh["points"]
    n = len(pts)
    tri, quad = mesh["triangle"], mesh["quad"]
    names = sorted(mesh["boundaries"])
    tags = {name: i + 1 for i, name in enumerate(names)}
    tag_planes, tag_fluid = len(names) + 1, len(names) + 2
    lines = ["$MeshFormat", "2.2 0 8", "$EndMeshFormat", "$PhysicalNames", str(len(names) + 2)]
    lines += [f'2 {tags[name]} "{name}"' for name in names]
    lines += [f'2 {tag_planes} "frontAndBack"', f'3 {tag_fluid} "fluid"', "$EndPhysicalNames"]
    lines += ["$Nodes", str(2 * n)]
    ids = np.arange(1, 2 * n + 1)
    xyz = np.vstack([np.column_stack([pts, np.zeros(n)]), np.column_stack([pts, np.full(n, mesh["depth"])])])
    lines += [f"{i} {x:.17g} {y:.17g} {z:.17g}" for i, (x, y, z) in zip(ids, xyz)]
    lines += ["$EndNodes"]
    elements = []

    def add(gmsh_type, tag, nodes):
        # 1-based gmsh node ids; elementary entity = physical group
        for row in nodes:
            elements.append(f"{gmsh_type} 2 {tag} {tag} " + " ".join(str(v + 1) for v in row))

    # cells: counter-clockwise bottom face at z = 0, then the top face (gmsh node order)
    add(6, tag_fluid, np.hstack([tri, tri + n]))
    add(5, tag_fluid, np.hstack([quad, quad + n]))
    for name in names:
        e = mesh["boundaries"][name]["edges"]
        add(3, tags[name], np.column_stack([e[:, 0], e[:, 1], e[:, 1] + n, e[:, 0] + n]))
    add(2, tag_planes, tri)
    add(2, tag_planes, tri + n)
    add(3, tag_planes, quad)
    add(3, tag_planes, quad + n)
    lines += ["$Elements", str(len(elements))]
    lines += [f"{i + 1} {e}" for i, e in enumerate(elements)]
    lines += ["$EndElements", ""]
    with open(out, "w") as f:
        f.write("\n".join(lines))
    return names


# ------------------------------------------------------------------------------------------
# OpenFOAM

def openfoam_env():
    env = dict(os.environ)
    env["WM_PROJECT_DIR"] = OPENFOAM_DIR
    env["FOAM_SIGFPE"] = "1"        # stop on a floating-point exception rather than go on with NaN
    return env


REQUIRED_TOOLS = ("rhoPimpleFoam", "gmshToFoam", "foamDictionary", "checkMesh", "foamToVTK")


def missing_tool():
    """The first OpenFOAM executable this module runs that is not on PATH, or None."""
    for tool in REQUIRED_TOOLS:
        if shutil.which(tool) is None:
            return tool
    return None


def require_openfoam():
    tool = missing_tool()
    if tool:
        raise bad_input(f"OpenFOAM not installed ({tool} not found): workflows/bench-openfoam install "
                        "(or workflows/install-deps)")


def run_tool(cmd, log, cwd=None):
    with open(log, "w") as out:
        rc = subprocess.run(cmd, cwd=cwd, stdout=out, stderr=subprocess.STDOUT, env=openfoam_env()).returncode
    if rc != 0:
        raise tool_failed(f"{' '.join(cmd)} failed (exit {rc}): see {log}")


def fill_templates(src, dst, values):
    """Copy the template dictionaries with every @NAME@ replaced; an unknown @NAME@ is an error."""
    for path in sorted(glob.glob(os.path.join(src, "*", "*"))):
        rel = os.path.relpath(path, src)
        with open(path) as f:
            body = f.read()
        for key, value in values.items():
            body = body.replace(f"@{key}@", str(value))
        left = re.findall(r"@[A-Z_0-9]+@", body)
        if left:
            raise bad_input(f"{path}: template field {left[0]} has no value")
        os.makedirs(os.path.dirname(os.path.join(dst, rel)), exist_ok=True)
        with open(os.path.join(dst, rel), "w") as f:
            f.write(body)


def set_patches(case, mesh, inner, upper):
    """Patch types and groups: the field templates name groups (inflow, farfield, wall), the
    samples name monitorWall and upperInnerWall, so they hold for any boundary names."""
    boundary = os.path.join(case, "constant", "polyMesh", "boundary")
    kinds = {"inflow": ("patch", ["inflow"]), "farfield": ("patch", ["farfield"]),
             "outflow": ("patch", ["farfield"]), "wall": ("wall", ["wall"]),
             "slip_wall": ("wall", ["wall"]), "symmetry": ("symmetryPlane", ["symmetryPlane"])}
    entries = {"frontAndBack": ("empty", ["empty"])}
    for name, b in mesh["boundaries"].items():
        if b["kind"] not in kinds:
            raise bad_input(f"flowmesh: /mesh/boundaries/{name}: kind {b['kind']} has no OpenFOAM counterpart here")
        kind, groups = kinds[b["kind"]]
        groups = groups + (["monitorWall"] if name in inner else []) + (["upperInnerWall"] if name in upper else [])
        entries[name] = (kind, groups)
    for name, (kind, groups) in entries.items():
        run_tool(["foamDictionary", boundary, "-entry", f"entry0/{name}/type", "-set", kind],
                 os.path.join(case, "log.foamDictionary"))
        run_tool(["foamDictionary", boundary, "-entry", f"entry0/{name}/inGroups", "-set",
                  f"List<word> {len(groups)}({' '.join(groups)})"], os.path.join(case, "log.foamDictionary"))
    # gmshToFoam's physicalType entries are not OpenFOAM patch keywords in 1912
    with open(boundary) as f:
        body = f.read()
    with open(boundary, "w") as f:
        f.write(re.sub(r"^\s*physicalType\s+\w+;\n", "", body, flags=re.M))
    return entries


def read_raw(path):
    """x and value of each face of a raw surface sample (columns x y z value), in file order.
    ValueError where the file has no complete row: the solver creates a sample file before it
    writes the rows, so the monitor can find it empty."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UserWarning)    # loadtxt's "input contained no data"
        data = np.loadtxt(path, comments="#", ndmin=2)
    if data.shape[0] == 0 or data.shape[1] < 4:
        raise ValueError(f"{path}: no complete 'x y z value' row")
    return data[:, 0], data[:, 3]


def sample_files(case, function, surface):
    """{iteration: path} of a surface-sampling function's output (pseudo-time = iteration)."""
    found = {}
    for path in glob.glob(os.path.join(case, "postProcessing", function, "*", f"p_{surface}.raw")):
        try:
            found[int(round(float(os.path.basename(os.path.dirname(path)))))] = path
        except ValueError:
            pass
    return found


class Monitor:
    """The anchor's criterion on the sampled inner-wall pressure, evaluated as samples appear."""

    def __init__(self, case, faces, opts):
        self.case, self.faces, self.opts = case, faces, opts
        self.cache, self.done, self.history = {}, set(), []
        self.consecutive, self.converged_at = 0, None

    def read(self, it, path):
        if it not in self.cache:
            x, p = read_raw(path)
            if len(x) != self.faces:
                return None         # still being written
            self.cache[it] = (x, p)
        return self.cache[it]

    def scan(self):
        samples = sample_files(self.case, "wallSamples", "monitor")
        for it in sorted(samples):
            back = it - self.opts.window
            if it in self.done or back not in samples:
                continue
            try:
                cur, old = self.read(it, samples[it]), self.read(back, samples[back])
            except (OSError, ValueError):
                continue
            if cur is None or old is None:
                continue
            x, p = cur
            change = np.abs(p - old[1]) / np.abs(p)
            # the faces next to the exit lip see the plume's shear layer (the anchor's exclusion)
            keep = x < x.max() - self.opts.lip
            worst = int(np.argmax(np.where(keep, change, -1.0)))
            self.done.add(it)
            self.history.append((it, float(change[worst]), float(x[worst]), float(change.max())))
            if it >= self.opts.ramp + self.opts.settle and change[worst] < self.opts.tolerance:
                self.consecutive += 1
            else:
                self.consecutive = 0
            if self.consecutive >= self.opts.consecutive and self.converged_at is None:
                self.converged_at = it
        # keep only what the next windows need
        newest = max(samples) if samples else 0
        for it in [k for k in self.cache if k < newest - 2 * self.opts.window]:
            del self.cache[it]


def stop_solver(case):
    subprocess.run(["foamDictionary", os.path.join(case, "system", "controlDict"), "-entry", "stopAt",
                    "-set", "writeNow"], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                   env=openfoam_env())


def parse_time_v(path):
    out = {}
    if not os.path.exists(path):
        return out
    for line in open(path):
        line = line.strip()
        if line.startswith("Elapsed (wall clock) time"):
            seconds = 0.0
            for part in line.rsplit(" ", 1)[1].split(":"):
                seconds = seconds * 60 + float(part)
            out["wall_s"] = seconds
        elif line.startswith("Maximum resident set size"):
            out["peak_MiB"] = int(line.rsplit(" ", 1)[1]) / 1024.0
        elif line.startswith("User time"):
            out["user_s"] = float(line.rsplit(" ", 1)[1])
        elif line.startswith("Exit status"):
            out["exit_status"] = int(line.rsplit(" ", 1)[1])
    return out


def parse_foam_log(path):
    """Clock time at each iteration and the first initial residual of each field per iteration."""
    clock, residuals, it, seen = {}, {}, 0, set()
    time_line = re.compile(r"^Time = ")
    clock_line = re.compile(r"^ExecutionTime = \S+ s\s+ClockTime = (\S+) s")
    res_line = re.compile(r"Solving for (\w+), Initial residual = ([0-9.eE+-]+)")
    with open(path, errors="replace") as f:
        for line in f:
            if time_line.match(line):
                it, seen = it + 1, set()
                continue
            m = clock_line.match(line)
            if m and it:
                clock[it] = float(m.group(1))
                continue
            m = res_line.search(line)
            if m and it and m.group(1) not in seen:
                seen.add(m.group(1))
                residuals.setdefault(m.group(1), []).append(float(m.group(2)))
    return clock, residuals


def template_values(cond, opts):
    """The template fields (@NAME@) from the conditions and the solver options (ramp, max_co,
    sample, openfoam_max_iterations)."""
    return {
        "P0": f"{cond['p0']:.10g}", "P_AMB": f"{cond['p_amb']:.10g}", "T0": f"{cond['T0']:.10g}",
        "T_AMB": f"{cond['T_amb']:.10g}", "GAMMA": f"{cond['gamma']:.10g}",
        "MOL_WEIGHT": f"{OPENFOAM_RR / cond['R']:.10g}",
        "CP": f"{cond['gamma'] * cond['R'] / (cond['gamma'] - 1):.10g}",
        "P_MIN": f"{0.01 * cond['p_amb']:.10g}", "P_MAX": f"{2 * cond['p0']:.10g}",
        # the anchor's temperature bounds (30 K, 600 K at T0 294 K), scaled with T0
        "T_MIN": f"{30.0 * cond['T0'] / 294.0:.10g}", "T_MAX": f"{600.0 * cond['T0'] / 294.0:.10g}",
        "RAMP": opts.ramp, "MAX_CO": opts.max_co, "SAMPLE": opts.sample,
        "END_ITERATIONS": opts.openfoam_max_iterations}


def setup_case(case, mesh, cond, inner, upper, templates, opts, label):
    """A fresh OpenFOAM case in `case`: the templates filled in, the mesh through gmsh 2.2 and
    gmshToFoam, patch types and groups, checkMesh (its main lines on stderr)."""
    require_openfoam()
    shutil.rmtree(case, ignore_errors=True)
    os.makedirs(case)
    fill_templates(templates, case, template_values(cond, opts))
    os.rename(os.path.join(case, "0.orig"), os.path.join(case, "0"))
    print(f"{label}: OpenFOAM case {case}", file=sys.stderr)
    msh = os.path.join(case, "flowmesh.msh")
    write_gmsh(mesh, msh)
    run_tool(["gmshToFoam", msh, "-case", case], os.path.join(case, "log.gmshToFoam"))
    os.remove(msh)
    set_patches(case, mesh, inner, upper)
    with open(os.path.join(case, "log.checkMesh"), "w") as out:
        subprocess.run(["checkMesh", "-case", case], stdout=out, stderr=subprocess.STDOUT, env=openfoam_env())
    with open(os.path.join(case, "log.checkMesh")) as f:
        check = f.read()
    if "Mesh OK" not in check and "Failed" not in check:
        raise tool_failed(f"checkMesh did not finish: see {case}/log.checkMesh")
    for line in check.splitlines():
        if re.search(r"^\s+cells:|Max aspect|non-orthogonality Max|Max skewness|Mesh OK|Failed", line):
            print(f"  checkMesh: {line.strip()}", file=sys.stderr)


def run_solver(case, faces, opts, label):
    """rhoPimpleFoam on `case` under /usr/bin/time -v (case/time.txt), stopped by `stopAt
    writeNow` when the monitor's criterion holds or after opts.timeout seconds (killed
    opts.grace seconds later). Writes case/monitor.csv and case/monitor.json; returns the state
    (criterion, converged_iteration, stop_reason, stop_requested_s, last_change)."""
    monitor = Monitor(case, faces, opts)
    hard_limit = opts.timeout + opts.grace
    # timeout --foreground keeps the solver in the process group of /usr/bin/time, so that an
    # interrupt of this script can stop the whole group (time does not pass signals on)
    cmd = ["/usr/bin/time", "-v", "-o", os.path.join(case, "time.txt"),
           "timeout", "--foreground", "-k", "10", str(hard_limit), "rhoPimpleFoam", "-case", case]
    print(f"{label}: rhoPimpleFoam -case {case} (one core; stops when the wall pressure is "
          f"steady or after {opts.timeout:g} s)", file=sys.stderr)
    start = time.monotonic()
    log = open(os.path.join(case, "log.rhoPimpleFoam"), "w")
    proc = subprocess.Popen(cmd, stdout=log, stderr=subprocess.STDOUT, env=openfoam_env(),
                            start_new_session=True)
    stop_reason, stopped_at = None, None

    def forward(signum, frame):
        # exit 4, not 1: an interrupted run wrote nothing (1 means "written, not converged",
        # which Makefile.cases may accept)
        os.killpg(proc.pid, signal.SIGTERM)
        raise Failure(f"interrupted (signal {signum}); rhoPimpleFoam stopped", 4)
    signal.signal(signal.SIGTERM, forward)
    signal.signal(signal.SIGINT, forward)
    while proc.poll() is None:
        monitor.scan()
        elapsed = time.monotonic() - start
        if stop_reason is None and monitor.converged_at is not None:
            stop_reason, stopped_at = "wall pressure steady", elapsed
            stop_solver(case)
        elif stop_reason is None and elapsed > opts.timeout:
            stop_reason, stopped_at = "time limit", elapsed
            stop_solver(case)
        time.sleep(opts.poll)
    log.close()
    rc = proc.returncode
    monitor.scan()
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    signal.signal(signal.SIGINT, signal.SIG_DFL)
    with open(os.path.join(case, "monitor.csv"), "w") as f:
        f.write(f"# wall p change over {opts.window} iterations, relative; criterion: inner walls "
                f"except {opts.lip} m at the exit < {opts.tolerance} at {opts.consecutive} samples in a row\n")
        f.write("iteration,max_change_criterion_faces,x_of_max_m,max_change_all_faces\n")
        for row in monitor.history:
            f.write("%d,%.6e,%.6f,%.6e\n" % row)
    if rc != 0:
        raise tool_failed(f"rhoPimpleFoam failed (exit {rc}{', hard time limit' if rc in (124, 137) else ''}): "
                          f"see {case}/log.rhoPimpleFoam")
    state = {"criterion": f"inner-wall pressure (faces within {opts.lip:g} m of the exit left out) changing by "
                          f"less than {opts.tolerance:g} (relative) over {opts.window} iterations at "
                          f"{opts.consecutive} samples in a row, from iteration {opts.ramp + opts.settle}",
             "converged_iteration": monitor.converged_at, "stop_reason": stop_reason or "endTime",
             "stop_requested_s": stopped_at,
             "last_change": monitor.history[-1] if monitor.history else None}
    with open(os.path.join(case, "monitor.json"), "w") as f:
        json.dump(state, f, indent=1)
    return state


def latest_time(case):
    """The largest time directory of a case (a number other than 0), or None."""
    times = []
    for entry in os.listdir(case):
        try:
            value = float(entry)
        except ValueError:
            continue
        if value > 0 and os.path.isdir(os.path.join(case, entry)):
            times.append((value, entry))
    return max(times)[1] if times else None


def foam_to_vtk(case, fields=("p", "T", "U", "rho")):
    """foamToVTK of the case's last time (the internal mesh, cell and point values); returns
    the path of the .vtu it wrote."""
    last = latest_time(case)
    if last is None:
        raise tool_failed(f"{case}: no time directory written by the solver: see {case}/log.rhoPimpleFoam")
    out = os.path.join(case, "VTK")
    shutil.rmtree(out, ignore_errors=True)
    run_tool(["foamToVTK", "-case", case, "-time", last, "-fields", "(" + " ".join(fields) + ")",
              "-noFaceZones", "-excludePatches", "(\".*\")"], os.path.join(case, "log.foamToVTK"))
    found = sorted(glob.glob(os.path.join(out, "**", "internal.vtu"), recursive=True)) + \
        sorted(glob.glob(os.path.join(out, "*.vtu")))
    if not found:
        raise tool_failed(f"foamToVTK wrote no .vtu: see {case}/log.foamToVTK")
    return found[-1]
