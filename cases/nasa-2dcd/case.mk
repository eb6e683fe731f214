# nasa-2dcd: flow validation against NASA TP-1704 (README.md). Spalart-Allmaras at second order
# (a first-order start, then tfmb-flow's default --matrix-free auto: defect correction while the
# limiter is live, Newton-Krylov once it is frozen), converged when the wall pressures and the
# wall force are stationary to 1e-6 (relative to p0) per iteration, or the density residual fell
# 8 orders. It converges at every NPR of npr-sweep on the case mesh (README.md, "Results").
# First order: FLOW_OPTS="--threads 2 --order 1 --stationary-tolerance 1e-6 --heat-transfer-dt 0".
# No heat-transfer probe: the validation compares wall pressures only.
ANALYSIS = flow
FLOW_MODEL = sa
FLOW_OPTS = --threads 2 --order 2 --first-order-start --stationary-tolerance 1e-6 --heat-transfer-dt 0
