// The block kind (furniture/kinds/block.hpp): the body has the solid box's mass, centre of gravity and
// inertia tensor about it (closed form M/12 diag(D^2 + H^2, W^2 + H^2, W^2 + D^2), turned with the
// placement's yaw), its bottom nodes sit at floor-contact onset, and options a rigid block cannot take
// are named errors.
#include <catch2/catch.hpp>

#include <furniture_fem/furniture/item_kinds.hpp>

#include <cmath>
#include <string>

using namespace furniture_fem;

namespace block_tests {  // this file's own names (its group compiles files in batches)

namespace {

BuildOptions block_options(double mass, std::optional<double> cog_h = std::nullopt) {
  BuildOptions o;
  o.name = "crate";
  o.fidelity = Fidelity::rigid;
  o.mass_kg = mass;
  o.cog_h = cog_h;
  return o;
}

std::string build_error(const BuildOptions& o, double W = 0.6, double D = 0.4, double H = 0.8) {
  Model model;
  try {
    build_block(model, {}, W, D, H, o);
  } catch (const ModelError& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

TEST_CASE("a block has the solid box's mass, centre of gravity and inertia tensor", "[furniture][block]") {
  // Closed form for W 0.6, D 0.4, H 0.8, M 25 kg: Ixx = M (D^2 + H^2)/12 = 1.6667, Iyy = 2.0833,
  // Izz = 1.0833 kg m^2, about the centre of gravity, in the item's axes. The hub's inertia is what the
  // frame leaves, computed by subtraction: exact up to round-off, bound 1e-10 relative. The centre of
  // gravity comes from a fixed-point iteration that converges to round-off: bound 1e-12 m.
  const double W = 0.6, D = 0.4, H = 0.8, M = 25.0;
  for (const auto cog_h : {std::optional<double>{}, std::optional<double>{0.3}}) {
    Model model;
    const Placement at = Placement::at(0.5, -0.3, 30.0);
    const ItemInfo info = build_block(model, at, W, D, H, block_options(M, cog_h));
    const double h = cog_h.value_or(0.5 * H);
    INFO("cog_h " << h);
    CHECK(model.body_mass(info.body) == Approx(M).epsilon(1e-12));
    const Vec3 cog = model.body_centre_of_gravity(info.body);
    CHECK((cog - info.to_world({0, 0, h})).norm() < 1e-12);
    const Mat3 I_local = info.R.transpose() * model.body_inertia(info.body, cog) * info.R;
    const Mat3 expected = (M / 12.0 * Vec3(D * D + H * H, W * W + H * H, W * W + D * D)).asDiagonal();
    INFO("inertia in item axes:\n" << I_local);
    CHECK((I_local - expected).norm() < 1e-10 * expected.norm());
    // The marker "cog" is the hub, on the vertical axis near the centre of gravity (the hub balances
    // the spokes, which put 0.2 % of the mass low: it sits within 1 % of H of it).
    const Marker* marker = info.marker("cog");
    REQUIRE(marker);
    const Vec3 hub = info.to_local(model.node(marker->node).X);
    CHECK(hub.head<2>().norm() < 1e-12);
    CHECK(std::abs(hub.z() - h) < 0.01 * H);
    CHECK(info.fidelity == Fidelity::rigid);
    CHECK(info.contact.alpha == Approx(M * newtons_per_kgf));
  }
}

TEST_CASE("a block's bottom nodes sit at floor-contact onset, on the lines from its centre of gravity to its edges",
          "[furniture][block]") {
  // Floor contact acts within half the member width of a node (5 mm for the 10 mm edge tubes): the
  // bottom centre lines at z = 5 mm put the box's bottom face on the floor. The top corners sit 5 mm
  // inside the faces; the bottom corners where the lines from the centre of gravity (0, 0, h) to the
  // box's bottom edges (+-W/2, +-D/2, 0) reach z = 5 mm, so that the pivots' lever arms have the box's
  // ratio b/h (the tipping threshold: tests/scene "a block tips at g b/h"). Exact geometry: 1e-12 m.
  for (const auto cog_h : {std::optional<double>{}, std::optional<double>{0.15}}) {
    const double W = 0.5, D = 0.3, H = 0.4, c = 0.005, h = cog_h.value_or(0.5 * H);
    Model model;
    const ItemInfo info = build_block(model, {}, W, D, H, block_options(10.0, cog_h));
    INFO("cog_h " << h);
    double zmin = 1e9;
    Vec3 lo = Vec3::Constant(1e9), hi = Vec3::Constant(-1e9);
    for (int n : model.body(info.body).nodes) {
      zmin = std::min(zmin, model.node(n).X.z());
      if (model.node(n).X.z() > H - c - 1e-9) {
        lo = lo.cwiseMin(model.node(n).X);
        hi = hi.cwiseMax(model.node(n).X);
      }
    }
    CHECK(zmin == Approx(c).epsilon(1e-12));
    CHECK((hi - lo - Vec3(W - 2 * c, D - 2 * c, 0)).norm() < 1e-12);  // the top face's corners
    REQUIRE(info.bottom_nodes.size() >= 4);
    int corners = 0;
    for (int n : info.bottom_nodes) {
      const Vec3 X = model.node(n).X;
      CHECK(X.z() == Approx(c).epsilon(1e-12));
      // Corner: on the line from (0, 0, h) to (+-W/2, +-D/2, 0) at height c.
      const double s = (h - c) / h;
      if (std::abs(std::abs(X.x()) - 0.5 * W * s) < 1e-12 && std::abs(std::abs(X.y()) - 0.5 * D * s) < 1e-12) ++corners;
      CHECK(std::abs(X.x()) <= 0.5 * W * s + 1e-12);
      CHECK(std::abs(X.y()) <= 0.5 * D * s + 1e-12);
    }
    CHECK(corners == 4);
    for (int e : model.body(info.body).elements) CHECK(0.5 * model.section_of(e).contact_width() == Approx(c));
  }
}

TEST_CASE("a block refuses what a rigid solid box cannot take, naming the item", "[furniture][block]") {
  BuildOptions o = block_options(10.0);
  o.fidelity = Fidelity::full;
  CHECK_THAT(build_error(o), Catch::Contains("block 'crate'") && Catch::Contains("fidelity \"full\""));
  o.fidelity = Fidelity::coarse;
  CHECK_THAT(build_error(o), Catch::Contains("fidelity \"coarse\""));
  o.fidelity = Fidelity::automatic;
  CHECK(build_error(o) == "no error");
  o = block_options(10.0);
  o.mass_kg.reset();
  CHECK_THAT(build_error(o), Catch::Contains("block 'crate'") && Catch::Contains("mass_kg is required"));
  o = block_options(10.0);
  o.cog_d1 = 0.1;
  CHECK_THAT(build_error(o), Catch::Contains("cog_d1 does not apply"));
  o = block_options(10.0);
  o.panel_spacing = 0.1;
  CHECK_THAT(build_error(o), Catch::Contains("panel_spacing and grid_scale do not apply"));
  CHECK_THAT(build_error(block_options(10.0, 0.002)), Catch::Contains("cog_h must lie within the frame") &&
                                                          Catch::Contains("got 0.002"));
  // The bottom corners close in by c/h: below h = 2c = 10 mm the base would shrink past half the box.
  CHECK_THAT(build_error(block_options(10.0, 0.009)), Catch::Contains("[0.01, "));
  CHECK(build_error(block_options(10.0, 0.01)) == "no error");
  CHECK_THAT(build_error(block_options(-1.0)), Catch::Contains("mass_kg must be positive"));
}

TEST_CASE("the block kind is registered and builds from its parameters", "[furniture][block][kinds]") {
  const ItemKindRegistry registry = builtin_item_kind_registry();
  const ItemKindEntry& kind = registry.at(ItemKind::block);
  Model model;
  BuildOptions o = block_options(12.0);
  const auto infos = kind.build(model, {}, kind.values({{"width", 0.3}, {"height", 0.9}}), o);
  REQUIRE(infos.size() == 1);
  CHECK(infos[0].size == Vec3(0.3, 0.4, 0.9));
  CHECK(model.body_mass(infos[0].body) == Approx(12.0).epsilon(1e-12));
  CHECK(item_kind_from_string("block") == ItemKind::block);
}

}  // namespace block_tests
