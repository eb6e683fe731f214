#!/usr/bin/env bash
# workflows/flow-benchmarks end to end on its cheapest entry (NPARC 0.75 on 240 x 60, a few
# seconds): the table row and the JSON figures are there and the run converged; usage errors
# exit 2. Arguments: source dir, scratch dir, bin dir.
set -euo pipefail
src=$1 scratch=$2 bin=$3
rm -rf "$scratch" && mkdir -p "$scratch"
list=$("$src/workflows/flow-benchmarks" --list)
grep -q '^nasa-2dcd-8.91 ' <<<"$list"
rc=0; "$src/workflows/flow-benchmarks" --only no-such-benchmark --bin "$bin" 2>/dev/null || rc=$?
[ "$rc" -eq 2 ] || { echo "unknown benchmark: exit $rc, expected 2"; exit 1; }
rc=0; "$src/workflows/flow-benchmarks" --pairs 0 --bin "$bin" 2>/dev/null || rc=$?
[ "$rc" -eq 2 ] || { echo "--pairs 0: exit $rc, expected 2"; exit 1; }
"$src/workflows/flow-benchmarks" --run-root "$scratch" --bin "$bin" --only nparc-0.75-240x60 \
  --json "$scratch/figures.json" | tee "$scratch/table.txt"
grep -q '^| nparc-0.75-240x60 | 14,701 | 1 | ' "$scratch/table.txt"
grep -q 'OpenMP waits: ' "$scratch/table.txt"  # the waits the timings ran with
/usr/bin/python3 - "$scratch/figures.json" <<'PY'
import json, sys
[f] = json.load(open(sys.argv[1]))
assert f["converged"], f
assert f["evaluations"] >= f["iterations"] > 0, f
assert f["residual_s"] > 0 and f["wall_s"] >= f["residual_s"], f
assert f["peak_mb"] > 0, f
print("flow-benchmarks: figures read back:", {k: f[k] for k in ("iterations", "linear", "wall_s")})
PY
# the cost ratio's split into the GMRES iterations' growth and the rest (figures of session 52's
# call: 55 / 535 and 68 / 1,024 iterations, cost ratio 1.74)
/usr/bin/python3 - "$src/workflows/flow-benchmarks" <<'PY'
import sys
from importlib.machinery import SourceFileLoader
fb = SourceFileLoader("flow_benchmarks", sys.argv[1]).load_module()
iterations, rest = fb.cost_split({"iterations": 55, "linear": 535}, {"iterations": 68, "linear": 1024}, 1.74)
assert abs(iterations - 1.548) < 1e-3 and abs(rest - 1.124) < 1e-3, (iterations, rest)
print(f"flow-benchmarks: cost split {iterations:.3f} x {rest:.3f}")
PY
