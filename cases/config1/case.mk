# config1 (seed Table 3): simple nozzle, one-way, no special joints (rigid joints).
CASE_TOML = cases/simple-nozzle/case.toml
ANALYSIS = oneway
# Flow conditions of every configuration: the seed's NPR 5.423 and a stagnation temperature that
# the Ti-6Al-4V strength tables cover (yield and ultimate strength to 810.9 K).
SET += --set flow.nozzle_pressure_ratio=5.423 --set flow.stagnation_temperature=750
# First-order convection: the second-order reconstruction of tfmb-flow does not yet converge on
# nozzles discharging into a far field (flow issues); first order does on the coarse (SMOKE) mesh.
FLOW_OPTS = --threads 2 --order 1
