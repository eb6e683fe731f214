// Modal analysis: small vibrations about a (static) state, K phi = omega^2 M phi with the
// constraints eliminated through a null-space basis of their Jacobian (dense; for models up to a
// few thousand unknowns).
#pragma once

#include <Eigen/Core>

#include "tfmb-beam/assembly.hpp"

namespace tfmb::beam {

struct ModalResult {
  Eigen::VectorXd frequencies_hz;  // ascending [Hz]
  Eigen::MatrixXd mode_shapes;     // columns over the 6 n nodal unknowns (+ joint unknowns)
};

/// First `n_modes` modes about `state` (load factor `load_factor` for the geometric stiffness).
ModalResult modal_analysis(const Assembly& assembly, const State& state, int n_modes, double load_factor = 0.0);

}  // namespace tfmb::beam
