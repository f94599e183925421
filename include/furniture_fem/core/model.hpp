#pragma once
// furniture_fem/core/model.hpp: what a structure is made of.
//
// Nodes (six DOF each), cross sections, materials, members split into elements (in pairs where the
// ASI-Gauss element needs them) and bodies, one per furniture item. The model is pure data plus the
// checks that make bad input fail loudly; elements, integrators and contact read it.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "errors.hpp"

namespace furniture_fem {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

// m/s^2 per g (the PEER/NGA convention; a head injury criterion takes accelerations in g too).
inline constexpr double standard_gravity = 9.80665;

namespace detail {
inline std::string fmt(double v) {
  std::ostringstream os;
  os.precision(6);
  os << v;
  return os.str();
}
inline bool finite(const Vec3& v) { return v.allFinite(); }
}  // namespace detail

// Steel of the furniture in the paper: E 206 GPa, nu 0.3, sigma_y 245 MPa, rho 7850 kg/m^3.
struct Material {
  std::string name = "steel";
  double E = 206e9;
  double nu = 0.3;
  double sigma_y = 245e6;
  double rho = 7850.0;
  double G() const { return E / (2.0 * (1.0 + nu)); }
  static Material steel() { return {}; }
};

// Properties of a cross section in its local axes: local x along the member, y and z across it.
// Iz resists bending in the x-y plane (curvature kappa_z), Iy in the x-z plane. Shear areas are
// k*A (Timoshenko). Plastic moduli give the fully plastic moments Mp = sigma_y * Zp.
struct Section {
  std::string name;
  double A = 0, Iy = 0, Iz = 0, J = 0;
  double Asy = 0, Asz = 0;     // shear areas for shear along y and along z
  double Zpy = 0, Zpz = 0;     // plastic moduli about y and about z
  double Zpx = 0;              // "plastic modulus" in torsion: Mx_p = Zpx * sigma_y / sqrt(3)
  double hy = 0, hz = 0;       // outer extents along local y and z (contact width, drawing)

  // Width used by the contact law: the paper's member width (50 mm for the 50 x 30 tubes).
  double contact_width() const { return std::max(hy, hz); }

  // Hollow rectangle, outer hy x hz, wall t (the paper's section types 1). Thin-wall formulas for
  // J (Bredt) and for the shear areas (the walls parallel to the shear carry it).
  static Section hollow_rectangle(double hy, double hz, double t, std::string name = "hollow rectangle") {
    if (!(hy > 0) || !(hz > 0) || !(t > 0) || 2 * t >= std::min(hy, hz))
      throw ModelError("section '" + name + "': hollow rectangle needs hy, hz > 2 t > 0 (hy = " +
                       detail::fmt(hy) + ", hz = " + detail::fmt(hz) + ", t = " + detail::fmt(t) + ")");
    Section s;
    s.name = std::move(name);
    const double iy = hy - 2 * t, iz = hz - 2 * t;
    s.A = hy * hz - iy * iz;
    s.Iz = (hz * hy * hy * hy - iz * iy * iy * iy) / 12.0;
    s.Iy = (hy * hz * hz * hz - iy * iz * iz * iz) / 12.0;
    const double am = (hy - t) * (hz - t);             // area enclosed by the wall's mid line
    s.J = 4.0 * am * am * t / (2.0 * ((hy - t) + (hz - t)));
    s.Asy = 2.0 * t * (hy - t);
    s.Asz = 2.0 * t * (hz - t);
    s.Zpz = (hz * hy * hy - iz * iy * iy) / 4.0;
    s.Zpy = (hy * hz * hz - iy * iz * iz) / 4.0;
    s.Zpx = 2.0 * am * t;                               // fully plastic Bredt torsion / tau_y
    s.hy = hy;
    s.hz = hz;
    return s;
  }

  // Circular tube, outer diameter D, wall t.
  static Section circular_tube(double D, double t, std::string name = "circular tube") {
    if (!(D > 0) || !(t > 0) || 2 * t >= D)
      throw ModelError("section '" + name + "': circular tube needs D > 2 t > 0 (D = " + detail::fmt(D) +
                       ", t = " + detail::fmt(t) + ")");
    Section s;
    s.name = std::move(name);
    const double d = D - 2 * t;
    const double pi = std::numbers::pi;
    s.A = pi * (D * D - d * d) / 4.0;
    s.Iy = s.Iz = pi * (D * D * D * D - d * d * d * d) / 64.0;
    s.J = 2.0 * s.Iy;
    s.Asy = s.Asz = s.A / 2.0;
    s.Zpy = s.Zpz = (D * D * D - d * d * d) / 6.0;
    const double rm = (D - t) / 2.0;
    s.Zpx = 2.0 * pi * rm * rm * t;
    s.hy = s.hz = D;
    return s;
  }

  // Direct property input, for sections the paper gives only by their properties (Table 1 types 2
  // and 3). Missing values are derived: J = Iy + Iz (a closed thin tube's upper bound), shear areas
  // A/2, plastic moduli 1.2 I/(h/2) (a typical shape factor of hollow sections).
  static Section from_properties(std::string name, double A, double Iy, double Iz, double hy, double hz,
                                 double J = 0, double Asy = 0, double Asz = 0) {
    Section s;
    s.name = std::move(name);
    s.A = A;
    s.Iy = Iy;
    s.Iz = Iz;
    s.hy = hy;
    s.hz = hz;
    s.J = J > 0 ? J : Iy + Iz;
    s.Asy = Asy > 0 ? Asy : A / 2;
    s.Asz = Asz > 0 ? Asz : A / 2;
    s.Zpz = hy > 0 ? 1.2 * Iz / (hy / 2) : 0;
    s.Zpy = hz > 0 ? 1.2 * Iy / (hz / 2) : 0;
    s.Zpx = s.J / std::max(hy, hz) * 2.0;
    s.validate();
    return s;
  }

  void validate() const {
    const std::array<std::pair<const char*, double>, 8> v{{{"A", A}, {"Iy", Iy}, {"Iz", Iz}, {"J", J},
                                                           {"Asy", Asy}, {"Asz", Asz}, {"hy", hy}, {"hz", hz}}};
    for (auto [key, val] : v)
      if (!(val > 0) || !std::isfinite(val))
        throw ModelError("section '" + name + "': " + key + " must be positive and finite (got " +
                         detail::fmt(val) + ")");
  }
};

enum Dof : unsigned { UX = 1, UY = 2, UZ = 4, RX = 8, RY = 16, RZ = 32, ALL_TRANSLATIONS = 7,
                      ALL_ROTATIONS = 56, ALL_DOFS = 63 };

struct Node {
  Vec3 X;          // initial position (m)
  int body = 0;
  unsigned fixed = 0;  // Dof mask of prescribed (zero) DOFs
};

// Where an element sits in its ASI-Gauss pair: the first (near the pair's end i), the second, or none
// (a member split into an odd count, allowed only for elements that do not need pairs).
enum class PairSlot : int { none = -1, first = 0, second = 1 };

struct ElementData {
  int n1 = 0, n2 = 0;
  int section = 0, material = 0, body = 0, member = 0;
  Vec3 y_ref;               // a vector in the local x-y plane, fixes the section's orientation
  double line_mass = 0;     // kg/m (rho A, scaled when a body's mass is calibrated)
  PairSlot slot = PairSlot::none;
  int partner = -1;         // the other element of the pair
};

struct Member {
  std::string name;
  int body = 0;
  int first_element = 0, element_count = 0;
  int node_i = 0, node_j = 0;
};

// A point mass on a node: mass (kg) and principal moments of rotary inertia (kg m^2) about the node
// along `axes` (columns, world axes at the start; they turn with the node). Items whose mass is not
// carried by their members (a solid block on a light frame of its edges) put it here.
struct PointMass {
  int node = 0;
  double mass = 0;
  Vec3 inertia = Vec3::Zero();
  Mat3 axes = Mat3::Identity();
  Mat3 inertia_tensor() const { return axes * inertia.asDiagonal() * axes.transpose(); }
};

struct Body {
  std::string name;
  std::vector<int> nodes, elements, members;
  std::vector<int> point_masses;  // indices into Model::point_masses(), in the order they were added
};

struct MemberOptions {
  double target_length = 0.05;  // the paper's 50 mm
  int elements = 0;             // overrides target_length when > 0
  // The length the count is taken from, when > 0 (a member's length in its item's own frame): the
  // nodes' distance differs by round-off with where an item stands, and a length half-way between two
  // counts then gave one count or the other from one placement to another.
  double count_length = 0;
  bool pairs = true;            // round the count up to an even number and mark pairs (ASI-Gauss)
  Vec3 y_ref = Vec3::Zero();    // zero: chosen automatically (global z, or global y for vertical members)
  double line_mass = -1;        // kg/m; negative: rho A
};

class Model {
 public:
  int add_body(std::string name) {
    bodies_.push_back(Body{std::move(name), {}, {}, {}, {}});
    return static_cast<int>(bodies_.size()) - 1;
  }
  int add_section(Section s) {
    s.validate();
    sections_.push_back(std::move(s));
    return static_cast<int>(sections_.size()) - 1;
  }
  int add_material(Material m) {
    const std::array<std::pair<const char*, double>, 3> v{{{"E", m.E}, {"sigma_y", m.sigma_y}, {"rho", m.rho}}};
    for (auto [key, val] : v)
      if (!(val > 0) || !std::isfinite(val))
        throw ModelError("material '" + m.name + "': " + key + " must be positive and finite (got " +
                         detail::fmt(val) + ")");
    if (!(m.nu > -1 && m.nu < 0.5))
      throw ModelError("material '" + m.name + "': nu must lie in (-1, 0.5) (got " + detail::fmt(m.nu) + ")");
    materials_.push_back(std::move(m));
    return static_cast<int>(materials_.size()) - 1;
  }
  static constexpr double max_member_elements = 1e6;
  int add_node(const Vec3& X, int body) {
    check_body(body, "add_node");
    if (!detail::finite(X))
      throw ModelError("node " + std::to_string(nodes_.size()) + " of body '" + bodies_[body].name +
                       "': coordinates are not finite (" + detail::fmt(X.x()) + ", " + detail::fmt(X.y()) +
                       ", " + detail::fmt(X.z()) + ")");
    nodes_.push_back(Node{X, body, 0});
    bodies_[body].nodes.push_back(static_cast<int>(nodes_.size()) - 1);
    return static_cast<int>(nodes_.size()) - 1;
  }
  void fix(int node, unsigned dofs = ALL_DOFS) { nodes_.at(node).fixed |= dofs; }

  // Adds a point mass (kg) and principal rotary inertia (kg m^2) to a node, the principal axes the
  // columns of `axes` (a rotation; default the node's initial axes, i.e. world axes); several on one
  // node add up. The simulation lumps them with the members' masses.
  void add_point_mass(int node, double mass, const Vec3& inertia = Vec3::Zero(), const Mat3& axes = Mat3::Identity()) {
    if (node < 0 || node >= num_nodes())
      throw ModelError("add_point_mass: node index out of range: " + std::to_string(node));
    const std::string who = "point mass on node " + std::to_string(node) + " of body '" + bodies_[nodes_[node].body].name + "'";
    if (!(mass >= 0) || !std::isfinite(mass))
      throw ModelError(who + ": mass must be non-negative and finite (got " + detail::fmt(mass) + " kg)");
    for (int i = 0; i < 3; ++i)
      if (!(inertia[i] >= 0) || !std::isfinite(inertia[i]))
        throw ModelError(who + ": rotary inertia must be non-negative and finite (got " + detail::fmt(inertia[i]) +
                         " kg m^2 about axis " + std::string(1, "xyz"[i]) + ")");
    if (!axes.allFinite() || (axes.transpose() * axes - Mat3::Identity()).norm() > 1e-9 || axes.determinant() < 0)
      throw ModelError(who + ": the principal axes must be a rotation (orthonormal columns, right-handed)");
    bodies_[nodes_[node].body].point_masses.push_back(static_cast<int>(point_masses_.size()));
    point_masses_.push_back(PointMass{node, mass, inertia, axes});
  }

  // Adds a member from node i to node j, split into elements of about opts.target_length (an even
  // count when opts.pairs), creating the intermediate nodes. Returns the member index.
  int add_member(std::string name, int node_i, int node_j, int section, int material,
                 const MemberOptions& opts = {}) {
    const std::string who = "member '" + name + "'";
    if (node_i < 0 || node_i >= num_nodes() || node_j < 0 || node_j >= num_nodes())
      throw ModelError(who + ": node index out of range (" + std::to_string(node_i) + ", " +
                       std::to_string(node_j) + ")");
    if (section < 0 || section >= static_cast<int>(sections_.size()))
      throw ModelError(who + ": unknown section " + std::to_string(section));
    if (material < 0 || material >= static_cast<int>(materials_.size()))
      throw ModelError(who + ": unknown material " + std::to_string(material));
    const int body = nodes_[node_i].body;
    if (nodes_[node_j].body != body)
      throw ModelError(who + ": nodes belong to different bodies ('" + bodies_[body].name + "' and '" +
                       bodies_[nodes_[node_j].body].name + "')");
    const Vec3 a = nodes_[node_i].X, b = nodes_[node_j].X;
    const double length = (b - a).norm();
    if (!(length > 1e-9))
      throw ModelError(who + ": zero length (" + detail::fmt(length) + " m) between nodes " +
                       std::to_string(node_i) + " and " + std::to_string(node_j));
    int n = opts.elements;
    if (n <= 0) {
      if (!(opts.target_length > 0))
        throw ModelError(who + ": target_length must be positive (got " + detail::fmt(opts.target_length) + ")");
      const double count = (opts.count_length > 0 ? opts.count_length : length) / opts.target_length;
      if (!count_fits(count, max_member_elements))
        throw ModelError(who + ": target_length " + detail::fmt(opts.target_length) + " m gives " + detail::fmt(count) +
                         " elements over " + detail::fmt(length) + " m (at most 1e6 per member)");
      n = std::max(1, static_cast<int>(std::lround(count)));
    }
    if (opts.pairs && n % 2 != 0) {
      if (opts.elements > 0)
        throw ModelError(who + ": ASI-Gauss needs an even element count, got " + std::to_string(n));
      n += 1;
    }
    const Vec3 axis = (b - a) / length;
    Vec3 yref = opts.y_ref;
    if (yref.norm() == 0) yref = std::abs(axis.z()) > 0.9 ? Vec3::UnitY() : Vec3::UnitZ();
    if (!detail::finite(yref) || axis.cross(yref).norm() < 1e-6 * yref.norm())
      throw ModelError(who + ": y_ref is parallel to the member axis or not finite");
    const double line_mass = opts.line_mass >= 0 ? opts.line_mass : materials_[material].rho * sections_[section].A;
    if (!std::isfinite(line_mass))
      throw ModelError(who + ": line mass is not finite (" + detail::fmt(line_mass) + ")");

    Member m{std::move(name), body, num_elements(), n, node_i, node_j};
    const int member_index = static_cast<int>(members_.size());
    int prev = node_i;
    for (int k = 0; k < n; ++k) {
      const int next = (k == n - 1) ? node_j : add_node(a + (b - a) * (double(k + 1) / n), body);
      ElementData e;
      e.n1 = prev;
      e.n2 = next;
      e.section = section;
      e.material = material;
      e.body = body;
      e.member = member_index;
      e.y_ref = yref;
      e.line_mass = line_mass;
      if (opts.pairs) {
        e.slot = (k % 2 == 0) ? PairSlot::first : PairSlot::second;
        e.partner = num_elements() + ((k % 2 == 0) ? 1 : -1);
      }
      elements_.push_back(e);
      bodies_[body].elements.push_back(num_elements() - 1);
      prev = next;
    }
    bodies_[body].members.push_back(member_index);
    members_.push_back(std::move(m));
    return member_index;
  }

  // Checks what add_* could not see alone: duplicate elements, unconnected nodes, odd pairs.
  void validate() const {
    std::vector<int> degree(nodes_.size(), 0);
    std::vector<std::pair<int, int>> keys;
    keys.reserve(elements_.size());
    for (int e = 0; e < num_elements(); ++e) {
      const auto& el = elements_[e];
      degree[el.n1]++;
      degree[el.n2]++;
      keys.emplace_back(std::min(el.n1, el.n2), std::max(el.n1, el.n2));
      if ((nodes_[el.n2].X - nodes_[el.n1].X).norm() <= 1e-9)
        throw ModelError(describe_element(e) + ": zero length");
      if (el.slot != PairSlot::none && (el.partner < 0 || el.partner >= num_elements() ||
                                        elements_[el.partner].partner != e))
        throw ModelError(describe_element(e) + ": ASI-Gauss pair partner is missing");
    }
    std::vector<int> order(keys.size());
    for (size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
    std::sort(order.begin(), order.end(), [&](int x, int y) { return keys[x] < keys[y]; });
    for (size_t i = 1; i < order.size(); ++i)
      if (keys[order[i]] == keys[order[i - 1]])
        throw ModelError(describe_element(order[i]) + ": duplicates " + describe_element(order[i - 1]) +
                         " (nodes " + std::to_string(keys[order[i]].first) + ", " +
                         std::to_string(keys[order[i]].second) + ")");
    for (int n = 0; n < num_nodes(); ++n)
      if (degree[n] == 0)
        throw ModelError("node " + std::to_string(n) + " of body '" + bodies_[nodes_[n].body].name +
                         "' at (" + detail::fmt(nodes_[n].X.x()) + ", " + detail::fmt(nodes_[n].X.y()) + ", " +
                         detail::fmt(nodes_[n].X.z()) + ") is not connected to any element");
  }

  std::string describe_element(int e) const {
    const auto& el = elements_.at(e);
    const auto& m = members_.at(el.member);
    return "member '" + m.name + "' element " + std::to_string(e - m.first_element) + " (global " +
           std::to_string(e) + ")";
  }

  // Mass of a body (kg) and its centre of gravity in the initial configuration, point masses included.
  double body_mass(int b) const {
    double m = 0;
    for (int e : bodies_.at(b).elements) m += elements_[e].line_mass * element_length(e);
    for (int i : bodies_.at(b).point_masses) m += point_masses_[i].mass;
    return m;
  }
  // Centre of gravity of a body in its initial configuration: every mass it carries, its elements'
  // line masses and its point masses.
  Vec3 body_centre_of_gravity(int b) const {
    return body_centre_of_gravity(b, [this](int n) -> const Vec3& { return nodes_[n].X; });
  }
  // The same with the nodes at position(n) (a deformed or moved configuration): the final state's centre
  // of gravity must weigh the same masses as the start's, or a body at rest reports a displacement.
  template <class Position>
  Vec3 body_centre_of_gravity(int b, Position&& position) const {
    double m = 0;
    Vec3 c = Vec3::Zero();
    for (int e : bodies_.at(b).elements) {
      const double me = elements_[e].line_mass * element_length(e);
      m += me;
      c += me * 0.5 * (position(elements_[e].n1) + position(elements_[e].n2));
    }
    for (int i : bodies_.at(b).point_masses) {
      const PointMass& p = point_masses_[i];
      m += p.mass;
      c += p.mass * position(p.node);
    }
    return m > 0 ? Vec3(c / m) : c;
  }
  // Inertia tensor (kg m^2) of a body about a point, in the initial configuration, with the masses
  // lumped as the simulation lumps them: half of each element's mass and of its rotary inertia
  // rho (Iy + Iz) L (isotropic) on each end node, and the point masses with their rotary inertia.
  Mat3 body_inertia(int b, const Vec3& about) const {
    Mat3 I = Mat3::Zero();
    const auto add_mass = [&](const Vec3& x, double m) {
      const Vec3 r = x - about;
      I += m * (r.squaredNorm() * Mat3::Identity() - r * r.transpose());
    };
    for (int e : bodies_.at(b).elements) {
      const auto& el = elements_[e];
      const Section& s = sections_[el.section];
      const double m = el.line_mass * element_length(e), J = el.line_mass / s.A * (s.Iy + s.Iz) * element_length(e);
      for (int n : {el.n1, el.n2}) add_mass(nodes_[n].X, 0.5 * m);
      I += J * Mat3::Identity();  // two ends, half each
    }
    for (int i : bodies_.at(b).point_masses) {
      const PointMass& p = point_masses_[i];
      add_mass(nodes_[p.node].X, p.mass);
      I += p.inertia_tensor();
    }
    return I;
  }
  double element_length(int e) const {
    return (nodes_[elements_[e].n2].X - nodes_[elements_[e].n1].X).norm();
  }

  int num_nodes() const { return static_cast<int>(nodes_.size()); }
  int num_elements() const { return static_cast<int>(elements_.size()); }
  int num_bodies() const { return static_cast<int>(bodies_.size()); }
  int num_members() const { return static_cast<int>(members_.size()); }
  const std::vector<Node>& nodes() const { return nodes_; }
  const std::vector<ElementData>& elements() const { return elements_; }
  std::vector<ElementData>& elements() { return elements_; }
  const std::vector<Member>& members() const { return members_; }
  const std::vector<Body>& bodies() const { return bodies_; }
  const std::vector<Section>& sections() const { return sections_; }
  const std::vector<Material>& materials() const { return materials_; }
  const std::vector<PointMass>& point_masses() const { return point_masses_; }
  const Node& node(int n) const { return nodes_.at(n); }
  const Member& member(int m) const { return members_.at(m); }
  const Body& body(int b) const { return bodies_.at(b); }
  const Section& section_of(int e) const { return sections_[elements_[e].section]; }
  const Material& material_of(int e) const { return materials_[elements_[e].material]; }
  // Multiplies the mass of body `b` (its members' line masses, and the mass and rotary inertia of the
  // point masses on its nodes) by `factor`: its centre of gravity stays where it is.
  void scale_body_mass(int b, double factor) {
    if (!(factor > 0) || !std::isfinite(factor))
      throw ModelError("body '" + bodies_.at(b).name + "': mass factor must be positive and finite (got " +
                       detail::fmt(factor) + ")");
    for (int e : bodies_.at(b).elements) elements_[e].line_mass *= factor;
    for (int i : bodies_.at(b).point_masses) {
      point_masses_[i].mass *= factor;
      point_masses_[i].inertia *= factor;
    }
  }
  // Turns body `b` rigidly by the rotation Q about `pivot`: its nodes, its sections' orientation and its
  // point masses' axes (an item leaning back on stoppers before the run, scene/build.hpp).
  void turn_body(int b, const Mat3& Q, const Vec3& pivot) {
    check_body(b, "turn_body");
    for (int n : bodies_[b].nodes) nodes_[n].X = pivot + Q * (nodes_[n].X - pivot);
    for (int e : bodies_[b].elements) elements_[e].y_ref = Q * elements_[e].y_ref;
    for (int i : bodies_[b].point_masses) point_masses_[i].axes = Q * point_masses_[i].axes;
  }
  void set_line_mass(int e, double mu) {
    if (!(mu >= 0) || !std::isfinite(mu))
      throw ModelError(describe_element(e) + ": line mass must be non-negative and finite (got " +
                       detail::fmt(mu) + ")");
    elements_.at(e).line_mass = mu;
  }

 private:
  void check_body(int b, const char* where) const {
    if (b < 0 || b >= num_bodies())
      throw ModelError(std::string(where) + ": unknown body " + std::to_string(b));
  }
  std::vector<Node> nodes_;
  std::vector<ElementData> elements_;
  std::vector<Member> members_;
  std::vector<Body> bodies_;
  std::vector<Section> sections_;
  std::vector<Material> materials_;
  std::vector<PointMass> point_masses_;
};

}  // namespace furniture_fem
