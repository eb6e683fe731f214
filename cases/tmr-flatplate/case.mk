# tmr-flatplate: Spalart-Allmaras verification (README.md). Second order (a first-order start,
# then tfmb-flow's default --matrix-free auto), 8 orders of the density residual.
# --turbulence-coupling auto and --cfl-max 1e7: nu_tilde in the Newton system with the mean flow
# once the residual has fallen 2 orders, and a CFL ceiling high enough for the wall layers. Their
# cells have aspect ratios up to 3e4, and the local time step is set by the short side, so at
# the default ceiling of 1e4 the streamwise CFL number is below 1 there and the run converged
# linearly (0.96-0.98 per iteration on the 273 x 193 level, not converged in 2000 iterations).
# The segregated SA step needs the V/dt term (a higher ceiling blew it up on nasa-2dcd), the
# coupled one does not. --limiter-rise-iterations 5: at that ceiling defect correction is a
# fixed-point iteration with no time term left, and on the plate its residual rose 5-8 % per
# iteration from a drop of 5e-6 (a mode at the leading edge it amplifies) until the stall rule
# froze the limiter 25 iterations later; a rise 5 iterations in a row freezes it there (273 x 193:
# 87 iterations instead of 105). Not tfmb-flow's default: at nasa-2dcd's ceiling of 1e4 a rise
# is a transient of the separation, and NPR 2.412 ran 9 minutes instead of 104 s. Measured:
# tools/tfmb-flow/README.md, "Benchmark". --ilu-fill 2: in the Newton phase GMRES with ILU(0)
# stopped at its 80 iterations leaving 0.4-0.9 of the residual, and the 545 x 385 level stalled at
# a drop of about 4e-6; with ILU(2) it converges 8 orders in 107 iterations, and 273 x 193 takes
# 83 instead of 87 in 0.88 of the time (1,711 linear iterations instead of 3,035; 535 MB
# instead of 467). --node-ordering lines: the wall-normal lines of the wall layers kept together
# in the ILU, which takes 545 x 385 under its 100-iteration target with the same Cf and CD
# (README.md). --turbulence-step-limit nu-tilde: a coupled step's nu_tilde limit holds nu_tilde
# alone, not the whole node (273 x 193: 71 iterations instead of 83; 545 x 385: 85 instead of 89;
# the same Cf and CD).
ANALYSIS = flow
FLOW_MODEL = sa
FLOW_OPTS = --threads 2 --turbulence-coupling auto --cfl-max 1e7 --limiter-rise-iterations 5 --ilu-fill 2 --node-ordering lines --turbulence-step-limit nu-tilde
# Pictures: Cf(x) against the TMR's finest-grid (545 x 385) SA results of FUN3D and CFL3D
# (refdata/flow/tmr_flatplate_sa_cf_vs_x_545x385.csv); x is in TMR grid units, L = 1 m.
PLOT_REFERENCE = \
  --reference '$(TFMB_ROOT)refdata/flow/tmr_flatplate_sa_cf_vs_x_545x385.csv:x:cf:where=code=FUN3D:label=FUN3D SA 545x385 (TMR):plot=skin-friction' \
  --reference '$(TFMB_ROOT)refdata/flow/tmr_flatplate_sa_cf_vs_x_545x385.csv:x:cf:where=code=CFL3D:label=CFL3D SA 545x385 (TMR):plot=skin-friction'
