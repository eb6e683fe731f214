"""calculix: write CalculiX (ccx) input decks and read its .dat and .frd results, for the adapters
that run ccx in place of a tfmb stage (workflows/adapters/README.md).

    deck = Deck("title"); deck.card("*NODE, NSET=NALL", rows)       # rows: tuples, one per line
    run(deck_text, workdir, job="beam")                              # -> (returncode, log text)
    blocks = read_dat(path)      # {(quantity, set): {node: values}}, the last time of each
    frd = read_frd(path)         # nodes, elements, results {name: {node: values}} (last step)

Card syntax and the meaning of every keyword: CalculiX CrunchiX User's Manual 2.20 (G. Dhondt).
The same conventions as the beam benchmark's reference decks (refdata/beam/calculix/*.inp):
one NSET per purpose, B32R beams with a RECT section, NLGEOM static steps.
"""
import os
import shutil
import subprocess


class Deck:
    """An input deck built card by card; text() joins it."""

    def __init__(self, heading):
        self.lines = ["*HEADING", heading]

    def card(self, keyword, rows=()):
        self.lines.append(keyword)
        for row in rows:
            self.lines.append(", ".join(_fmt(v) for v in row) if isinstance(row, (tuple, list)) else str(row))

    def comment(self, text):
        # ccx skips lines starting with "**".
        self.lines.extend("** " + line for line in text.splitlines())

    def text(self):
        return "\n".join(self.lines) + "\n"


def _fmt(value):
    if isinstance(value, float):
        # ccx reads a number from at most 20 characters (Fortran (1:20) fields): 13 significant
        # digits, 19 characters with sign and exponent.
        return "%.12e" % value
    return str(value)


def available():
    """Path of ccx on PATH, or None."""
    return shutil.which("ccx")


def run(deck_text, workdir, job="beam", threads=1, timeout=None):
    """Writes workdir/job.inp and runs ccx there; returns (returncode, log text). ccx reports some
    failures only in its log with return code 0 ("*ERROR", non-convergence): callers check it."""
    os.makedirs(workdir, exist_ok=True)
    with open(os.path.join(workdir, job + ".inp"), "w") as f:
        f.write(deck_text)
    for ext in (".dat", ".frd", ".sta", ".cvg"):
        path = os.path.join(workdir, job + ext)
        if os.path.exists(path):
            os.remove(path)
    env = dict(os.environ, OMP_NUM_THREADS=str(threads), CCX_NPROC_EQUATION_SOLVER=str(threads))
    proc = subprocess.run(["ccx", job], cwd=workdir, env=env, stdout=subprocess.PIPE,
                          stderr=subprocess.STDOUT, timeout=timeout)
    log = proc.stdout.decode(errors="replace")
    with open(os.path.join(workdir, "ccx.log"), "w") as f:
        f.write(log)
    return proc.returncode, log


def log_errors(log):
    """The lines of a ccx log that say the run failed (ccx may still exit 0)."""
    bad = ("*ERROR", "increment size smaller than minimum", "divergence")
    return [line.strip() for line in log.splitlines() if any(b in line for b in bad)]


def read_dat(path):
    """Blocks of a .dat file written by *NODE PRINT: {(quantity, set): {node: [values]}}, quantity
    'displacements' or 'forces' as ccx titles them; for every block the last time printed wins.
    A value printed in a local system (*TRANSFORM) is flagged: {node: ([values], True)}."""
    blocks = {}
    current = None
    with open(path) as f:
        for line in f:
            text = line.strip()
            if not text:
                continue
            if " for set " in text and " and time " in text:
                quantity = text.split()[0]
                nset = text.split(" for set ")[1].split(" and time ")[0].strip()
                current = {}
                blocks[(quantity, nset)] = current
                continue
            if current is None:
                continue
            parts = text.split()
            try:
                node = int(parts[0])
                local = parts[-1] == "L"
                values = [float(v) for v in (parts[1:-1] if local else parts[1:])]
            except ValueError:
                current = None
                continue
            current[node] = (values, local)
    return blocks


def read_frd(path):
    """Nodes {id: (x, y, z)}, elements {id: [nodes]} and the last result block of each name
    {name: {node: [values]}} of an ASCII .frd file (fixed columns: 3 + I10 + n x E12.5)."""
    nodes, elements, results = {}, {}, {}
    with open(path) as f:
        lines = f.read().splitlines()
    i, n = 0, len(lines)
    while i < n:
        line = lines[i]
        key = line[:6].strip()
        if key == "2C":
            i += 1
            while i < n and lines[i].startswith(" -1"):
                row = lines[i]
                nodes[int(row[3:13])] = tuple(float(row[13 + 12 * k:25 + 12 * k]) for k in range(3))
                i += 1
            continue
        if key == "3C":
            i += 1
            elem = None
            while i < n and (lines[i].startswith(" -1") or lines[i].startswith(" -2")):
                row = lines[i]
                if row.startswith(" -1"):
                    elem = int(row[3:13])
                    elements[elem] = []
                else:
                    elements[elem].extend(int(row[3 + 10 * k:13 + 10 * k])
                                          for k in range((len(row) - 3) // 10))
                i += 1
            continue
        if line.startswith(" -4"):
            name = line.split()[1]
            values = {}
            i += 1
            while i < n and lines[i].startswith(" -5"):
                i += 1
            while i < n and lines[i].startswith(" -1"):
                row = lines[i]
                count = (len(row) - 13) // 12
                values[int(row[3:13])] = [float(row[13 + 12 * k:25 + 12 * k]) for k in range(count)]
                i += 1
            results[name] = values
            continue
        i += 1
    return nodes, elements, results
