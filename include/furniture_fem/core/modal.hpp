#pragma once
// furniture_fem/core/modal.hpp: natural frequencies and mode shapes of one body at its current state,
// from the tangent stiffness and the lumped mass (dense generalized eigenproblem: for the small
// models of verification and tutorials, a few thousand DOFs at most).
#include <vector>

#include "dense_kernels.hpp"
#include "simulation.hpp"

namespace furniture_fem {

struct ModalResult {
  std::vector<double> omega;   // rad/s, ascending, rigid-body modes (omega below rigid_tol) removed
  Eigen::MatrixXd shapes;      // columns: mode shapes over the free DOFs of the body (mass-normalised)
  std::vector<int> free_dofs;  // body-local DOF index of each row of shapes
  int rigid_modes = 0;
};

template <class Sim>
ModalResult modal_analysis(Sim& sim, int body, int modes, double rigid_tol = 1e-3) {
  const Eigen::MatrixXd K = sim.stiffness_matrix(body);
  const Eigen::VectorXd m = sim.mass_diagonal(body);
  const auto& nodes = sim.body_nodes(body);
  ModalResult res;
  for (int i = 0; i < K.rows(); ++i)
    if (!sim.dof_fixed(nodes[i / 6], i % 6)) res.free_dofs.push_back(i);
  const int n = static_cast<int>(res.free_dofs.size());
  Eigen::MatrixXd Kf(n, n);
  Eigen::VectorXd mf(n);
  for (int a = 0; a < n; ++a) {
    mf[a] = m[res.free_dofs[a]];
    for (int b = 0; b < n; ++b) Kf(a, b) = K(res.free_dofs[a], res.free_dofs[b]);
  }
  // Symmetric form: M^-1/2 K M^-1/2 (lumped M is diagonal and positive).
  const Eigen::VectorXd s = mf.cwiseSqrt().cwiseInverse();
  const Eigen::MatrixXd A = s.asDiagonal() * (0.5 * (Kf + Kf.transpose())) * s.asDiagonal();
  const detail::SymmetricEigen es = detail::symmetric_eigen(A);
  const double scale = std::max(1.0, std::sqrt(std::abs(es.values.maxCoeff())));
  std::vector<int> kept;
  for (int i = 0; i < n; ++i) {
    const double w = std::sqrt(std::max(0.0, es.values[i]));
    if (w < rigid_tol * scale * 1e-3 || w < rigid_tol) {
      ++res.rigid_modes;
      continue;
    }
    if (static_cast<int>(kept.size()) < modes) {
      kept.push_back(i);
      res.omega.push_back(w);
    }
  }
  res.shapes.resize(n, kept.size());
  for (size_t k = 0; k < kept.size(); ++k) res.shapes.col(k) = s.asDiagonal() * es.vectors.col(kept[k]);
  return res;
}

}  // namespace furniture_fem
