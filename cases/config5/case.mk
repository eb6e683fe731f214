# config5 (seed Table 3): realistic nozzle, two-way, the throat joint of each half a revolute
# joint with a torsional spring of 100 N m/rad instead of a restraint (see README.md for why the
# lip joints stay restrained in a static analysis).
CASE_TOML = $(CASES_DIR)/realistic-nozzle/case.toml
ANALYSIS = twoway
SET += --set analysis.kind=twoway \
       --set joint.upper_throat.kind=revolute_spring --set joint.upper_throat.stiffness=100 \
       --set joint.lower_throat.kind=revolute_spring --set joint.lower_throat.stiffness=100
# Flow conditions of every configuration: the seed's NPR 5.423 and a stagnation temperature that
# the Ti-6Al-4V strength tables cover (yield and ultimate strength to 810.9 K).
SET += --set flow.nozzle_pressure_ratio=5.423 --set flow.stagnation_temperature=750
# The convergent flaps' outer sides and the cavity between divergent and external flaps are not
# part of the flow domain (closed, vented cavity): they are loaded with the ambient pressure.
LOADS_OPTS += --missing-side-pressure 101325
# Flap sections: a stiffened flap represented by a 20 mm equivalent titanium plate (a 3 mm sheet,
# as drawn, cannot carry 5.4 bar over these spans: its bending stress would exceed 1 GPa).
SET += $(foreach f,upper_convergent upper_divergent upper_external lower_convergent lower_divergent lower_external,--set flap.$(f).thickness=0.02)
# Flow: second-order Spalart-Allmaras RANS (first-order start, then second order until the wall
# pressure is stationary to 1e-6), as cases/nasa-2dcd; the wall layers reach y+ about 1
# (flow.yplus_target in case.toml). Its heat transfer coefficient and adiabatic wall temperature
# load tfmb-heat (thermal.solid_boundary = convection_radiation in case.toml).
FLOW_MODEL = sa
FLOW_OPTS = --threads 2 --order 2 --first-order-start --stationary-tolerance 1e-6
