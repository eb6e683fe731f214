# config2 (seed Table 3): simple nozzle, two-way; in the upper half the two joints become one
# revolute joint with clearance (upper_12; upper_2 and upper_3 stay rigidly joined), so the
# solution can turn asymmetric. A torsional restraint is needed for a static solution: the
# clearance joint carries a spring (see README.md).
CASE_TOML = cases/simple-nozzle/case.toml
ANALYSIS = twoway
SET += --set joint.upper_12.kind=revolute_clearance --set joint.upper_12.inner_radius=0.004 \
       --set joint.upper_12.outer_radius=0.0042 --set analysis.kind=twoway \
       --set analysis.time=dynamic --set analysis.end_time=0.01 --set analysis.time_step=0.0005
# Flow conditions of every configuration: the seed's NPR 5.423 and a stagnation temperature that
# the Ti-6Al-4V strength tables cover (yield and ultimate strength to 810.9 K).
SET += --set flow.nozzle_pressure_ratio=5.423 --set flow.stagnation_temperature=750
# First-order convection: the second-order reconstruction of tfmb-flow does not yet converge on
# nozzles discharging into a far field (flow issues); first order does on the coarse (SMOKE) mesh.
FLOW_OPTS = --threads 2 --order 1
