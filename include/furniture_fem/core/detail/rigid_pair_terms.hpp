#pragma once
// The contact pairs' terms in a rigid group's joint 6 x 6-per-body system, summed per pair of bodies.
//
// A pair with effective stiffness k (3 x 3) at a point p between bodies a and b moves with the bodies
// through T_a = [I, -S_a], S_a = [p - c_a]x (and T_b likewise), and adds T_a^T k T_a and T_b^T k T_b
// to the diagonal blocks, -T_a^T k T_b and -T_b^T k T_a off it. With S_b = S_a + D, D = [c_a - c_b]x,
// every block follows from four sums over the body pair's contact pairs: K = sum k, KS = sum k S_a,
// SK = sum S_a k, SKS = sum S_a k S_a. So each contact pair costs three 3 x 3 products and the 144
// additions into the group's matrix are made once per body pair, not once per contact pair (stacked
// cabinets have hundreds of element pairs per step, a handful of body pairs).
#ifndef FURNITURE_FEM_CORE_INTERNAL
#error "furniture_fem/core/detail/rigid_pair_terms.hpp is internal: include <furniture_fem/core/simulation.hpp>"
#endif
#include "rotation.hpp"

#include <Eigen/Core>
#include <vector>

namespace furniture_fem::detail {

class RigidPairTerms {
 public:
  explicit RigidPairTerms(int bodies) : n_(bodies), sums_(static_cast<size_t>(bodies) * bodies) {}

  // A contact pair between the group's bodies ia and ib (their indices in the group), its effective
  // stiffness k and its point's arm from body a's centre, p - c_a.
  void add(int ia, int ib, const Eigen::Matrix3d& k, const Eigen::Vector3d& arm_a) {
    Sums& s = sums_[static_cast<size_t>(ia) * n_ + ib];
    const Eigen::Matrix3d S = skew(arm_a);
    const Eigen::Matrix3d kS = k * S, Sk = S * k;
    s.K += k;
    s.KS += kS;
    s.SK += Sk;
    s.SKS += Sk * S;
    s.used = true;
  }

  // The sums' blocks added to the group's matrix A (6 per body, in the group's order), given the
  // bodies' centres the arms were taken from.
  void add_to(const std::vector<Eigen::Vector3d>& centre, Eigen::MatrixXd& A) const {
    for (int ia = 0; ia < n_; ++ia)
      for (int ib = 0; ib < n_; ++ib)
        if (const Sums& s = sums_[static_cast<size_t>(ia) * n_ + ib]; s.used) add_body_pair(ia, ib, s, centre, A);
  }

 private:
  struct Sums {
    Eigen::Matrix3d K = Eigen::Matrix3d::Zero(), KS = Eigen::Matrix3d::Zero(), SK = Eigen::Matrix3d::Zero(),
                    SKS = Eigen::Matrix3d::Zero();
    bool used = false;
  };

  static void add_body_pair(int ia, int ib, const Sums& s, const std::vector<Eigen::Vector3d>& centre,
                            Eigen::MatrixXd& A) {
    const Eigen::Matrix3d D = skew(centre[ia] - centre[ib]);
    const Eigen::Matrix3d KD = s.K * D, DK = D * s.K;
    const Eigen::Matrix3d KSb = s.KS + KD;  // sum k S_b
    const Eigen::Matrix3d SbK = s.SK + DK;  // sum S_b k
    const Eigen::Matrix3d SaKSb = s.SKS + s.SK * D, SbKSa = s.SKS + D * s.KS;
    const Eigen::Matrix3d SbKSb = SaKSb + D * s.KS + DK * D;
    const int a = 6 * ia, b = 6 * ib;
    const auto add = [&A](int r, int c, const Eigen::Matrix3d& kk, const Eigen::Matrix3d& kSc,
                          const Eigen::Matrix3d& Srk, const Eigen::Matrix3d& SrkSc, double sign) {
      A.block<3, 3>(r, c) += sign * kk;
      A.block<3, 3>(r, c + 3) -= sign * kSc;
      A.block<3, 3>(r + 3, c) += sign * Srk;
      A.block<3, 3>(r + 3, c + 3) -= sign * SrkSc;
    };
    add(a, a, s.K, s.KS, s.SK, s.SKS, 1.0);    // T_a^T k T_a
    add(b, b, s.K, KSb, SbK, SbKSb, 1.0);      // T_b^T k T_b
    add(a, b, s.K, KSb, s.SK, SaKSb, -1.0);    // -T_a^T k T_b
    add(b, a, s.K, s.KS, SbK, SbKSa, -1.0);    // -T_b^T k T_a
  }

  int n_;
  std::vector<Sums> sums_;
};

}  // namespace furniture_fem::detail
