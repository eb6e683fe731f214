#!/usr/bin/python3
"""Run every tool's documented sample command lines, so that they keep working.

Each tool's main.cpp (tools/<tool>/main.cpp) opens with a comment whose
"Sample runs:" section lists example command lines; a line indented deeper than the commands
continues the one above. A note after a command, `# ...` or a parenthesised `(...)` set off by two
or more spaces, is prose, with two exceptions the runner reads:
  (cases/NAME)   the sample's placeholder files come from that case instead of the default one;
  (exit N)       the sample is documented to exit N (otherwise 0 is expected).

The sample commands name placeholder files (model.h5, flowmesh.h5, flow.h5, loads.h5, ...). The
set-up runs the real chain once on a coarse case and leaves those files, under the same names, in
SCRATCH/setup/<case>/; every sample then runs in a fresh folder of its own, SCRATCH/<tool>-<k>/,
holding copies of the placeholder files its command names (copies, not links: a sample writing
flow.h5 must not overwrite the set-up's), with `cases` and `data` linked to the source tree so
that paths such as cases/simple-nozzle/case.toml work as written.

A sample passes when it exits with the documented code and, when that is 0, every file it names
as output (-o, --curves-csv, --summary) exists and every .h5 among them passes tfmb-check.
Prints one line per sample (tool, command, exit code, seconds); exits 1 naming the failed samples.

  run_sample_runs.py SOURCE_DIR BIN_DIR SCRATCH_DIR [--only TOOL ...]
  run_sample_runs.py --self-test     the header parser on a planted header
"""
import os
import pathlib
import re
import shlex
import shutil
import subprocess
import sys
import time

DEFAULT_CASE = "simple-nozzle"
OUTPUT_OPTIONS = ("-o", "--output", "--curves-csv", "--summary")
# [s] per command; the slowest sample, tfmb-beam's 1000 dynamic steps, takes about 7 s on 2 cores.
SAMPLE_TIMEOUT = 300

# Options appended to some samples to keep the whole run short. Only options the tool has, and
# only where the tool takes the last of a repeated option (tfmb-flow sets CLI11's TakeLast), so
# the documented command itself stays verbatim in front of them.
SHORTEN = [
    # Steady flows: first order to a loose wall-pressure stationarity, about 60 iterations on the
    # coarse set-up mesh, so that the run exits 0 (converged); at second order the inviscid
    # samples' wall pressure keeps chattering behind the blunt 10 mm flap ends and they stop
    # unconverged (exit 1) at any iteration limit.
    ("tfmb-flow", lambda tokens: "--time-step" not in tokens,
     ["--order", "1", "--stationary-tolerance", "1e-3", "--max-iterations", "300"]),
    # Time-accurate flows: 10 physical steps, the last 5 averaged, with a tolerance on the
    # average's halves that 5 steps meet, so that the run exits 0 (a statistically converged mean).
    ("tfmb-flow", lambda tokens: "--time-step" in tokens,
     ["--time-steps", "10", "--statistics-start", "6", "--statistics-tolerance", "0.5"]),
]


# --------------------------------------------------------------------------------------------
# Header parsing

def split_note(text):
    """(command text, note or None) of one comment line's text: a `#` outside quotes after
    whitespace starts a note, and so does a trailing `(...)` set off by two or more spaces."""
    quote = None
    for i, ch in enumerate(text):
        if quote:
            if ch == quote:
                quote = None
        elif ch in "'\"":
            quote = ch
        elif ch == "#" and (i == 0 or text[i - 1].isspace()):
            return text[:i].rstrip(), text[i + 1:].strip()
    m = re.match(r"^(.*?\S)\s{2,}\(([^()]*)\)\s*$", text)
    if m:
        return m.group(1), m.group(2).strip()
    return text.rstrip(), None


def parse_samples(header_text):
    """The sample commands of a main.cpp: a list of dicts with line, tokens, notes."""
    lines = header_text.splitlines()
    samples = []
    start = None
    for i, line in enumerate(lines):
        if not line.startswith("//"):
            break  # only the opening comment block documents samples
        if re.match(r"^//\s*Sample runs:\s*$", line):
            start = i + 1
            break
    if start is None:
        return samples
    base = None
    for i in range(start, len(lines)):
        m = re.match(r"^//( *)(\S.*)$", lines[i])
        if not m:
            break  # a blank comment line or the code ends the section
        indent = len(m.group(1))
        if base is None:
            base = indent
        if indent < base:
            break  # prose after the samples, e.g. tfmb-heat's note on $TFMB_MATERIAL_DB
        code, note = split_note(m.group(2))
        if indent == base:
            samples.append({"line": i + 1, "code": code, "notes": []})
        elif not samples:
            break
        else:
            samples[-1]["code"] += " " + code
        if note:
            samples[-1]["notes"].append(note)
    for s in samples:
        s["tokens"] = shlex.split(s.pop("code"))
    return samples


def sample_case(sample):
    for note in sample["notes"]:
        m = re.fullmatch(r"cases/([A-Za-z0-9_.-]+)", note)
        if m:
            return m.group(1)
    return DEFAULT_CASE


def expected_code(sample):
    for note in sample["notes"]:
        m = re.fullmatch(r"exit (\d+)", note)
        if m:
            return int(m.group(1))
    return 0


def output_files(tokens):
    """Files a command names as its outputs."""
    outputs = []
    for i, tok in enumerate(tokens):
        if tok in OUTPUT_OPTIONS and i + 1 < len(tokens):
            outputs.append(tokens[i + 1])
        elif "=" in tok and tok.split("=", 1)[0] in OUTPUT_OPTIONS:
            outputs.append(tok.split("=", 1)[1])
    return outputs


def main_sources(src):
    tools = src / "tools"
    return sorted(tools.glob("*/main.cpp"))


# --------------------------------------------------------------------------------------------
# Set-up: the real chain on small cases

def run(cmd, cwd, env, log, timeout=SAMPLE_TIMEOUT):
    """Exit code and seconds of a command, its output appended to log (-1: timed out)."""
    start = time.monotonic()
    with open(log, "a") as out:
        out.write("$ " + shlex.join(str(c) for c in cmd) + "\n")
        out.flush()
        try:
            rc = subprocess.run([str(c) for c in cmd], cwd=cwd, env=env, stdout=out,
                                stderr=subprocess.STDOUT, timeout=timeout).returncode
        except subprocess.TimeoutExpired:
            out.write(f"timed out after {timeout} s\n")
            rc = -1
        except OSError as e:
            out.write(f"cannot run: {e}\n")
            rc = 127
    return rc, time.monotonic() - start


def tail(path, n=15):
    try:
        return "\n".join("    " + l for l in path.read_text(errors="replace").splitlines()[-n:])
    except OSError:
        return ""


class SetupError(Exception):
    pass


def copy_case_files(src, case, folder):
    """Copies the case's own files (case.toml and its geometry) into folder; their names."""
    case_dir = src / "cases" / case
    if not (case_dir / "case.toml").is_file():
        raise SetupError(f"no case {case_dir}/case.toml")
    names = []
    for f in sorted(case_dir.iterdir()):
        if f.is_file():
            shutil.copy(f, folder / f.name)
            names.append(f.name)
    return names


def setup_case(src, bin_dir, scratch, case, env):
    """SCRATCH/setup/<case>/ with the placeholder files of the samples; returns (folder, names
    of the case's own files)."""
    folder = scratch / "setup" / case
    folder.mkdir(parents=True)
    log = folder / "setup.log"
    case_files = copy_case_files(src, case, folder)
    shutil.copy(src / "data" / "materials-db.h5", folder / "materials-db.h5")

    def stage(name, *args, ok=(0,)):
        rc, secs = run([bin_dir / args[0], *args[1:]], folder, env, log)
        if rc not in ok:
            raise SetupError(f"set-up {case}: {name} exited {rc}; last lines of {log}:\n"
                             + tail(log))

    if case != DEFAULT_CASE:
        # Other cases serve structure samples: their model is all they need.
        stage("input", "tfmb-input", "case.toml", "-o", "model.h5")
        return folder, case_files

    # config1's one-way chain (Makefile.cases, cases/config1/case.mk: NPR 5.423, 750 K, 10 mm
    # flaps, second-order SA) on a mesh 8x coarser than the case's and 4 beam elements per flap:
    # about 3 s, and the 1000 steps of tfmb-beam's dynamic sample take about 7 s.
    flaps = ["upper_1", "upper_2", "upper_3", "lower_1", "lower_2", "lower_3"]
    sets = ["--set", "mesh.scale=8", "--set", "flow.nozzle_pressure_ratio=5.423",
            "--set", "flow.stagnation_temperature=750"]
    for f in flaps:
        sets += ["--set", f"flap.{f}.thickness=0.01", "--set", f"flap.{f}.elements=4"]
    stage("input", "tfmb-input", "case.toml", *sets, "-o", "model.h5")
    stage("mesh flow", "tfmb-mesh", "flow", "model.h5", "-o", "flowmesh.h5")
    stage("mesh solid", "tfmb-mesh", "solid", "model.h5", "-o", "solidmesh.h5")
    flow_args = subprocess.run([sys.executable, src / "workflows" / "flow-args", "model.h5",
                                "--model", "sa"], cwd=folder, capture_output=True, text=True)
    if flow_args.returncode != 0:
        raise SetupError(f"set-up {case}: workflows/flow-args exited {flow_args.returncode}: "
                         f"{flow_args.stderr.strip()}")
    # SA with its heat-transfer probe: tfmb-heat's convection boundary needs the flow's heat
    # transfer coefficient and adiabatic wall temperature. Exit 1 (a flagged unconverged flow)
    # is still a valid input for the samples, as in Makefile.cases' SMOKE runs.
    stage("flow", "tfmb-flow", "flowmesh.h5", *flow_args.stdout.split(), "--order", "2",
          "--first-order-start", "--stationary-tolerance", "1e-3", "--max-iterations", "300",
          "-o", "flow.h5", ok=(0, 1))
    shutil.copy(folder / "flow.h5", folder / "flow_prev.h5")
    stage("heat", "tfmb-heat", "solidmesh.h5", "flow.h5", "model.h5", "--db", "materials-db.h5",
          "-o", "thermal.h5")
    stage("matmap", "tfmb-matmap", "thermal.h5", "model.h5", "--db", "materials-db.h5",
          "-o", "materials.h5")
    stage("loads forces", "tfmb-loads", "forces", "flow.h5", "model.h5", "-o", "loads.h5")
    stage("beam", "tfmb-beam", "model.h5", "loads.h5", "materials.h5", "-o", "structure.h5")
    stage("loads displace", "tfmb-loads", "displace", "structure.h5", "model.h5",
          "--mesh", "flowmesh.h5", "-o", "walldisp.h5")
    return folder, case_files


# --------------------------------------------------------------------------------------------
# Running the samples

def run_sample(src, bin_dir, scratch, tool, k, sample, setups, env):
    """(ok, rc, seconds, command line as run, problem)."""
    tokens = sample["tokens"]
    if not tokens or tokens[0] != tool:
        return False, None, 0.0, shlex.join(tokens), f"does not start with {tool}"
    extra = []
    for name, applies, options in SHORTEN:
        if name == tool and applies(tokens):
            extra += options
    shown = shlex.join(tokens + extra)
    setup, case_files = setups[sample_case(sample)]
    folder = scratch / f"{tool}-{k}"
    shutil.rmtree(folder, ignore_errors=True)
    folder.mkdir(parents=True)
    for name in ("cases", "data"):
        (folder / name).symlink_to(src / name, target_is_directory=True)
    outputs = output_files(tokens)
    for tok in tokens[1:]:
        if tok in outputs or "/" in tok or not (setup / tok).is_file():
            continue
        shutil.copy(setup / tok, folder / tok)
        if tok == "case.toml":  # its geometry file is named relative to it
            for f in case_files:
                shutil.copy(setup / f, folder / f)
    log = folder / "log.txt"
    rc, secs = run([bin_dir / tool, *tokens[1:], *extra], folder, env, log)
    expected = expected_code(sample)
    if rc != expected:
        what = "timed out" if rc == -1 else f"exit {rc}, expected {expected}"
        return False, rc, secs, shown, f"{what}; last lines of {log}:\n{tail(log)}"
    if expected != 0:
        return True, rc, secs, shown, None
    for out in outputs:
        path = folder / out
        if not path.is_file() or path.stat().st_size == 0:
            return False, rc, secs, shown, f"no output {out}"
        if out.endswith(".h5"):
            check = subprocess.run([bin_dir / "tfmb-check", "--no-summary", out], cwd=folder,
                                   capture_output=True, text=True)
            if check.returncode != 0:
                report = (check.stdout + check.stderr).strip()
                return False, rc, secs, shown, (f"{out} fails tfmb-check "
                                                f"(exit {check.returncode}):\n{report}")
    return True, rc, secs, shown, None


def main(argv):
    if len(argv) < 4 or argv[1] in ("-h", "--help"):
        print(__doc__)
        return 0 if len(argv) > 1 and argv[1] in ("-h", "--help") else 2
    src = pathlib.Path(argv[1]).resolve()
    bin_dir = pathlib.Path(argv[2]).resolve()
    scratch = pathlib.Path(argv[3]).resolve()
    only = set(argv[5:]) if len(argv) > 4 and argv[4] == "--only" else None

    samples = []  # (tool, k, sample, main.cpp)
    failed = []
    for main_cpp in main_sources(src):
        tool = main_cpp.relative_to(src / "tools").parts[0]
        if only and tool not in only:
            continue
        parsed = parse_samples(main_cpp.read_text())
        if not parsed:
            print(f"FAIL  {tool}: no 'Sample runs:' commands in {main_cpp.relative_to(src)}")
            failed.append(f"{tool} (no samples)")
        for k, sample in enumerate(parsed, 1):
            samples.append((tool, k, sample, main_cpp))

    shutil.rmtree(scratch, ignore_errors=True)
    scratch.mkdir(parents=True)
    env = dict(os.environ)
    # As Makefile.cases: idle OpenMP threads sleep, so tfmb-flow's 2 threads do not spin against
    # each other on a busy machine.
    env["OMP_WAIT_POLICY"] = "passive"
    # tfmb-heat's header: the database defaults to $TFMB_MATERIAL_DB when --db is not given.
    env["TFMB_MATERIAL_DB"] = str(src / "data" / "materials-db.h5")

    setups = {}
    start = time.monotonic()
    try:
        for case in sorted({DEFAULT_CASE} | {sample_case(s) for _, _, s, _ in samples}):
            t0 = time.monotonic()
            setups[case] = setup_case(src, bin_dir, scratch, case, env)
            print(f"set-up {case}: {time.monotonic() - t0:.1f} s ({setups[case][0]})")
    except SetupError as e:
        print(f"FAIL  {e}")
        return 1
    sys.stdout.flush()

    for tool, k, sample, main_cpp in samples:
        ok, rc, secs, shown, problem = run_sample(src, bin_dir, scratch, tool, k, sample,
                                                  setups, env)
        where = f"{main_cpp.relative_to(src)}:{sample['line']}"
        print(f"{'ok  ' if ok else 'FAIL'}  {tool:12s} {shown}  -> rc {rc}, {secs:.1f} s")
        if not ok:
            print(f"      {where}: {problem}")
            failed.append(f"{tool} sample {k} ({where})")
        sys.stdout.flush()
    total = time.monotonic() - start
    if failed:
        print(f"samples: {len(failed)} failed ({total:.0f} s): " + "; ".join(failed))
        return 1
    print(f"samples: all {len(samples)} documented sample runs pass ({total:.0f} s)")
    return 0


# --------------------------------------------------------------------------------------------

PLANTED_HEADER = """\
// tfmb-x: a planted header.
//
// Sample runs:
//   tfmb-x in.h5 -o out.h5                      # a note, not an argument
//   tfmb-x in.h5 --function "p=1; q=2" -o b.h5   (cases/other)
//   tfmb-x in.h5 --long-option 1
//     --continued 2 -o c.h5      (a note on a continuation line)
//   tfmb-x bad.h5   (exit 3)
// Prose after the samples.
#include <x>
//   tfmb-x not-a-sample
"""


def self_test():
    got = parse_samples(PLANTED_HEADER)
    want = [["tfmb-x", "in.h5", "-o", "out.h5"],
            ["tfmb-x", "in.h5", "--function", "p=1; q=2", "-o", "b.h5"],
            ["tfmb-x", "in.h5", "--long-option", "1", "--continued", "2", "-o", "c.h5"],
            ["tfmb-x", "bad.h5"]]
    problems = []
    if [s["tokens"] for s in got] != want:
        problems.append(f"tokens {[s['tokens'] for s in got]}")
    if [sample_case(s) for s in got] != [DEFAULT_CASE, "other", DEFAULT_CASE, DEFAULT_CASE]:
        problems.append("cases " + str([sample_case(s) for s in got]))
    if [expected_code(s) for s in got] != [0, 0, 0, 3]:
        problems.append("exit codes " + str([expected_code(s) for s in got]))
    if [output_files(s["tokens"]) for s in got] != [["out.h5"], ["b.h5"], ["c.h5"], []]:
        problems.append("outputs " + str([output_files(s["tokens"]) for s in got]))
    if parse_samples("// no samples here\nint x;\n"):
        problems.append("samples found in a header without a 'Sample runs:' section")
    for p in problems:
        print(f"self-test: wrong {p}")
    print("self-test: " + ("failed" if problems else "the parser reads the planted header"))
    return 1 if problems else 0


if __name__ == "__main__":
    if sys.argv[1:] == ["--self-test"]:
        sys.exit(self_test())
    sys.exit(main(sys.argv))
