#!/usr/bin/env bash
# workflows/adapters/calculix-beam on config1 (SMOKE meshes, the analytic stand-in flow so that
# the test takes seconds): its structure.h5 passes tfmb-check and agrees with tfmb-beam's, both
# with dead loads (the adapter's *CLOAD is dead). Tolerances, from the measured comparison in
# workflows/adapters/README.md: displacements within 2 % of the largest (measured 1.25 %: B32R
# with one ccx element per model element is 1.1 % stiffer than beam theory on a cantilever),
# support and joint forces within 1 % (measured 0.18 %). A joint kind the adapter cannot
# represent is refused with exit 3. Skips (exit code 77) only when ccx is not installed.
#   test_calculix_beam.sh SOURCE_DIR SCRATCH_DIR BIN_DIR
set -euo pipefail
src=$1 run=$2 bin=$3
if ! command -v ccx > /dev/null; then
  echo "SKIP: ccx (CalculiX) is not installed (apt-get install calculix-ccx)"
  exit 77
fi
adapter=$src/workflows/adapters/calculix-beam
compare=$src/workflows/adapters/compare-structure
rm -rf "$run" && mkdir -p "$run"
make -s -f "$src/Makefile.cases" CASE=config1 SMOKE=1 RUN="$run" BIN="$bin" \
  FLOW="$src/tests/workflows/analytic-flow" "$run/loads.h5" "$run/materials.h5" > "$run/make.log" 2>&1 \
  || { tail -20 "$run/make.log"; exit 1; }

"$adapter" --help > /dev/null
"$adapter" "$run/model.h5" "$run/loads.h5" "$run/materials.h5" -o "$run/ccx.h5"
"$bin/tfmb-check" "$run/ccx.h5" > /dev/null
"$bin/tfmb-beam" "$run/model.h5" "$run/loads.h5" "$run/materials.h5" --dead-loads -o "$run/beam.h5" 2> /dev/null
"$compare" "$run/beam.h5" "$run/ccx.h5" --names tfmb-beam,ccx --json "$run/compare.json" --max-relative 0.02

/usr/bin/python3 - "$run/compare.json" <<'PY'
import json, sys
import numpy as np
c = json.load(open(sys.argv[1]))
worst = 0.0
for j in c["joints"]:
    a, b = np.array(j["a"][:2]), np.array(j["b"][:2])
    worst = max(worst, np.linalg.norm(a - b) / np.linalg.norm(a))
print(f"largest joint/support force difference {worst:.3%}")
sys.exit(0 if worst < 0.01 else 1)
PY

# A clearance joint is refused with one line and exit 3, and a missing input likewise.
/usr/bin/python3 - "$run/model.h5" "$run/model-clearance.h5" <<'PY'
import shutil, sys
import h5py
shutil.copy(sys.argv[1], sys.argv[2])
with h5py.File(sys.argv[2], "r+") as f:
    name = sorted(f["joints"])[0]
    f["joints"][name].attrs["kind"] = "revolute_clearance"
PY
rc=0; "$adapter" "$run/model-clearance.h5" -o "$run/refused.h5" 2> "$run/refused.txt" || rc=$?
[ $rc -eq 3 ] && [ "$(wc -l < "$run/refused.txt")" -eq 1 ] && grep -q revolute_clearance "$run/refused.txt" \
  || { echo "clearance joint: expected exit 3 with one line, got $rc:"; cat "$run/refused.txt"; exit 1; }
rc=0; "$adapter" "$run/no-such.h5" -o "$run/x.h5" 2> "$run/missing.txt" || rc=$?
[ $rc -eq 3 ] && [ "$(wc -l < "$run/missing.txt")" -eq 1 ] || { echo "missing input: exit $rc"; exit 1; }
[ ! -e "$run/refused.h5" ] || { echo "a refused model left a structure.h5"; exit 1; }
echo "calculix-beam: ok"
