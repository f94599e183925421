#pragma once
// Internal: whether every value of a long vector is finite, checked at every step of a simulation.
// Users include furniture_fem/core/simulation.hpp, not this file.
#ifndef FURNITURE_FEM_CORE_INTERNAL
#error "furniture_fem/core/detail/finite.hpp is internal: include <furniture_fem/core/simulation.hpp>"
#endif
#include <Eigen/Core>

namespace furniture_fem::detail {

// x - x is 0 for a finite x and NaN for an infinity or a NaN, and a NaN stays in a sum: the vector is
// finite when the sums of x - x are 0. Four independent sums and no early exit keep the loop free of
// branches and of one long chain of additions; Eigen's allFinite() (the same test, value by value
// with an exit) took 2 % of a rigid scene's run for the two vectors of its step (docs/performance.md
// section 7).
inline bool all_finite(const Eigen::VectorXd& v) {
  const double* p = v.data();
  const Eigen::Index n = v.size();
  double s0 = 0, s1 = 0, s2 = 0, s3 = 0;
  Eigen::Index i = 0;
  for (; i + 4 <= n; i += 4) {
    s0 += p[i] - p[i];
    s1 += p[i + 1] - p[i + 1];
    s2 += p[i + 2] - p[i + 2];
    s3 += p[i + 3] - p[i + 3];
  }
  for (; i < n; ++i) s0 += p[i] - p[i];
  return (s0 + s1) + (s2 + s3) == 0;
}

}  // namespace furniture_fem::detail
