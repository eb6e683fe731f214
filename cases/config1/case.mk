# config1 (seed Table 3): simple nozzle, one-way, no special joints (rigid joints). Each wall is
# clamped upstream and hinged to the sidewalls at the flap junctions (cases/simple-nozzle/case.toml
# and README.md: the seed names no supports; a 0.75 m cantilever cannot carry the pressure).
CASE_TOML = $(CASES_DIR)/simple-nozzle/case.toml
ANALYSIS = oneway
# Flow conditions of every configuration: the seed's NPR 5.423 and a stagnation temperature that
# the Ti-6Al-4V strength tables cover (yield and ultimate strength to 810.9 K).
SET += --set flow.nozzle_pressure_ratio=5.423 --set flow.stagnation_temperature=750
# Flap sections: a stiffened flap represented by a 10 mm equivalent titanium plate (the 3 mm sheet
# as drawn would carry about 2 GPa of bending stress over a 0.25 m span at 4 bar, 10 mm about
# 0.2 GPa: see cases/simple-nozzle/README.md).
SET += $(foreach f,upper_1 upper_2 upper_3 lower_1 lower_2 lower_3,--set flap.$(f).thickness=0.01)
# Flow: second-order Spalart-Allmaras RANS (first-order start, then second order until the wall
# pressure is stationary to 1e-6), as cases/nasa-2dcd; the wall layers reach y+ about 1
# (flow.yplus_target in case.toml). Its heat transfer coefficient and adiabatic wall temperature
# load tfmb-heat (thermal.solid_boundary = convection_radiation in case.toml).
FLOW_MODEL = sa
FLOW_OPTS = --threads 2 --order 2 --first-order-start --stationary-tolerance 1e-6
# The seed's comparison: the same beam problem with the pressure as a few nodal forces per flap
# (its manual RecurDyn route); difference in runs/config1/nodal-forces.json and plots/nodal_forces.png.
ONEWAY_EXTRA = $(RUN)/nodal-forces.json
