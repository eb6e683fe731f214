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
# Pictures: the inner walls' p/p0 against TP-1704's upper-flap orifices (refdata/flow/
# mason_tp1704_B1_upper_flap_p_npr8p91.csv, a third-party transcription, trust moderate-low) in
# the experiment's own coordinate x/l_e (throat at x = 0, l_e = 57.52 mm, README.md), the
# centreline readings with the band to the 45 % half-span row; drawn only for a run at the
# data's NPR 8.91 (the npr-sweep's other NPRs have no measurements here).
PLOT_REFERENCE = --walls '*_inner' --x-origin 0 --x-length 0.05752 --x-label 'x / l_e (throat at 0, l_e = 57.52 mm)' \
  --reference '$(TFMB_ROOT)refdata/flow/mason_tp1704_B1_upper_flap_p_npr8p91.csv:x_over_le:p_over_ptj_centreline:band=p_over_ptj_y_over_halfwidth_0p45:band-label=band to the 45 % half-span row:npr=8.91:label=TP-1704 B1 NPR 8.91, centreline'
