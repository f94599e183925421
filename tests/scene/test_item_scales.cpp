// The item parameters mass_scale, friction_scale and alpha_scale (what studies perturb) and
// stiffness_scale: each changes the item as built by exactly its factor, and a run sees it.
#include <catch2/catch.hpp>

#include <furniture_fem/core/modal.hpp>
#include <furniture_fem/scene/scene_runner.hpp>

#include <string>

using namespace furniture_fem;
using nlohmann::json;
using Catch::Matchers::Contains;

namespace item_scales_tests {  // this file's own names (its group compiles files in batches)

namespace {

json cabinet_scene(const json& params, const std::string& law = "paper") {
  return {{"name", "scaled cabinet"},
          {"contact", {{"law", law}}},
          {"items", {{{"kind", "tall_cabinet"}, {"name", "cab"}, {"fidelity", "coarse"}, {"params", params}}}},
          {"ground_motion", {{"source", "points"}, {"x", {{0.0, 0.0}, {1.0, 0.0}}}}},
          {"duration", 0.1}};
}

struct Built {
  Model model;
  std::vector<ItemInfo> items;
};
Built build(const json& j) {
  Built b;
  b.items = build_scene(parse_scene_json(j, "scales.json"), b.model);
  return b;
}

}  // namespace

TEST_CASE("mass_scale multiplies the item's mass and keeps its centre of gravity", "[scene][scales]") {
  const Built plain = build(cabinet_scene(json::object()));
  for (double f : {0.8, 1.1, 2.5}) {
    const Built scaled = build(cabinet_scene({{"mass_scale", f}}));
    const int b = scaled.items[0].body;
    CHECK(scaled.model.body_mass(b) == Approx(f * plain.model.body_mass(b)).epsilon(1e-12));
    CHECK((scaled.model.body_centre_of_gravity(b) - plain.model.body_centre_of_gravity(b)).norm() < 1e-12);
    CHECK(scaled.items[0].calibration.mass == Approx(f * plain.items[0].calibration.mass).epsilon(1e-12));
  }
}

TEST_CASE("friction_scale and alpha_scale multiply the item's contact values", "[scene][scales]") {
  const Built plain = build(cabinet_scene(json::object()));
  const Built scaled = build(cabinet_scene({{"friction_scale", 0.9}, {"alpha_scale", 1.3}}));
  const ItemContact &a = plain.items[0].contact, &b = scaled.items[0].contact;
  CHECK(b.mu_floor_long == Approx(0.9 * a.mu_floor_long).epsilon(1e-15));
  CHECK(b.mu_floor_short == Approx(0.9 * a.mu_floor_short).epsilon(1e-15));
  CHECK(b.mu_wall == Approx(0.9 * a.mu_wall).epsilon(1e-15));
  CHECK(b.mu_item == Approx(0.9 * a.mu_item).epsilon(1e-15));
  CHECK(b.alpha == Approx(1.3 * a.alpha).epsilon(1e-15));
  CHECK(b.Dc == a.Dc);  // the damping coefficient is its own parameter
  // A scale applies after a given value: mu_floor_long 0.4 times 0.5.
  const Built both = build(cabinet_scene({{"mu_floor_long", 0.4}, {"friction_scale", 0.5}}));
  CHECK(both.items[0].contact.mu_floor_long == Approx(0.2).epsilon(1e-15));
}

TEST_CASE("the scales round-trip and are range-checked; stiff refuses a penalty", "[scene][scales]") {
  const json j = cabinet_scene({{"mass_scale", 1.2}, {"friction_scale", 0.9}, {"alpha_scale", 2.0}});
  const SceneSpec s = parse_scene_json(j, "scales.json");
  CHECK(to_json(parse_scene_json(to_json(s), "again")) == to_json(s));
  CHECK(*s.items[0].params.mass_scale == 1.2);
  CHECK_THROWS_WITH(parse_scene_json(cabinet_scene({{"mass_scale", 0.0}}), "bad.json"),
                    Contains("items[0].params.mass_scale") && Contains("[0.01, 100]"));
  CHECK_THROWS_WITH(validate(parse_scene_json(cabinet_scene({{"alpha_scale", 2.0}}, "stiff"), "stiff.json")),
                    Contains("items[0].params.alpha_scale") && Contains("not used by contact law \"stiff\""));
}

TEST_CASE("a run sees friction_scale: a block held at 0.25 g slides once its friction is scaled below it",
          "[scene][scales]") {
  // Table acceleration 0.25 g for 0.5 s; mu 0.3 holds the block (0.3 g > 0.25 g); scaled by 0.5
  // (mu 0.15) it slides with relative acceleration (0.25 - 0.15) g: 0.5 * 0.1 g * 0.5^2 = 0.123 m.
  constexpr double g = 9.80665;
  const auto slide = [&](double scale) {
    json j = {{"name", "block"},
              {"items", {{{"kind", "block"}, {"name", "crate"}, {"fidelity", "rigid"},
                          {"params", {{"width", 0.4}, {"depth", 0.4}, {"height", 0.4}, {"mass_kg", 20.0},
                                      {"mu_floor_long", 0.3}, {"mu_floor_short", 0.3}, {"friction_scale", scale}}}}}},
              {"ground_motion", {{"source", "points"}, {"x", {{0.0, 0.25 * g}, {0.5, 0.25 * g}, {0.5001, 0.0}}}}},
              {"contact", {{"law", "stiff"}}},
              {"duration", 0.5}};
    RunOptions o;
    o.write_files = false;
    o.progress = false;
    return run_scene(parse_scene_json(j, "block.json"), o).items.at(0).slide;
  };
  CHECK(slide(1.0) < 1e-4);
  CHECK(slide(0.5) == Approx(0.5 * 0.1 * g * 0.25).epsilon(0.03));  // the onset and the stick spring: ~1 %
}

TEST_CASE("stiffness_scale multiplies the members' moduli: a flexible item's frequencies by its square root",
          "[scene][scales]") {
  // K scales by f (E and G = E / (2 (1 + nu)) both do), the lumped mass not at all: every elastic
  // natural frequency of the free item scales by sqrt(f) (modal_analysis, its rigid-body modes removed).
  // A small locker on a coarse grid (51 nodes), so that the dense eigenproblem is quick.
  const auto locker = [](const json& params, const std::string& fidelity = "coarse") {
    json p = {{"width", 0.5}, {"depth", 0.4}, {"height", 0.8}, {"grid_scale", 5.0}, {"element_length", 0.2}};
    p.update(params);
    return json{{"name", "frame"},
                {"items", {{{"kind", "locker"}, {"name", "crate"}, {"fidelity", fidelity}, {"params", p}}}},
                {"ground_motion", {{"source", "points"}, {"x", {{0.0, 0.0}, {1.0, 0.0}}}}},
                {"duration", 0.1}};
  };
  const auto frequencies = [&](const json& params) {
    SceneSimulation<DirectLdltSolver> scene(parse_scene_json(locker(params), "frame.json"));
    const Model& m = *scene.model;
    for (int e : m.body(scene.items[0].body).elements)
      CHECK(m.material_of(e).E == Approx(206e9 * params.value("stiffness_scale", 1.0)).epsilon(1e-15));
    return modal_analysis(*scene.sim, scene.items[0].body, 6).omega;
  };
  const std::vector<double> plain = frequencies(json::object());
  REQUIRE(plain.size() == 6);
  for (double f : {0.05, 4.0, 100.0}) {
    const std::vector<double> scaled = frequencies({{"stiffness_scale", f}});
    REQUIRE(scaled.size() == 6);
    for (std::size_t i = 0; i < plain.size(); ++i) {
      INFO("mode " << i << " of the frame at " << f << " times its stiffness");
      CHECK(scaled[i] == Approx(std::sqrt(f) * plain[i]).epsilon(1e-9));
    }
  }
  // Read, written back, range-checked; a rigid item, or one `auto` leaves rigid, has nothing to scale.
  const SceneSpec s = parse_scene_json(locker({{"stiffness_scale", 2.5}}), "frame.json");
  CHECK(*s.items[0].params.stiffness_scale == 2.5);
  CHECK(to_json(parse_scene_json(to_json(s), "again")) == to_json(s));
  CHECK_THROWS_WITH(parse_scene_json(locker({{"stiffness_scale", 0.0}}), "bad.json"),
                    Contains("items[0].params.stiffness_scale") && Contains("[0.001, 1000]"));
  for (const std::string fidelity : {"rigid", "auto"})
    CHECK_THROWS_WITH(validate(parse_scene_json(locker({{"stiffness_scale", 2.0}}, fidelity), "rigid.json")),
                      Contains("items[0].params.stiffness_scale") && Contains("no frame stiffness to scale") &&
                          Contains("(got 2)"));
  CHECK_NOTHROW(validate(parse_scene_json(locker({{"stiffness_scale", 2.0}}, "full"), "full.json")));
}

}  // namespace item_scales_tests
