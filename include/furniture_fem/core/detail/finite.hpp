#pragma once
// Internal: whether every value of a long vector is finite, checked at every step of a simulation.
// Users include furniture_fem/core/simulation.hpp, not this file.
#ifndef FURNITURE_FEM_CORE_INTERNAL
#error "furniture_fem/core/detail/finite.hpp is internal: include <furniture_fem/core/simulation.hpp>"
#endif
#include <Eigen/Core>
#include <cstring>
#include <vector>

namespace furniture_fem::detail {

// x - x is 0 for a finite x and NaN for an infinity or a NaN, and a NaN stays in a sum: the vector is
// finite when the sums of x - x are 0. Independent sums and no early exit keep the loop free of
// branches and of one long chain of additions; Eigen's allFinite() (the same test, value by value
// with an exit) took 2 % of a rigid scene's run for the two vectors of its step (docs/performance.md
// section 7). With GCC's and clang's vector types (SSE2 on x86-64) two values go in one instruction.
#if defined(__GNUC__) || defined(__clang__)
#define FFEM_FINITE_PAIRS 1
typedef double FinitePair __attribute__((vector_size(16)));
inline FinitePair finite_pair_at(const double* p) {
  FinitePair a;
  std::memcpy(&a, p, sizeof a);  // unaligned load
  return a - a;
}
#endif
inline bool all_finite(const double* p, Eigen::Index n) {
  Eigen::Index i = 0;
  double s = 0;
#ifdef FFEM_FINITE_PAIRS
  FinitePair s01 = {0, 0}, s23 = {0, 0};
  for (; i + 4 <= n; i += 4) {
    s01 += finite_pair_at(p + i);
    s23 += finite_pair_at(p + i + 2);
  }
  s = (s01[0] + s01[1]) + (s23[0] + s23[1]);
#endif
  for (; i < n; ++i) s += p[i] - p[i];
  return s == 0;
}
inline bool all_finite(const Eigen::VectorXd& v) { return all_finite(v.data(), v.size()); }

// The same test on the six values of each listed node (a body's increment): Eigen's allFinite() on
// every node's six took 2 % of a rigid study run, not inlined (docs/performance.md section 8).
inline bool nodes_finite(const Eigen::VectorXd& v, const std::vector<int>& nodes) {
#ifdef FFEM_FINITE_PAIRS
  FinitePair s0 = {0, 0}, s1 = {0, 0}, s2 = {0, 0};
  for (int n : nodes) {
    const double* p = v.data() + 6 * static_cast<Eigen::Index>(n);
    s0 += finite_pair_at(p);
    s1 += finite_pair_at(p + 2);
    s2 += finite_pair_at(p + 4);
  }
  const FinitePair s = s0 + s1 + s2;
  return s[0] + s[1] == 0;
#else
  double s0 = 0, s1 = 0, s2 = 0;
  for (int n : nodes) {
    const double* p = v.data() + 6 * static_cast<Eigen::Index>(n);
    s0 += (p[0] - p[0]) + (p[3] - p[3]);
    s1 += (p[1] - p[1]) + (p[4] - p[4]);
    s2 += (p[2] - p[2]) + (p[5] - p[5]);
  }
  return s0 + s1 + s2 == 0;
#endif
}

}  // namespace furniture_fem::detail
