#!/usr/bin/python3
"""Damaged files are refused, never crash a reader (issue 23).

A valid file of every kind (`tfmb-check --example KIND`) is damaged in a fixed, seeded set of
ways: single and multiple byte flips in the superblock, in the HDF5 metadata structures found
by their signatures (object headers, B-trees, heaps) and anywhere in the file, truncations and
zeroed blocks. `tfmb-check` runs on every damaged copy and must exit 0 (the damage hit raw
values that still pass every check) or 3 with stderr lines naming the file, one line when
HDF5 finds the file damaged; a signal, a hang, exit 4 or any other code fails the test.

Then the stages read damaged copies of the files of a real coarse chain (the sample runs'
set-up, tests/samples/run_sample_runs.py: simple-nozzle on a mesh 8x coarser), one input
damaged at a time: tfmb-matmap, tfmb-loads, tfmb-strain, tfmb-beam, tfmb-mesh deform, tfmb-heat
and tfmb-flow --restart must exit 0, 1 or 3, never crash, name the damaged file in the last
line when they exit 3, and leave no output file unless they exit 0 or 1. Stages that are not
built (the sanitizer build makes only tfmb-check) are skipped.

Last, tfmb-plot (tools/tfmb-plot/tfmb-plot, Python) draws from damaged copies of the example
flow, structure, thermal and strain files: it must exit 0 or 3, on 3 print exactly one line
"tfmb-plot: error: ..." naming the damaged file (never a Python traceback), and leave no
picture behind.

  test_corrupt_files.py SOURCE_DIR BIN_DIR SCRATCH_DIR [--seed N] [--per-kind N]
                        [--per-stage N] [--per-plot N] [--keep]

Prints one line per failure and a summary per kind and stage; exits 1 if anything failed.
--keep leaves the damaged files of failures in SCRATCH_DIR/failed/ to reproduce them.
"""
import argparse
import os
import pathlib
import random
import shutil
import signal
import subprocess
import sys
import zlib

# Signatures of the HDF5 structures that carry metadata (HDF5 file format specification, sections
# III and IV): version 2 object headers and their continuation chunks, v1/v2 B-tree nodes, local
# and global heaps, symbol table nodes, fractal heaps and free-space managers.
SIGNATURES = [b"OHDR", b"OCHK", b"TREE", b"BTHD", b"BTIN", b"BTLF", b"HEAP", b"GCOL", b"SNOD",
              b"FRHP", b"FHDB", b"FHIB", b"FSHD", b"FSSE"]
# [s] per run: a valid example checks in well under a second, and the readers give up on a
# file whose HDF5 metadata makes the library loop after 10 s (libcommon h5.cpp).
TIMEOUT = 60
# Exit codes (libcommon errors.hpp): 0 ok, 1 flagged unconverged result, 3 bad input.
READER_CODES = {0, 3}
STAGE_CODES = {0, 1, 3}


def metadata_offsets(data):
    """Offsets of every metadata structure found by its signature, in file order."""
    offsets = []
    for signature in SIGNATURES:
        start = data.find(signature)
        while start >= 0:
            offsets.append(start)
            start = data.find(signature, start + 1)
    return sorted(offsets)


def flip(data, offset, rng):
    """`data` with the byte at `offset` changed (never to its own value)."""
    out = bytearray(data)
    out[offset] ^= rng.randrange(1, 256)
    return bytes(out)


def mutations(data, count, rng):
    """`count` (label, damaged bytes) pairs, deterministic for a given rng state. Two in three
    hit the HDF5 metadata (superblock, structures found by signature): that is what crashed the
    readers; the rest are anywhere-flips, truncations and zeroed blocks."""
    structures = metadata_offsets(data)
    size = len(data)
    result = []
    for i in range(count):
        kind = i % 9
        if kind in (0, 1):  # superblock: signature, versions, sizes, addresses, checksum
            offset = rng.randrange(0, min(size, 96))
            result.append((f"flip superblock byte {offset}", flip(data, offset, rng)))
        elif kind in (2, 3, 4) and structures:  # a structure's header or its first entries
            base = rng.choice(structures)
            offset = min(size - 1, base + rng.randrange(0, 96))
            result.append((f"flip byte {offset} (structure {data[base:base + 4].decode()} at "
                           f"{base})", flip(data, offset, rng)))
        elif kind == 5:  # several flips in one structure
            base = rng.choice(structures) if structures else 0
            out = data
            offsets = sorted({min(size - 1, base + rng.randrange(0, 256)) for _ in range(4)})
            for offset in offsets:
                out = flip(out, offset, rng)
            result.append((f"flip bytes {offsets}", out))
        elif kind == 6:  # anywhere, raw data included
            offset = rng.randrange(0, size)
            result.append((f"flip byte {offset}", flip(data, offset, rng)))
        elif kind == 7:  # truncation, as by a full disk or an interrupted copy
            length = rng.choice([rng.randrange(0, 96), rng.randrange(96, size),
                                 size - rng.randrange(1, 64)])
            result.append((f"truncate to {length} bytes", data[:max(0, length)]))
        else:  # a zeroed block, as by a bad sector
            length = rng.choice([16, 64, 256, 512])
            offset = rng.randrange(0, max(1, size - length))
            out = bytearray(data)
            out[offset:offset + length] = bytes(len(out[offset:offset + length]))
            result.append((f"zero {length} bytes at {offset}", bytes(out)))
    return result


def run(command, cwd=None):
    """(exit code or -signal, stderr text, timed out)."""
    try:
        done = subprocess.run(command, cwd=cwd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                              timeout=TIMEOUT)
    except subprocess.TimeoutExpired as e:
        return None, (e.stderr or b"").decode(errors="replace"), True
    return done.returncode, done.stderr.decode(errors="replace"), False


def outcome(code, timed_out):
    if timed_out:
        return "hang"
    if code < 0:
        return f"signal {signal.Signals(-code).name}"
    return f"exit {code}"


def judge_check(path, code, stderr, timed_out):
    """The failure text of one tfmb-check run on a damaged file, or None."""
    if timed_out or code not in READER_CODES:
        return f"{outcome(code, timed_out)}: {stderr.strip()[-300:]}"
    lines = stderr.splitlines()
    if code == 3:
        if not lines:
            return "exit 3 without a message"
        if any(not line.startswith(f"{path}: ") for line in lines):
            return f"exit 3 with a line not naming the file: {stderr.strip()[-300:]}"
        # Damage HDF5 detects ends the check in one line; damage it cannot see (a string or a
        # value changed in place) may break several rules, one line each as for any bad file.
        if len(lines) != 1 and any(line.endswith(": damaged file") for line in lines):
            return f"{len(lines)} lines for a damaged file, expected one: {stderr[-300:]}"
    elif lines:
        return f"exit 0 with messages: {stderr.strip()[-300:]}"
    return None


def judge_stage(path, output, code, stderr, timed_out, check):
    """The failure text of one stage run on a damaged input, or None."""
    if timed_out or code not in STAGE_CODES:
        return f"{outcome(code, timed_out)}: {stderr.strip()[-300:]}"
    if code == 3:
        lines = stderr.strip().splitlines()
        if not lines:
            return "exit 3 without a message"
        if os.path.basename(path) not in lines[-1]:
            # Values changed in place can leave a file valid on its own (tfmb-check accepts
            # it) that disagrees with another input; the stage may then name the other one.
            valid_alone = subprocess.run([check, "--no-summary", path], cwd=os.path.dirname(path),
                                         capture_output=True).returncode == 0
            if not valid_alone:
                return f"exit 3 without a last line naming the file: {stderr.strip()[-300:]}"
        stem = output[:-len(".h5")]
        left = [f for f in (output, output + ".tmp", stem + ".xdmf") if os.path.exists(f)]
        if left:
            return f"exit 3 but it left {', '.join(os.path.basename(f) for f in left)}"
    return None


def run_stages(args, bin_dir, scratch, fail):
    """Each stage on damaged copies of each of its inputs; returns the number of runs."""
    src = pathlib.Path(args.source).resolve()
    sys.path.insert(0, str(src / "tests" / "samples"))
    import run_sample_runs  # the chain set-up of the sample runs, not a second copy of it
    env = dict(os.environ, OMP_WAIT_POLICY="passive")
    chain, _ = run_sample_runs.setup_case(src, pathlib.Path(bin_dir), pathlib.Path(scratch),
                                          run_sample_runs.DEFAULT_CASE, env)
    # (tool, arguments): the sample runs' commands (each tool's main.cpp), every input a file of
    # the chain; each .h5 input in turn is replaced by a damaged copy.
    stages = [
        ("tfmb-matmap", ["thermal.h5", "model.h5", "--db", "materials-db.h5", "-o", "out.h5"]),
        ("tfmb-loads", ["forces", "flow.h5", "model.h5", "-o", "out.h5"]),
        ("tfmb-loads", ["displace", "structure.h5", "model.h5", "--mesh", "flowmesh.h5",
                        "-o", "out.h5"]),
        ("tfmb-strain", ["structure.h5", "materials.h5", "-o", "out.h5"]),
        ("tfmb-beam", ["model.h5", "loads.h5", "materials.h5", "-o", "out.h5"]),
        ("tfmb-mesh", ["deform", "flowmesh.h5", "walldisp.h5", "-o", "out.h5"]),
        ("tfmb-heat", ["solidmesh.h5", "flow.h5", "model.h5", "--db", "materials-db.h5",
                       "-o", "out.h5"]),
        ("tfmb-flow", ["flowmesh.h5", "--p0", "5.5e5", "--T0", "294", "--restart", "flow.h5",
                       "--max-iterations", "2", "-o", "out.h5"]),
    ]
    originals = {}
    runs = 0
    for tool, arguments in stages:
        for position, name in enumerate(arguments):
            if not name.endswith(".h5") or name == "out.h5":
                continue
            if name not in originals:
                with open(chain / name, "rb") as f:
                    originals[name] = f.read()
            label = f"{tool} {arguments[0]}" if tool in ("tfmb-loads", "tfmb-mesh") else tool
            rng = random.Random(args.seed * 1000003 + zlib.crc32(f"{label} {name}".encode()))
            counts = {}
            for k, (what, data) in enumerate(mutations(originals[name], args.per_stage, rng)):
                work = os.path.join(scratch, "stages", f"{tool}-{position}-{k:02d}")
                os.makedirs(work)
                for other in arguments:
                    if other.endswith(".h5") and other not in (name, "out.h5"):
                        shutil.copy(chain / other, os.path.join(work, other))
                damaged = "damaged-" + name
                with open(os.path.join(work, damaged), "wb") as f:
                    f.write(data)
                command = [os.path.join(bin_dir, tool)] + [damaged if i == position else a
                                                           for i, a in enumerate(arguments)]
                code, stderr, timed_out = run(command, cwd=work)
                runs += 1
                verdict = outcome(code, timed_out)
                counts[verdict] = counts.get(verdict, 0) + 1
                problem = judge_stage(os.path.join(work, damaged), os.path.join(work, "out.h5"),
                                      code, stderr, timed_out, os.path.join(bin_dir, "tfmb-check"))
                if problem:
                    fail(f"{label} with damaged {name} #{k} ({what}): {problem}",
                         os.path.join(work, damaged))
                else:
                    shutil.rmtree(work)
            print(f"{label} with a damaged {name}: {args.per_stage} runs: "
                  + ", ".join(f"{n} {v}" for v, n in sorted(counts.items())), flush=True)
    return runs


# tfmb-plot's picture of each kind it reads (tools/tfmb-plot/tfmb-plot).
PLOTS = {"flow": [["wall-pressure"], ["field", "--field", "mach"], ["residuals"]],
         "structure": [["deformed"]], "thermal": [["temperature"]], "strain": [["strain"]]}


def judge_plot(path, output, code, stderr, timed_out):
    """The failure text of one tfmb-plot run on a damaged file, or None."""
    if timed_out or code not in READER_CODES:
        return f"{outcome(code, timed_out)}: {stderr.strip()[-300:]}"
    lines = stderr.splitlines()
    if "Traceback" in stderr:
        return f"a Python traceback: {stderr.strip()[-300:]}"
    if code == 3:
        if len(lines) != 1 or not lines[0].startswith(f"tfmb-plot: error: {path}"):
            return f"exit 3 without one line naming the file: {stderr.strip()[-300:]}"
        if os.path.exists(output):
            return "exit 3 but it left the picture"
    return None


def run_plots(args, valid, scratch, fail):
    """tfmb-plot on damaged copies of the example files; returns the number of runs."""
    plot = os.path.join(os.path.abspath(args.source), "tools", "tfmb-plot", "tfmb-plot")
    runs = 0
    work = os.path.join(scratch, "plot")
    os.makedirs(work)
    for kind, commands in PLOTS.items():
        rng = random.Random(args.seed * 1000003 + zlib.crc32(f"tfmb-plot {kind}".encode()))
        counts = {}
        for k, (label, data) in enumerate(mutations(valid[kind], args.per_plot, rng)):
            path = os.path.join(work, f"{kind}-{k:02d}.h5")
            with open(path, "wb") as f:
                f.write(data)
            command = commands[k % len(commands)]
            output = os.path.join(work, "out.png")
            code, stderr, timed_out = run([plot, command[0], path, *command[1:], "-o", output])
            runs += 1
            verdict = outcome(code, timed_out)
            counts[verdict] = counts.get(verdict, 0) + 1
            problem = judge_plot(path, output, code, stderr, timed_out)
            if problem:
                fail(f"tfmb-plot {command[0]} {kind} #{k} ({label}): {problem}", path)
            else:
                os.remove(path)
            if os.path.exists(output):
                os.remove(output)
        print(f"tfmb-plot {kind}: {args.per_plot} damaged copies: "
              + ", ".join(f"{n} {v}" for v, n in sorted(counts.items())), flush=True)
    return runs


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("source")
    parser.add_argument("bin")
    parser.add_argument("scratch")
    parser.add_argument("--seed", type=int, default=23)
    parser.add_argument("--per-kind", type=int, default=36)
    parser.add_argument("--per-stage", type=int, default=9)
    parser.add_argument("--per-plot", type=int, default=9)
    parser.add_argument("--keep", action="store_true")
    args = parser.parse_args()
    bin_dir = os.path.abspath(args.bin)
    check = os.path.join(bin_dir, "tfmb-check")
    scratch = os.path.abspath(args.scratch)
    shutil.rmtree(scratch, ignore_errors=True)
    os.makedirs(os.path.join(scratch, "valid"))
    failures = []

    def fail(text, damaged=None):
        failures.append(text)
        print("FAIL " + text, flush=True)
        if args.keep and damaged is not None:
            os.makedirs(os.path.join(scratch, "failed"), exist_ok=True)
            shutil.copy(damaged, os.path.join(scratch, "failed", f"{len(failures)}.h5"))

    listing = subprocess.run([check, "--list"], capture_output=True, text=True, check=True)
    kinds = [line.split()[0] for line in listing.stdout.splitlines() if line.strip()]
    valid = {}
    for kind in kinds:
        path = os.path.join(scratch, "valid", f"{kind}.h5")
        subprocess.run([check, "--example", kind, "-o", path], check=True)
        code, stderr, _ = run([check, "--no-summary", path])
        if code != 0:
            fail(f"{kind}: the valid example fails tfmb-check: {stderr.strip()}")
        with open(path, "rb") as f:
            valid[kind] = f.read()

    # tfmb-check on every damaged copy of every kind.
    damaged_dir = os.path.join(scratch, "damaged")
    os.makedirs(damaged_dir)
    totals = {"exit 0": 0, "exit 3": 0}
    for kind in kinds:
        # One seed per kind, so that adding a kind does not change the others' mutations.
        rng = random.Random(args.seed * 1000003 + zlib.crc32(kind.encode()))
        counts = {}
        for k, (label, data) in enumerate(mutations(valid[kind], args.per_kind, rng)):
            path = os.path.join(damaged_dir, f"{kind}-{k:02d}.h5")
            with open(path, "wb") as f:
                f.write(data)
            code, stderr, timed_out = run([check, "--no-summary", path])
            verdict = outcome(code, timed_out)
            counts[verdict] = counts.get(verdict, 0) + 1
            problem = judge_check(path, code, stderr, timed_out)
            if problem:
                fail(f"tfmb-check {kind} #{k} ({label}): {problem}", path)
            else:
                totals[verdict] += 1
                os.remove(path)
        print(f"tfmb-check {kind}: {args.per_kind} damaged copies: "
              + ", ".join(f"{n} {v}" for v, n in sorted(counts.items())), flush=True)

    # The stages' own readers on damaged copies of a real chain's files, one input at a time.
    stage_runs = 0
    tools = ["tfmb-input", "tfmb-mesh", "tfmb-flow", "tfmb-heat", "tfmb-matmap", "tfmb-loads",
             "tfmb-beam", "tfmb-strain"]
    missing = [t for t in tools if not os.path.exists(os.path.join(bin_dir, t))]
    if missing:
        print(f"stages: {', '.join(missing)} not built, the stage runs are skipped")
    else:
        stage_runs = run_stages(args, bin_dir, scratch, fail)

    plot_runs = run_plots(args, valid, scratch, fail) if args.per_plot > 0 else 0

    checked = len(kinds) * args.per_kind
    print(f"tfmb-check: {checked} damaged files of {len(kinds)} kinds; stages: {stage_runs} runs; "
          f"tfmb-plot: {plot_runs} runs; {len(failures)} failures")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
