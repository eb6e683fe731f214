#!/usr/bin/env bash
# workflows/study on local cores: a two-point study (config1 one-way, SMOKE, NPR 4 and 6) run by
# snakemake through Makefile.cases; results.csv has both points with every quantity a one-way
# run gives, and the physics of a higher NPR (more thrust, more deflection); a plot per quantity;
# a second run redoes nothing; a failing point fails the study (exit 1) and is marked in the
# table; bad study files exit 3 with one line naming the file and what is wrong, usage errors 2.
# About 80 s on 2 cores (two SMOKE one-way runs one after the other).
#   test_study.sh SOURCE_DIR SCRATCH_DIR BIN_DIR
set -euo pipefail
src=$(cd "$1" && pwd) scratch=$2 bin=$(cd "$3" && pwd)
study=$src/workflows/study
fail() { echo "FAIL: $*" >&2; exit 1; }
rm -rf "$scratch" && mkdir -p "$scratch"
cd "$scratch"

# Refusals: one line, the right exit code, no traceback.
refused() {  # refused CODE "what the line must say" study-arguments...
  local want=$1 text=$2 rc=0; shift 2
  "$study" "$@" > out.txt 2> err.txt || rc=$?
  [ $rc -eq "$want" ] || fail "study $*: exit $rc, expected $want ($(cat err.txt))"
  [ "$(wc -l < err.txt)" -eq 1 ] || fail "study $*: not one line on stderr: $(cat err.txt)"
  grep -q -- "$text" err.txt || fail "study $*: '$(cat err.txt)' does not say '$text'"
  ! grep -q Traceback err.txt || fail "study $*: traceback"
}
refused 2 "usage" run
refused 2 "usage" frobnicate x.toml
refused 3 "nothing.toml: cannot read" write nothing.toml --bin "$bin"
printf '[study]\ncase = "config1"\ncolour = "red"\n[parameters.npr]\nset = "flow.nozzle_pressure_ratio"\nvalues = [4]\n' > bad-key.toml
refused 3 "bad-key.toml: \[study\]: unknown key 'colour'" write bad-key.toml --bin "$bin"
printf '[study]\ncase = "config1"\ndesign = "zip"\n[parameters.a]\nset = "flow.nozzle_pressure_ratio"\nvalues = [4, 5]\n[parameters.b]\nvariable = "FLOW_MODEL"\nvalues = ["sa"]\n' > bad-zip.toml
refused 3 "bad-zip.toml: design = zip needs lists of one length" write bad-zip.toml --bin "$bin"
printf '[study]\ncase = "config1"\n[settings]\nRUN = "x"\n[parameters.a]\nset = "flow.nozzle_pressure_ratio"\nvalues = [4]\n' > bad-run.toml
refused 3 "bad-run.toml: \[settings\] RUN: set by the study itself" write bad-run.toml --bin "$bin"
printf '[study\n' > not-toml.toml
refused 3 "not-toml.toml: not TOML" write not-toml.toml --bin "$bin"
echo "ok: refusals (usage 2, bad study files 3, one line each)"

# A grid of a case.toml key and a make variable: one rule per combination, each its own make.
printf '[study]\ncase = "config1"\n[settings]\nSMOKE = 1\n[parameters.npr]\nset = "flow.nozzle_pressure_ratio"\nvalues = [4.0, 6.0]\n[parameters.model]\nvariable = "FLOW_MODEL"\nvalues = ["sa", "sst"]\n' > grid.toml
"$study" write grid.toml --dir "$scratch/grid" --bin "$bin" 2> /dev/null
[ "$(grep -c '^rule p[0-9]*:' grid/Snakefile)" -eq 4 ] || fail "a 2 x 2 grid: not four point rules in grid/Snakefile"
grep -q "RUN=$scratch/grid/points/p004_npr-6.0_model-sst .*FLOW_MODEL=sst 'EXTRA_SET=--set flow.nozzle_pressure_ratio=6.0' oneway" grid/Snakefile \
  || fail "grid/Snakefile: the last point's make command is not NPR 6 under SST"
echo "ok: a 2 x 2 grid writes four point rules"

# Two points, run.
cat > npr.toml <<'EOF'
[study]
case = "config1"
goal = "oneway"
[settings]
SMOKE = 1
[parameters.npr]
set = "flow.nozzle_pressure_ratio"
values = [4.0, 6.0]
EOF
start=$(date +%s)
"$study" run npr.toml --dir "$scratch/npr" --bin "$bin" --cores 2 > npr.log 2>&1 || { tail -30 npr.log; fail "study run"; }
echo "ok: two points in $(( $(date +%s) - start )) s"
/usr/bin/python3 - "$scratch/npr" <<'PY'
import csv, os, sys
d = sys.argv[1]
rows = list(csv.DictReader(open(os.path.join(d, "results.csv"))))
assert [r["npr"] for r in rows] == ["4.0", "6.0"], f"results.csv rows: {[r['point'] for r in rows]}"
quantities = ("discharge_coefficient", "thrust_ratio", "thrust_x", "max_displacement",
              "worst_total_margin", "worst_mechanical_margin")
for r in rows:
    assert r["status"] == "ok" or r["status"].startswith("attention"), f"point {r['point']}: status {r['status']}"
    for q in quantities:
        assert r[q] != "", f"point {r['point']}: no {q}"
low, high = rows
v = {q: (float(low[q]), float(high[q])) for q in quantities}
# A higher nozzle pressure ratio: more thrust per unit depth, more pressure on the flaps (a larger
# deflection and less strain margin); Cd and F/F_i are ratios near 1 for both.
assert v["thrust_x"][1] > v["thrust_x"][0], f"thrust {v['thrust_x']}"
assert v["max_displacement"][1] > v["max_displacement"][0], f"largest displacement {v['max_displacement']}"
assert v["worst_mechanical_margin"][1] < v["worst_mechanical_margin"][0], f"mechanical margin {v['worst_mechanical_margin']}"
for q in ("discharge_coefficient", "thrust_ratio"):
    assert all(0.8 < x < 1.1 for x in v[q]), f"{q} {v[q]}"
for q in quantities:
    png = os.path.join(d, "plots", f"{q}-vs-npr.png")
    assert open(png, "rb").read(8) == b"\x89PNG\r\n\x1a\n", f"{png}: not a PNG"
print("ok: results.csv: " + ", ".join(f"{q} {a:.4g} -> {b:.4g}" for q, (a, b) in v.items()))
PY

# Run again: nothing to do, no point reruns.
before=$(stat -c %Y npr/points/*/summary.json)
"$study" run npr.toml --dir "$scratch/npr" --bin "$bin" --cores 2 > npr-again.log 2>&1 || { tail -30 npr-again.log; fail "study run again"; }
[ "$before" = "$(stat -c %Y npr/points/*/summary.json)" ] || fail "a second run reran points"
grep -q "Nothing to be done" npr-again.log || fail "a second run: snakemake found something to do"
echo "ok: a second run redoes nothing"

# A point that fails (NPR 0.5: tfmb-input refuses it): exit 1, the row marked failed.
sed 's/values = \[4.0, 6.0\]/values = [0.5]/' npr.toml > failing.toml
rc=0
"$study" run failing.toml --dir "$scratch/failing" --bin "$bin" --cores 2 > failing.log 2>&1 || rc=$?
[ $rc -eq 1 ] || { tail -20 failing.log; fail "a failing point: exit $rc, expected 1"; }
grep -q "^p001_npr-0.5,0.5,failed or unfinished (see logs/p001_npr-0.5.log)," failing/results.csv || fail "failing/results.csv: $(cat failing/results.csv)"
grep -q "outside the allowed range" failing/logs/p001_npr-0.5.log || fail "the point's log does not say why it failed"
echo "ok: a failing point fails the study (exit 1), its row marked failed"
