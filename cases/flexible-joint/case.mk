# flexible-joint: the planar file stage (tfmb-input -> model.h5 -> tfmb-beam) with the in-plane
# part of the seed's example-1 tip load at a = 9 (F1 = 500 N along the beams, F2 = 25 N across;
# the out-of-plane F3 = 200 N has no place in a planar model), and the seed's two examples in 3D
# through the beam library (tfmb-beam-flexible-joint-seed), whose CSV files and plots are kept in
# cases/flexible-joint/results/ (README.md quotes their numbers).
ANALYSIS = structure
BEAM_OPTS = --point-load beam_2:end:500,25
SEED_EXAMPLES ?= $(BIN)/tfmb-beam-flexible-joint-seed
# An installed tree's cases are read-only material: there the results go to the run folder.
SEED_RESULTS ?= $(if $(TFMB_INSTALLED),$(RUN)/seed-examples,$(CASE_DIR)/results)

structure: seed-examples
seed-examples:
	@mkdir -p $(RUN)/logs $(SEED_RESULTS)
	$(SEED_EXAMPLES) -o $(SEED_RESULTS) 2> >(tee $(RUN)/logs/seed-examples.log >&2)
	/usr/bin/python3 $(CASE_DIR)/plot_seed_examples.py $(SEED_RESULTS)
.PHONY: seed-examples
