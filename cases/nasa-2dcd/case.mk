# nasa-2dcd: flow validation against NASA TP-1704 (README.md). Spalart-Allmaras with first-order
# convection (second order, --order 2 --first-order-start --matrix-free true, converges at NPR
# 8.91; at the separated NPR 2.412 on SMOKE only so far: README.md), converged when the wall
# pressures and the wall force are stationary
# to 1e-6 (relative to p0) per iteration, or the density residual fell 8 orders. No heat-transfer
# probe: the validation compares wall pressures only.
ANALYSIS = flow
FLOW_MODEL = sa
FLOW_OPTS = --threads 2 --order 1 --stationary-tolerance 1e-6 --heat-transfer-dt 0
