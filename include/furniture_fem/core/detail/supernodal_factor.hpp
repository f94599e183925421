#pragma once
// Internal: the factor L of a sparse LDL^T repacked into supernodes for fast substitutions.
//
// Between refreshes a body's factorisation is reused for about a hundred right-hand sides, so the
// substitutions (L y = b, L^T x = z: every entry of L read twice per step) cost more than the
// factorisation. Eigen's simplicial factor stores each entry with its own row index (12 bytes per
// entry) and substitutes one scalar at a time through that index. A beam node's six DOFs share their
// pattern, and AMD orders them together, so runs of consecutive columns of L have the same rows below
// them (supernodes). Here each supernode is one dense block: its unit lower triangle and the panel of
// its rows below, with one row index per panel row. That is about 8 bytes per entry (a third less
// memory traffic), and the substitutions become small dense triangular solves and matrix-vector
// products that vectorise. The factorisation itself stays Eigen's; only its storage is repacked.
// Layout of a supernode of w columns and `below` rows under it, contiguous: the strictly lower part
// of its triangle column by column (w (w - 1) / 2 entries), then its panel (below x w, column-major).
// Every stored value is an entry of L, and the substitutions stream the factor once each.
#ifndef FURNITURE_FEM_CORE_INTERNAL
#error "furniture_fem/core/detail/supernodal_factor.hpp is internal: include <furniture_fem/core/solvers.hpp>"
#endif
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <algorithm>
#include <vector>

namespace furniture_fem::detail {

class SupernodalFactor {
 public:
  using Sparse = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

  // Repacks the strictly lower part of a unit lower triangular L (column-major, rows sorted in each
  // column, as Eigen's SimplicialLDLT stores it; entries on or above the diagonal are ignored).
  // O(nnz), no allocation when the pattern is the one of the last call.
  void assign(const Sparse& L) {
    if (!L.isCompressed()) {
      Sparse c = L;
      c.makeCompressed();
      assign(c);
      return;
    }
    const int n = static_cast<int>(L.cols());
    const int* outer = L.outerIndexPtr();
    const int* inner = L.innerIndexPtr();
    const double* value = L.valuePtr();
    first_.resize(n);  // each column's first entry below the diagonal
    for (int j = 0; j < n; ++j) {
      int p = outer[j];
      while (p < outer[j + 1] && inner[p] <= j) ++p;
      first_[j] = p;
    }
    auto count = [&](int j) { return outer[j + 1] - first_[j]; };
    // Column j + 1 joins column j's supernode when column j's rows are j + 1 followed by column
    // j + 1's rows exactly.
    start_.clear();
    for (int j = 0; j < n;) {
      int w = 1;
      while (j + w < n) {
        const int a = j + w - 1, b = j + w;
        if (count(a) == 0 || inner[first_[a]] != b || count(a) != count(b) + 1 ||
            !std::equal(inner + first_[a] + 1, inner + outer[a + 1], inner + first_[b]))
          break;
        ++w;
      }
      start_.push_back(j);
      j += w;
    }
    start_.push_back(n);
    const int ns = static_cast<int>(start_.size()) - 1;
    offset_.assign(ns + 1, 0);
    row_offset_.assign(ns + 1, 0);
    int most_below = 0;
    for (int s = 0; s < ns; ++s) {
      const int c0 = start_[s], w = start_[s + 1] - c0;
      const int below = count(c0) - (w - 1);  // rows after the supernode
      offset_[s + 1] = offset_[s] + w * (w - 1) / 2 + below * w;
      row_offset_[s + 1] = row_offset_[s] + below;
      most_below = std::max(most_below, below);
    }
    values_.resize(offset_[ns]);
    row_index_.resize(row_offset_[ns]);
    scratch_.resize(most_below);  // the substitutions allocate nothing
    for (int s = 0; s < ns; ++s) {
      const int c0 = start_[s], w = start_[s + 1] - c0;
      const int below = row_offset_[s + 1] - row_offset_[s];
      std::copy(inner + first_[c0] + (w - 1), inner + outer[c0 + 1], row_index_.data() + row_offset_[s]);
      double* tri = values_.data() + offset_[s];
      double* panel = tri + w * (w - 1) / 2;
      for (int t = 0; t < w; ++t) {
        const double* v = value + first_[c0 + t];
        const int in_tri = w - 1 - t;  // rows c0 + t + 1 .. c0 + w - 1 come first
        tri = std::copy(v, v + in_tri, tri);
        std::copy(v + in_tri, v + in_tri + below, panel + t * below);
      }
    }
  }

  // x <- L^{-1} x. The triangles are small (about six columns): plain loops; the panels are
  // matrix-vector products (Eigen's, vectorised) with one gather or scatter of x per supernode.
  void solve_lower(Eigen::VectorXd& x) const {
    double* xv = x.data();
    for (int s = 0; s + 1 < static_cast<int>(start_.size()); ++s) {
      const int c0 = start_[s], w = start_[s + 1] - c0;
      const int below = row_offset_[s + 1] - row_offset_[s];
      const double* tri = values_.data() + offset_[s];
      double* xs = xv + c0;
      for (int t = 0; t < w; ++t)
        for (int i = t + 1; i < w; ++i) xs[i] -= *tri++ * xs[t];
      if (below == 0) continue;
      const Eigen::Map<const Eigen::MatrixXd> panel(tri, below, w);
      auto tmp = scratch_.head(below);
      tmp.noalias() = panel * Eigen::Map<const Eigen::VectorXd>(xs, w);
      const int* ri = row_index_.data() + row_offset_[s];
      for (int r = 0; r < below; ++r) xv[ri[r]] -= tmp[r];
    }
  }

  // x <- L^{-T} x
  void solve_upper(Eigen::VectorXd& x) const {
    double* xv = x.data();
    for (int s = static_cast<int>(start_.size()) - 2; s >= 0; --s) {
      const int c0 = start_[s], w = start_[s + 1] - c0;
      const int below = row_offset_[s + 1] - row_offset_[s];
      const double* tri = values_.data() + offset_[s];
      double* xs = xv + c0;
      if (below > 0) {
        const Eigen::Map<const Eigen::MatrixXd> panel(tri + w * (w - 1) / 2, below, w);
        auto tmp = scratch_.head(below);
        const int* ri = row_index_.data() + row_offset_[s];
        for (int r = 0; r < below; ++r) tmp[r] = xv[ri[r]];
        Eigen::Map<Eigen::VectorXd>(xs, w).noalias() -= panel.transpose() * tmp;
      }
      // Column t's triangle entries start at t (w - 1) - t (t - 1) / 2.
      for (int t = w - 1; t >= 0; --t) {
        const double* col = tri + t * (w - 1) - t * (t - 1) / 2;
        for (int i = t + 1; i < w; ++i) xs[t] -= col[i - t - 1] * xs[i];
      }
    }
  }

  int supernodes() const { return static_cast<int>(start_.size()) - 1; }
  std::size_t stored_values() const { return values_.size(); }

 private:
  std::vector<int> first_;       // scratch of assign()
  std::vector<int> start_;       // first column of each supernode (and n at the end)
  std::vector<int> offset_;      // start of each supernode's values
  std::vector<int> row_offset_;  // start of each supernode's panel row indices
  std::vector<double> values_;
  std::vector<int> row_index_;
  mutable Eigen::VectorXd scratch_;
};

}  // namespace furniture_fem::detail
