#pragma once
// Internal: the wireframe from which every furniture item is built.
// Users include furniture_fem/furniture/furniture.hpp, not this file.
//
// A builder describes an item as straight lines in the item's local frame (panel grids, frame edges,
// legs, casters). Lines meet at crossings and T-junctions; realize() splits every line at each point
// where another line crosses it or ends on it, so that lines sharing a point share a node, and turns
// each piece into one Model member (an even number of elements for ASI-Gauss pairs). Pieces that
// coincide (a panel edge that is also the next panel's edge) become one member, named after the line
// added first.
#ifndef FURNITURE_FEM_FURNITURE_INTERNAL
#error "furniture_fem/furniture/detail/furniture_wireframe.hpp is internal: include <furniture_fem/furniture/furniture.hpp>"
#endif
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "../../core/model.hpp"

namespace furniture_fem::detail {

// Geometric tolerance of the wireframe (m): points closer than this are the same point.
inline constexpr double wire_tolerance = 1e-6;

struct WireLine {
  std::string name;       // unique within the item; its pieces are named "<name>:<k>"
  Vec3 a, b;              // end points in the item's local frame (m)
  int section = 0;        // index into the Model's sections
  Vec3 y_ref_local = Vec3::Zero();  // section orientation in the local frame; zero: automatic
  double density_factor = 1;        // initial line mass = factor x rho A (a prior for the calibration)
};

// The result of realize(): which Model entities the wireframe became.
struct RealizedWireframe {
  std::vector<int> members;                    // Model member indices, in creation order
  std::map<std::string, int> line_end_a_node;  // line name -> node at its end a
  std::map<std::string, int> line_end_b_node;  // line name -> node at its end b
};

// Evenly spaced coordinates from lo to hi (both included) at about `spacing`; the number of intervals
// is a positive multiple of `multiple` (2 puts a node on the middle, and lets every(v, 2) stay symmetric).
inline std::vector<double> lattice(double lo, double hi, double spacing, int multiple = 1) {
  const int n = multiple * std::max(1, static_cast<int>(std::lround((hi - lo) / (spacing * multiple))));
  std::vector<double> v(n + 1);
  for (int i = 0; i <= n; ++i) v[i] = lo + (hi - lo) * double(i) / n;
  v.back() = hi;  // exact end, so that edges of different panels coincide bit for bit
  return v;
}

// Every k-th entry of a lattice, always keeping the last one (so the panel reaches its far edge).
inline std::vector<double> every(const std::vector<double>& v, int k) {
  std::vector<double> out;
  for (size_t i = 0; i < v.size(); i += static_cast<size_t>(std::max(1, k))) out.push_back(v[i]);
  if (out.back() != v.back()) out.push_back(v.back());
  return out;
}

// The lattice entry nearest to z among the interior ones (shelves snap to the grid).
inline double snap_interior(const std::vector<double>& v, double z) {
  if (v.size() < 3) return 0.5 * (v.front() + v.back());
  double best = v[1];
  for (size_t i = 1; i + 1 < v.size(); ++i)
    if (std::abs(v[i] - z) < std::abs(best - z)) best = v[i];
  return best;
}

class Wireframe {
 public:
  void add_line(std::string name, const Vec3& a, const Vec3& b, int section, const Vec3& y_ref_local = Vec3::Zero(),
                double density_factor = 1.0) {
    if ((b - a).norm() <= wire_tolerance)
      throw ModelError("furniture wireframe: line '" + name + "' has zero length");
    if (!names_.insert(name).second)
      throw ModelError("furniture wireframe: line name '" + name + "' is used twice");
    lines_.push_back(WireLine{std::move(name), a, b, section, y_ref_local, density_factor});
  }

  // A grid of lines on an axis-aligned rectangle in the plane {normal_axis = plane}: lines along the
  // first in-plane axis u at each v in vs, and lines along the second axis v at each u in us
  // (u < v in the order x, y, z). Lines are named "<panel>/<axis><index>", e.g. "top/x0" is the
  // top board's line along x at its first (front) y. The section's local y lies in the panel plane,
  // so a 50 x 30 tube shows its 30 mm side across the panel, like the sheet it stands for.
  void panel(const std::string& panel_name, int normal_axis, double plane, const std::vector<double>& us,
             const std::vector<double>& vs, int section) {
    const int u = normal_axis == 0 ? 1 : 0;
    const int v = normal_axis == 2 ? 1 : 2;
    const char axis_letter[3] = {'x', 'y', 'z'};
    auto point = [&](double pu, double pv) {
      Vec3 p;
      p[normal_axis] = plane;
      p[u] = pu;
      p[v] = pv;
      return p;
    };
    for (size_t j = 0; j < vs.size(); ++j)
      add_line(panel_name + "/" + axis_letter[u] + std::to_string(j), point(us.front(), vs[j]),
               point(us.back(), vs[j]), section, Vec3::Unit(v));
    for (size_t i = 0; i < us.size(); ++i)
      add_line(panel_name + "/" + axis_letter[v] + std::to_string(i), point(us[i], vs.front()),
               point(us[i], vs.back()), section, Vec3::Unit(u));
  }

  const std::vector<WireLine>& lines() const { return lines_; }

  // Builds the wireframe into `model` as part of `body`, placed by x_world = R x_local + p.
  RealizedWireframe realize(Model& model, int body, int material, const Mat3& R, const Vec3& p,
                            double element_length) const {
    const auto cuts = cut_parameters();
    RealizedWireframe out;
    std::map<std::tuple<long long, long long, long long>, int> node_at;
    auto key = [](const Vec3& x) {
      const double q = 1.0 / wire_tolerance;
      return std::make_tuple(std::llround(x.x() * q), std::llround(x.y() * q), std::llround(x.z() * q));
    };
    auto node = [&](const Vec3& x_local) {
      auto [it, fresh] = node_at.try_emplace(key(x_local), -1);
      if (fresh) it->second = model.add_node(R * x_local + p, body);
      return it->second;
    };
    std::set<std::pair<int, int>> built;
    for (size_t i = 0; i < lines_.size(); ++i) {
      const WireLine& line = lines_[i];
      const auto& t = cuts[i];
      out.line_end_a_node[line.name] = node(line.a);
      out.line_end_b_node[line.name] = node(line.b);
      for (size_t k = 0; k + 1 < t.size(); ++k) {
        const int n1 = node(line.a + t[k] * (line.b - line.a));
        const int n2 = node(line.a + t[k + 1] * (line.b - line.a));
        if (!built.insert({std::min(n1, n2), std::max(n1, n2)}).second) continue;  // shared edge
        MemberOptions opts;
        opts.target_length = element_length;
        opts.count_length = (t[k + 1] - t[k]) * (line.b - line.a).norm();  // the same at every placement
        opts.pairs = true;
        opts.y_ref = line.y_ref_local.norm() > 0 ? Vec3(R * line.y_ref_local) : Vec3::Zero();
        opts.line_mass = line.density_factor * model.materials()[material].rho * model.sections()[line.section].A;
        out.members.push_back(
            model.add_member(line.name + ":" + std::to_string(k), n1, n2, line.section, material, opts));
      }
    }
    return out;
  }

 private:
  // For each line, the sorted parameters t in [0, 1] where it must be split: its ends, the ends of
  // other lines lying on it, and the points where other lines cross it.
  std::vector<std::vector<double>> cut_parameters() const {
    const double tol = wire_tolerance;
    std::vector<std::vector<double>> cuts(lines_.size());
    for (size_t i = 0; i < lines_.size(); ++i) {
      const Vec3 a = lines_[i].a, d = lines_[i].b - lines_[i].a;
      const double len2 = d.squaredNorm(), len = std::sqrt(len2);
      auto& t = cuts[i];
      t = {0.0, 1.0};
      auto on_line = [&](const Vec3& q) {
        const double s = (q - a).dot(d) / len2;
        if (s * len > tol && (1 - s) * len > tol && (a + s * d - q).norm() <= tol) t.push_back(s);
      };
      for (size_t j = 0; j < lines_.size(); ++j) {
        if (j == i) continue;
        const Vec3 c = lines_[j].a, e = lines_[j].b - lines_[j].a;
        on_line(c);
        on_line(lines_[j].b);
        // Interior crossing of two non-parallel segments: closest points of the two carrier lines.
        const Vec3 n = d.cross(e);
        if (n.squaredNorm() <= 1e-12 * len2 * e.squaredNorm()) continue;
        const Vec3 w = c - a;
        const double s = w.cross(e).dot(n) / n.squaredNorm();
        const double r = w.cross(d).dot(n) / n.squaredNorm();
        const double elen = e.norm();
        if (s * len > tol && (1 - s) * len > tol && r * elen >= -tol && (1 - r) * elen >= -tol &&
            ((a + s * d) - (c + r * e)).norm() <= tol)
          t.push_back(s);
      }
      std::sort(t.begin(), t.end());
      std::vector<double> unique;
      for (double s : t)
        if (unique.empty() || (s - unique.back()) * len > tol) unique.push_back(s);
      unique.back() = 1.0;
      t = std::move(unique);
    }
    return cuts;
  }

  std::vector<WireLine> lines_;
  std::set<std::string> names_;
};

// Index of a section in the model, adding it unless an identical one (same name and properties) is
// there already: items built into one model share their sections.
inline int find_or_add_section(Model& model, const Section& s) {
  const auto& all = model.sections();
  for (size_t i = 0; i < all.size(); ++i)
    if (all[i].name == s.name && all[i].A == s.A && all[i].Iy == s.Iy && all[i].Iz == s.Iz &&
        all[i].hy == s.hy && all[i].hz == s.hz)
      return static_cast<int>(i);
  return model.add_section(s);
}

inline int find_or_add_material(Model& model, const Material& m) {
  const auto& all = model.materials();
  for (size_t i = 0; i < all.size(); ++i)
    if (all[i].name == m.name && all[i].E == m.E && all[i].nu == m.nu && all[i].rho == m.rho &&
        all[i].sigma_y == m.sigma_y)
      return static_cast<int>(i);
  return model.add_material(m);
}

}  // namespace furniture_fem::detail
