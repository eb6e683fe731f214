# config3 (seed Table 3): realistic nozzle, one-way, every revolute joint restrained.
CASE_TOML = cases/realistic-nozzle/case.toml
ANALYSIS = oneway
# Flow conditions of every configuration: the seed's NPR 5.423 and a stagnation temperature that
# the Ti-6Al-4V strength tables cover (yield and ultimate strength to 810.9 K).
SET += --set flow.nozzle_pressure_ratio=5.423 --set flow.stagnation_temperature=750
# The convergent flaps' outer sides and the cavity between divergent and external flaps are not
# part of the flow domain (closed, vented cavity): they are loaded with the ambient pressure.
LOADS_OPTS += --missing-side-pressure 101325
