#include "tfmb-beam/modal.hpp"

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>

#include "tfmb-beam/errors.hpp"
#include "tfmb-beam/inertia.hpp"

namespace tfmb::beam {

ModalResult modal_analysis(const Assembly& assembly, const State& state, int n_modes, double load_factor) {
  const int nn = assembly.num_nodes();
  const int nq = 6 * nn + assembly.num_joint_dofs();
  const int nm = assembly.num_multipliers();
  if (nq > 6000) throw ModelError("modal analysis: model too large for the dense eigen solver (" + std::to_string(nq) + " unknowns)");
  Eigen::VectorXd r;
  Triplets trip;
  assembly.assemble(state, load_factor, r, &trip);
  Eigen::SparseMatrix<double> ks(assembly.size(), assembly.size());
  ks.setFromTriplets(trip.begin(), trip.end());
  const Eigen::MatrixXd kfull(ks);
  Eigen::MatrixXd k = kfull.topLeftCorner(nq, nq);
  k = 0.5 * (k + k.transpose());  // symmetric at equilibrium (FORMULATION.md sec. 2)
  const Eigen::MatrixXd b = kfull.block(nq, 0, nm, nq);

  const MassModel mm = build_mass(assembly.model());
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(nq, nq);
  for (int o = 0; o < mm.mass_scalar.outerSize(); ++o)
    for (Eigen::SparseMatrix<double>::InnerIterator it(mm.mass_scalar, o); it; ++it)
      for (int c = 0; c < 3; ++c) m(6 * it.row() + c, 6 * it.col() + c) += it.value();
  for (int i = 0; i < nn; ++i) {
    const Eigen::Matrix3d fr = assembly.frame(state, i);
    m.block<3, 3>(6 * i + 3, 6 * i + 3) += fr * mm.nodal_inertia[i] * fr.transpose();
  }
  // Null-space basis Z of B: the admissible motions.
  Eigen::MatrixXd z;
  if (nm > 0) {
    Eigen::FullPivLU<Eigen::MatrixXd> lu(b);
    z = lu.kernel();
  } else {
    z = Eigen::MatrixXd::Identity(nq, nq);
  }
  const Eigen::MatrixXd kr = z.transpose() * k * z;
  Eigen::MatrixXd mr = z.transpose() * m * z;
  // Massless unknowns (joint angles) would make M singular; they are slaved to the nodes by the
  // constraints, so Z^T M Z is regular unless a node carries no mass at all.
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(kr, mr);
  if (es.info() != Eigen::Success)
    throw ModelError("modal analysis: the mass matrix is singular on the admissible motions; give every node mass or rotary inertia");
  ModalResult res;
  const int n = std::min<int>(n_modes, static_cast<int>(es.eigenvalues().size()));
  res.frequencies_hz.resize(n);
  res.mode_shapes.resize(nq, n);
  for (int i = 0; i < n; ++i) {
    res.frequencies_hz(i) = std::sqrt(std::max(es.eigenvalues()(i), 0.0)) / (2.0 * M_PI);
    res.mode_shapes.col(i) = z * es.eigenvectors().col(i);
  }
  return res;
}

}  // namespace tfmb::beam
