#pragma once
// Internal: the per-body linear system and the corotational element kinematics.
// Users include furniture_fem/core/simulation.hpp, not this file.
#ifndef FURNITURE_FEM_CORE_INTERNAL
#error "furniture_fem/core/detail/body_system.hpp is internal: include <furniture_fem/core/simulation.hpp>"
#endif
#include <Eigen/SparseCore>
#include <algorithm>
#include <array>
#include <vector>

#include "../elements.hpp"
#include "../model.hpp"
#include "group_layout.hpp"
#include "matrix_free.hpp"
#include "rotation.hpp"

namespace furniture_fem::detail {

// Corotational kinematics of a two-node element. The element frame E follows the chord (e1) and the
// mean of the nodal triads (Crisfield's choice, symmetric in the two nodes); local deformations are
// the elongation and the rotations of the nodal triads relative to E. A rigid motion gives d = 0
// exactly, so rotating a frame as a rigid body produces no internal force.
struct CorotationalFrame {
  Mat3 E;       // columns e1, e2, e3 of the current element frame
  double l = 0; // current length
  Vec12 d;      // local deformation DOFs for the element policy
};

// Positions enter as initial coordinates plus displacements, and the elongation is formed as
// (2 dX.du + du.du) / (l + L0): both keep full precision in the deformation even though the
// coordinates are about 1 m and the strains about 1e-9 (a stiff axial member would otherwise leave a
// round-off floor of EA/L0 * 1e-16 m in its force).
inline CorotationalFrame corotate(const Vec3& X1, const Vec3& X2, const Vec3& u1, const Vec3& u2, const Mat3& R1,
                                  const Mat3& R2, const Mat3& E0, double L0) {
  CorotationalFrame c;
  const Vec3 dX = X2 - X1, du = u2 - u1;
  const Vec3 dx = dX + du;
  c.l = dx.norm();
  const Vec3 e1 = dx / c.l;
  const Vec3 q = 0.5 * (R1 * E0.col(1) + R2 * E0.col(1));
  Vec3 e3 = e1.cross(q);
  e3.normalize();
  const Vec3 e2 = e3.cross(e1);
  c.E.col(0) = e1;
  c.E.col(1) = e2;
  c.E.col(2) = e3;
  c.d.setZero();
  c.d.segment<3>(3) = rotation_log(c.E.transpose() * R1 * E0);
  c.d[6] = (2.0 * dX.dot(du) + du.squaredNorm()) / (c.l + L0);
  c.d.segment<3>(9) = rotation_log(c.E.transpose() * R2 * E0);
  return c;
}

// Initial element frame from the chord and the member's y reference vector.
inline Mat3 initial_frame(const Vec3& X1, const Vec3& X2, const Vec3& y_ref) {
  Mat3 E;
  const Vec3 e1 = (X2 - X1).normalized();
  const Vec3 e3 = e1.cross(y_ref).normalized();
  E.col(0) = e1;
  E.col(1) = e3.cross(e1);
  E.col(2) = e3;
  return E;
}

// A change of a node's contact term since its body's factorisation, put on a solve by the Woodbury
// identity (Simulation::FlexibleBody): the change d of the node's term (in the factor's frame), on its
// translations only (dim 3) or with its rotations (dim 6).
struct ContactChange {
  int local;
  Mat6 d;
  int dim;
};

// The Woodbury system of a set of changes: each change's first row in it, its size m, and the LU of
// I + D S (D the changes' terms, block-diagonal; S the factor's columns of the changed nodes at their
// rows).
struct Woodbury {
  std::vector<int> at;
  int m = 0;
  DenseLu lu;
};

// One body's sparse effective matrix with a fixed pattern and, per element, the positions of its
// 144 entries in the value array: assembly writes straight into the matrix without searching or
// allocating.
struct BodySystem {
  std::vector<int> nodes;            // global node ids, in local order
  std::vector<int> elements;         // global element ids
  std::vector<int> local_of_node;    // only valid for this body's nodes (indexed by global id via map)
  SparseMatrix K;
  std::vector<std::array<int, 144>> element_slots;
  std::vector<int> diag_slot;        // value index of each diagonal entry
  std::vector<std::array<int, 36>> node_slots;  // value indices of each node's 6 x 6 diagonal block (row-major)
  std::vector<char> fixed;           // per local DOF
  Eigen::VectorXd r, dx, work;       // residual, solution, scratch
  Vec3 Xc = Vec3::Zero();            // initial centroid
  Mat3 Q_factor = Mat3::Identity();  // body rotation when the matrix was factorised
  long steps_since_refresh = 1 << 30;
  bool needs_refresh = true;
  bool assembled = false;            // K holds the tangent at the current configuration
  bool rigid = false;                // solved as a rigid body (6 DOF)
  Vec3 rigid_c0 = Vec3::Zero(), rigid_dc = Vec3::Zero();  // centre at the step's start, its increment
  Mat3 rigid_Q = Mat3::Identity();   // rotation since the step's start
  bool rigid_at_start = false;       // its nodes not moved since the step's start (centre rigid_c0)
  // Contact inside the implicit step: the effective-matrix terms of the body's contacts (local node,
  // 3 x 3 on the contact point's translation; a point off the node, at a member's surface, carries its
  // offset and acts on the node's six DOF); the terms put into the factorisation (per local node, 6 x 6,
  // in the factor's frame; the nodes that have one); and the columns K^-1 e of the factorised matrix for
  // the nodes whose term has changed since, kept until the next factorisation (contact_column_dim[local]
  // columns, its translations and then its rotations, start at contact_column[local]).
  struct ContactTerm {
    static constexpr bool checkpoint_as_bytes = true;  // core/checkpoint.hpp
    int local;
    int status = 0;  // NodalContactTangent::status
    Mat3 K;
    Vec3 arm0 = Vec3::Zero();  // a contact off the node: the point's offset (NodalContactTangent)
    bool at_node() const { return arm0.x() == 0 && arm0.y() == 0 && arm0.z() == 0; }
  };
  std::vector<ContactTerm> contact;
  std::vector<Mat6> contact_factored;
  std::vector<int> status_factored;  // per local node: its contact status as factorised
  // The largest relative change of a node's contact term that a reused factorisation left out of a
  // solve (below FlexibleBody::contact_change_tolerance, in the same regime) since the start.
  double max_reuse_error = 0;
  // The element frames (local element order) when the matrix was factorised, and the factorisations
  // due because a member's frame turned away from the body's rotation by more than
  // SimulationOptions::frame_drift_refresh since (largest drift a reused factorisation solved with: max_frame_drift).
  std::vector<Mat3> frames_factor;
  double max_frame_drift = 0;
  long drift_refreshes = 0;
  // Conjugate-gradient solves of contact changes refined on a reused factorisation, and the steps whose
  // refinement did not converge (their changes then went on the Woodbury update or a refactorisation).
  long refinement_solves = 0, refinement_fallbacks = 0;
  std::vector<int> factored_nodes;
  std::vector<char> contact_seen;  // scratch, per local node
  std::vector<Mat6> contact_now;   // scratch, per local node
  std::vector<int> status_now;     // scratch, per local node
  Eigen::MatrixXd contact_columns;
  std::vector<int> contact_column;      // per local node; -1: not computed
  std::vector<int> contact_column_dim;  // per local node: 3 (translations) or 6 columns computed
  int contact_columns_used = 0;
  // The last solve's Woodbury changes and the body's turn since its factorisation (the factor's frame
  // to the current one): a group's pair terms go on that solve with the same operator
  // (Simulation::solve_flexible_group). Scratch of the step, not saved.
  std::vector<ContactChange> solve_changes;
  Woodbury solve_woodbury;  // of solve_changes (kept for the group's products with the same operator)
  Mat3 solve_turn = Mat3::Identity();
  GroupFactor group_factor;  // of the group this body leads (detail/group_layout.hpp)
  int ndof() const { return static_cast<int>(nodes.size()) * 6; }
};

inline void build_pattern(BodySystem& bs, const Model& model, const std::vector<int>& local_index) {
  const int n = bs.ndof();
  std::vector<Eigen::Triplet<double, int>> trip;
  trip.reserve(bs.elements.size() * 144 + n);
  for (int i = 0; i < n; ++i) trip.emplace_back(i, i, 0.0);
  for (int e : bs.elements) {
    const auto& el = model.elements()[e];
    const int base[2] = {local_index[el.n1] * 6, local_index[el.n2] * 6};
    for (int a = 0; a < 2; ++a)
      for (int b = 0; b < 2; ++b)
        for (int i = 0; i < 6; ++i)
          for (int j = 0; j < 6; ++j) trip.emplace_back(base[a] + i, base[b] + j, 0.0);
  }
  bs.K.resize(n, n);
  bs.K.setFromTriplets(trip.begin(), trip.end());
  bs.K.makeCompressed();
  auto slot = [&](int row, int col) {
    const int* inner = bs.K.innerIndexPtr();
    const int start = bs.K.outerIndexPtr()[col], end = bs.K.outerIndexPtr()[col + 1];
    const int* p = std::lower_bound(inner + start, inner + end, row);
    return static_cast<int>(p - inner);
  };
  bs.diag_slot.resize(n);
  for (int i = 0; i < n; ++i) bs.diag_slot[i] = slot(i, i);
  bs.node_slots.resize(bs.nodes.size());
  for (size_t k = 0; k < bs.nodes.size(); ++k)
    for (int i = 0; i < 36; ++i) bs.node_slots[k][i] = slot(6 * int(k) + i / 6, 6 * int(k) + i % 6);
  bs.element_slots.resize(bs.elements.size());
  for (size_t k = 0; k < bs.elements.size(); ++k) {
    const auto& el = model.elements()[bs.elements[k]];
    const int base[2] = {local_index[el.n1] * 6, local_index[el.n2] * 6};
    for (int i = 0; i < 12; ++i)
      for (int j = 0; j < 12; ++j)
        bs.element_slots[k][i * 12 + j] = slot(base[i / 6] + i % 6, base[j / 6] + j % 6);
  }
  bs.r.setZero(n);
  bs.dx.setZero(n);
  bs.work.setZero(n);
}

}  // namespace furniture_fem::detail
