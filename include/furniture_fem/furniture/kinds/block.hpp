#pragma once
// furniture_fem/furniture/kinds/block.hpp: the kind "block" (build_block): a solid uniform box, rigid
// only, for scenes whose answer is known in closed form (a block sliding or resting on the table).
#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "generic_box.hpp"

namespace furniture_fem {

namespace detail {

// Outer width of the block's edge tubes: their half width is the floor contact distance L, so the
// bottom edges' centre lines sit L above the base (floor-contact onset, as the other builders).
inline constexpr double block_edge_width = 0.010;
// Share of the block's mass on its frame (edges and spokes): the rest is on the hub, which then
// carries all the inertia the frame lacks (a larger share could exceed the solid's inertia).
inline constexpr double block_frame_mass_share = 0.01;

// Why a block cannot be built with these options, or nothing. A block is a rigid body: its frame is
// contact geometry, not a structure, so finite-element fidelities and panel options do not apply.
inline std::string block_option_problem(const BuildOptions& o) {
  if (o.fidelity == Fidelity::full || o.fidelity == Fidelity::coarse)
    return "fidelity \"" + to_string(o.fidelity) + "\" is not available: a block is modelled rigid (use \"rigid\" or "
           "\"auto\")";
  if (!o.mass_kg) return "mass_kg is required (the block's mass, kg)";
  if (o.cog_d1) return "cog_d1 does not apply: a block's centre of gravity lies on its vertical axis (cog_h sets its height)";
  if (o.panel_spacing || o.grid_scale != 1.0) return "panel_spacing and grid_scale do not apply: a block has no panels";
  return {};
}

// Height of the hub (item frame) that puts the body's centre of gravity at h: the frame's edges
// (mass m_e, centroid at z_e) and the spokes from the hub to the bottom corners (mass mu s each, at mid
// length) move it; solved by fixed-point iteration (the frame is light: it converges in a few steps).
inline double block_hub_height(double M, double h, double z_e, double m_e, double mu, double half_diag2, double c) {
  double z = h;
  for (int k = 0; k < 50; ++k) {
    const double m_s = 4 * mu * std::sqrt(half_diag2 + (z - c) * (z - c));
    z = (M * h - m_e * z_e - m_s * 0.5 * c) / (M - m_e - 0.5 * m_s);
  }
  return z;
}

// Where a block's bottom corners go. Floor contact acts at the nodes, whose centre lines sit c above
// the floor, so a block tips about its bottom nodes, not about the box's edges. Each bottom corner is
// put where the line from the centre of gravity (height h) to the box's bottom edge crosses the height
// c: a fraction 1 - c/h of the box's half width and depth. The lever arms of weight and table
// acceleration about that pivot then have the box's ratio b/h, so the block tips at g b/h exactly (with
// the corners c inside the faces it tipped at g (b - c)/(h - c): 4 % low for a 0.2 x 1 m block).
inline double block_bottom_scale(double h, double c) { return 1.0 - c / h; }

}  // namespace detail

// A solid uniform box W x D x H of mass mass_kg (required), its centre of gravity on its vertical axis at
// cog_h (default H/2), to be solved as a rigid body. Modelled as a light frame of its 12 edges (10 mm
// tubes, the contact geometry: the top corners 5 mm inside the faces, the bottom ones 5 mm above the base
// on the lines from the centre of gravity to the box's bottom edges) with 4 spokes from a hub
// node to the bottom corners; the frame carries 1 % of the mass, the hub the rest and the principal
// inertia that makes the body's inertia tensor about its centre of gravity the solid box's,
// M/12 diag(D^2 + H^2, W^2 + H^2, W^2 + D^2) in the item's axes. Marker "cog": the hub.
inline ItemInfo build_block(Model& model, const Placement& placement, double W, double D, double H,
                            const BuildOptions& opts = {}) {
  const std::string name = detail::name_or(opts, "block");
  const std::string who = "block '" + name + "'";
  detail::check_options(opts, who);
  detail::check_size(W, D, H, who);
  if (const std::string why = detail::block_option_problem(opts); !why.empty()) throw ModelError(who + ": " + why);
  const double M = *opts.mass_kg, c = 0.5 * detail::block_edge_width;
  const double h = opts.cog_h.value_or(0.5 * H);
  // The bottom corners close in by c/h (block_bottom_scale): at h = 2c they sit at half the box.
  if (!(h >= 2 * c && h <= H - c))
    throw ModelError(who + ": cog_h must lie within the frame, in [" + detail::fmt(2 * c) + ", " + detail::fmt(H - c) +
                     "] m (got " + detail::fmt(h) + ")");
  ItemInfo info;
  info.name = name;
  info.kind = ItemKind::block;
  info.body = model.add_body(name);
  info.R = placement.rotation();
  info.position = placement.position();
  info.size = {W, D, H};
  info.fidelity = Fidelity::rigid;  // "auto" too: there is nothing else to choose

  // Frame: corners, edges, hub and spokes, with a line mass that gives it its share of the mass. The
  // top corners sit c inside the faces; the bottom ones on the lines from the centre of gravity to the
  // box's bottom edges (block_bottom_scale), so the posts lean by a fraction of a degree.
  const double x = 0.5 * W - c, y = 0.5 * D - c, z0 = c, z1 = H - c;
  const double s = detail::block_bottom_scale(h, c), xb = 0.5 * W * s, yb = 0.5 * D * s;
  const double bottom_len = 4 * (xb + yb), top_len = 4 * (x + y);
  const double post_len = 4 * std::sqrt((x - xb) * (x - xb) + (y - yb) * (y - yb) + (z1 - z0) * (z1 - z0));
  const double half_diag2 = xb * xb + yb * yb, edges = bottom_len + top_len + post_len;
  const double z_edges = (bottom_len * z0 + top_len * z1 + post_len * 0.5 * (z0 + z1)) / edges;
  const double mu = detail::block_frame_mass_share * M / (edges + 4 * std::sqrt(half_diag2 + (h - c) * (h - c)));
  const double z_hub = detail::block_hub_height(M, h, z_edges, mu * edges, mu, half_diag2, c);
  const auto node = [&](const Vec3& local) { return model.add_node(info.to_world(local), info.body); };
  const std::array<std::pair<const char*, std::array<double, 2>>, 4> corners{
      {{"front_left", {-1, -1}}, {"front_right", {1, -1}}, {"back_right", {1, 1}}, {"back_left", {-1, 1}}}};
  std::array<int, 4> bottom{}, top{};
  std::array<Vec3, 4> bottom_local, top_local;  // element counts follow these: the same at every placement
  for (int k = 0; k < 4; ++k) {
    const auto [sx, sy] = corners[k].second;
    bottom_local[k] = Vec3(sx * xb, sy * yb, z0);
    top_local[k] = Vec3(sx * x, sy * y, z1);
    bottom[k] = node(bottom_local[k]);
    top[k] = node(top_local[k]);
  }
  const Vec3 hub_local(0, 0, z_hub);
  const int hub = node(hub_local);
  const int section = detail::find_or_add_section(
      model, Section::hollow_rectangle(detail::block_edge_width, detail::block_edge_width, 0.001, "block edge 10x10x1"));
  const int material = detail::find_or_add_material(model, Material::steel());
  MemberOptions mo;
  mo.target_length = opts.effective_element_length();
  mo.line_mass = mu;
  const auto member = [&](const std::string& name, int a, int b, const Vec3& a_local, const Vec3& b_local) {
    mo.count_length = (b_local - a_local).norm();
    model.add_member(name, a, b, section, material, mo);
  };
  for (int k = 0; k < 4; ++k) {
    const std::string from = corners[k].first, to = corners[(k + 1) % 4].first;
    const int next = (k + 1) % 4;
    member("bottom/" + from + "-" + to, bottom[k], bottom[next], bottom_local[k], bottom_local[next]);
    member("top/" + from + "-" + to, top[k], top[next], top_local[k], top_local[next]);
    member("post/" + from, bottom[k], top[k], bottom_local[k], top_local[k]);
    member("spoke/" + from, hub, bottom[k], hub_local, bottom_local[k]);
  }

  // The hub: the rest of the mass, and the inertia the frame and the hub's offset from the centre of
  // gravity leave to the solid box's (the frame is symmetric about the item's x-z and y-z planes, so
  // that remainder is diagonal in the item's axes).
  const Vec3 cog = info.to_world({0, 0, h});
  const double m_hub = M - model.body_mass(info.body), d = z_hub - h;
  const Vec3 box(D * D + H * H, W * W + H * H, W * W + D * D);
  const Mat3 rest = info.R.transpose() * model.body_inertia(info.body, cog) * info.R;
  const Vec3 J = M / 12.0 * box - rest.diagonal() - m_hub * Vec3(d * d, d * d, 0);
  for (int i = 0; i < 3; ++i)
    if (!(J[i] >= 0))
      throw ModelError(who + ": its frame alone exceeds the solid box's inertia about item axis " +
                       std::string(1, "xyz"[i]) + " (a block too flat for its edge tubes)");
  model.add_point_mass(hub, m_hub, J, info.R);

  const int long_axis = W >= D ? 0 : 1;
  const auto& tall = paper_item(PaperItem::tall_cabinet);
  info.contact = ItemContact::from_rule(M, opts.mu_static_long.value_or(tall.mu_static_long),
                                        opts.mu_static_short.value_or(tall.mu_static_short), long_axis);
  info.contact.at_nodes = true;  // the bottom corners' placement above is its contact at the surface
  for (int n : model.body(info.body).nodes)
    if (info.to_local(model.node(n).X).z() <= z0 + detail::wire_tolerance) info.bottom_nodes.push_back(n);
  info.long_axis_nodes = detail::longest_line_along(model, info, long_axis);
  info.markers.push_back(Marker{"cog", info.body, hub, Vec3(0, 0, h)});
  info.calibration.target_mass = M;
  info.calibration.mass = model.body_mass(info.body);
  info.calibration.target_cog = Vec3(0, 0, h);
  info.calibration.cog = info.to_local(model.body_centre_of_gravity(info.body));
  return info;
}

struct BlockKind : ItemKindDefaults {
  static constexpr std::string_view name = "block";
  static constexpr std::string_view meaning =
      "solid uniform box, rigid only (fidelity \"rigid\" or \"auto\"): its mass, centre of gravity and inertia "
      "tensor are the solid's; `mass_kg` required, `cog_h` on its vertical axis (default H/2), no `cog_d1`";
  static std::vector<ItemParameter> parameters() {
    const auto& tall = paper_item(PaperItem::tall_cabinet);
    return generic_box_parameters({0.4, 0.4, 0.4}, tall.mu_static_long, tall.mu_static_short);
  }
  static Vec3 size(const ItemValues& v) { return generic_box_size(v); }
  static std::vector<ItemInfo> build(Model& model, const Placement& at, const ItemValues& v, const BuildOptions& o) {
    return {build_block(model, at, v["width"], v["depth"], v["height"], with_static_friction(o, v))};
  }
};

}  // namespace furniture_fem
