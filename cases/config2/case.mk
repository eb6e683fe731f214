# config2 (seed Table 3): simple nozzle, two-way, with a clearance joint in the upper half. The
# seed: "two joints in the upper half component were replaced by one including a certain amount
# of clearance". Here the two joints at the upper x = 0.25 m junction, the rigid flap joint
# upper_12 and the sidewall hinge upper_hinge_1, become one revolute joint with 0.2 mm radial
# clearance (4 mm pin in a 4.2 mm bore): upper_1 is a 0.25 m cantilever from the duct whose end
# carries upper_2 through the clearance joint; upper_2 and upper_3 (rigidly joined) turn about the
# x = 0.50 m hinge, so the wall can kink at the joint and the upper half deflects more than the
# lower one (see cases/simple-nozzle/README.md). Contact stiffness 1e10 N/m for the 1 m wide pin
# (line contact, of order E* times the width; the 1e8 default would let the 160 kN/m joint load
# press 1.6 mm into a 0.2 mm clearance).
CASE_TOML = $(CASES_DIR)/simple-nozzle/case.toml
ANALYSIS = twoway
SET += --set analysis.kind=twoway \
       --set joint.upper_12.kind=revolute_clearance --set joint.upper_12.inner_radius=0.004 \
       --set joint.upper_12.outer_radius=0.0042 --set joint.upper_12.contact_stiffness=1e10
# Supports: config1's mounts with the x = 0.25 m upper hinge gone: the remaining hinges' pins run
# in slots along the wall. The upper half is then a determinate chain: upper_1 a 0.25 m
# cantilever from the duct carrying the aft flaps through the clearance joint (full mesh: 44 mm
# at the joint, kink 23 deg, mechanical strain 1.1 % at the duct, beyond yield). The alternative,
# the x = 0.50 m upper hinge pinned (EXTRA_SET="--set support.upper_hinge_2.kind=pinned"), props
# upper_1 through the aft flaps (full mesh: 1.55 mm at the joint, kink 0.47 deg, converged in 5
# iterations); see cases/simple-nozzle/README.md.
SET += --set 'support=[{name="upper_duct",flap="upper_1",end="start",kind="clamp"},{name="upper_hinge_2",flap="upper_2",end="end",kind="sliding_pinned"},{name="lower_duct",flap="lower_1",end="start",kind="clamp"},{name="lower_hinge_1",flap="lower_1",end="end",kind="sliding_pinned"},{name="lower_hinge_2",flap="lower_2",end="end",kind="sliding_pinned"}]'
# Exchange: static by default (the beam solved to equilibrium in every coupling iteration,
# iterated to convergence); EXCHANGE=dynamic is the seed's variant (0.01 s of beam dynamics per
# exchange, seven exchanges): see Makefile.cases and cases/simple-nozzle/README.md.
# Flow conditions of every configuration: the seed's NPR 5.423 and a stagnation temperature that
# the Ti-6Al-4V strength tables cover (yield and ultimate strength to 810.9 K).
SET += --set flow.nozzle_pressure_ratio=5.423 --set flow.stagnation_temperature=750
# Flap sections: a 10 mm equivalent plate for a stiffened flap, as config1.
SET += $(foreach f,upper_1 upper_2 upper_3 lower_1 lower_2 lower_3,--set flap.$(f).thickness=0.01)
# Flow: second-order Spalart-Allmaras RANS (first-order start, then second order until the wall
# pressure is stationary to 1e-6), as cases/nasa-2dcd; the wall layers reach y+ about 1
# (flow.yplus_target in case.toml). Its heat transfer coefficient and adiabatic wall temperature
# load tfmb-heat (thermal.solid_boundary = convection_radiation in case.toml).
FLOW_MODEL = sa
FLOW_OPTS = --threads 2 --order 2 --first-order-start --stationary-tolerance 1e-6
