# The seed's validation load: 0.01 N downwards at the revolute joint (the end of beam_a), held
# for the analysis time (1 s, case.toml [analysis]). The load is small because the outer clamps
# hold the span axially: at 0.1 N membrane stiffening already cuts the deflection to 0.88 of the
# small-deflection answer that the seed's check compares with.
BEAM_OPTS = --point-load beam_a:end:0,-0.01
