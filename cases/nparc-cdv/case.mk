# nparc-cdv: inviscid verification (README.md). Pictures: the wall p/p0 against the exact
# quasi-1D solution (isentropic plus at most one normal shock, Anderson 2003 ch. 5) for the run's
# own exit pressure ratio, with the area law taken from the wall's height above the symmetry
# axis; x in inches, the coordinate of the NPARC definition (refdata/flow/nparc_cdv_nozzle_definition.csv).
ANALYSIS = flow
PLOT_REFERENCE = --exact quasi1d --x-length 0.0254 --x-label 'x [in] (NPARC CDV definition)'
