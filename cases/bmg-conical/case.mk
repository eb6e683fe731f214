# bmg-conical: axisymmetric validation against Back, Massier and Gier (README.md). Spalart-
# Allmaras at second order (a first-order start, then tfmb-flow's default --matrix-free auto),
# as the flow test's second-order run (tests/flow/test_bmg_nozzle.cpp,
# ViscousSecondOrderConverges); converged when the wall pressures are stationary to 1e-6 of p0 per
# iteration or the density residual fell 8 orders. No heat-transfer probe: the comparison is of
# wall pressures only.
ANALYSIS = flow
FLOW_MODEL = sa
FLOW_OPTS = --threads 2 --order 2 --first-order-start --stationary-tolerance 1e-6 --heat-transfer-dt 0
# SMOKE's mesh.scale=4 alone would give 35 x 20 cells, on which the second-order run stalls at a
# density residual drop of 2.8e-5 (measured); these counts divided by 4 give 70 x 40 cells, the
# flow test's coarse 71 x 41 nodes, converged in about 60 iterations (the first layer is then
# 2e-6 m, y+ about 5 by tfmb-mesh's estimate).
ifeq ($(SMOKE),1)
  SET += --set mesh.cells_along=280 --set mesh.cells_across=160
endif
# Pictures: the wall p/pt against the experiment in inches from the throat, the data's own axis.
PLOT_REFERENCE = --reference '$(TFMB_ROOT)refdata/flow/bmg_conical_nozzle_wall_p_gdtk.csv:x_in_from_throat:p_over_pt:label=Back, Massier and Gier (1965), read off a figure' \
  --x-origin 0 --x-length 0.0254 --x-label 'x [in] (throat at 0)'
