// A contact law registered by the test program itself (register_contact_law; issue 48): a cubic spring
// with a parameter of its own (k3), composed with the paper's damping and friction
// (tests/support/cubic_law.hpp). Its name and its key go through the reader, the writer and validation
// as a built-in law's do; every key it declares changes its force; any other key, a law registered twice
// or under a built-in's name is an error naming it; a block rests where the cubic spring carries its
// weight. Its checkpoint and resume: tests/scene/test_resume.cpp (variant 5).
#include <catch2/catch.hpp>

#include <furniture_fem/scene/reader.hpp>
#include <furniture_fem/scene/scene_runner.hpp>

#include "../support/block_scene.hpp"
#include "../support/cubic_law.hpp"
#include "../support/floor_probes.hpp"
#include "../support/input_errors.hpp"

#include <cmath>
#include <map>
#include <string>
#include <vector>

using namespace furniture_fem;
using nlohmann::json;
using Catch::Matchers::Contains;
using ffem_test::cubic_law;
using ffem_test::input_error;

namespace registered_law_tests {  // this file's own names (its group compiles files in batches)

namespace {

// The rigid 20 kg block at rest under the cubic law; `floor` its floor overrides.
json cubic_scene(const json& floor = json::object()) {
  json j = ffem_test::block_scene({{"source", "points"}, {"x", {{0.0, 0.0}, {1.0, 0.0}}}}, 0.2);
  j["contact"] = {{"law", "cubic"}, {"floor", floor}};
  return j;
}

SceneSpec parsed(const json& j) {
  cubic_law();  // registered before its name is read
  return parse_scene_json(j, "cubic.json");
}

// The floor parameters the scene gives its item.
ContactParams floor_params(const SceneSpec& s) {
  Model model;
  const auto items = build_scene(s, model);
  return scene_body_contacts(s, model, items).at(items.at(0).body).floor;
}

// The law's force on a node 0.1 mm into the floor (ffem_test::floor_probes), through its registered kernel.
std::vector<Vec3> floor_forces(const ContactParams& p) {
  std::vector<Vec3> out;
  for (const ContactKinematics& k : ffem_test::floor_probes(1e-4)) {
    ContactState state;
    out.push_back(scene_law(cubic_law()).kernel->force(k, p, state).on_a);
  }
  return out;
}

// A record whose name is a built-in law's.
struct PaperNamedLaw : ffem_test::CubicSceneLaw {
  static constexpr std::string_view name = "paper";
};

// The sink of every bottom node of the scene's item below its place at t = 0, at the run's end.
class BottomSink : public RunObserver {
 public:
  void end(const RunView& run, RunSummary&) override {
    for (int n : run.items.at(0).bottom_nodes) sinks.push_back(run.model.node(n).X.z() - run.sim.position(n).z());
    nodes = static_cast<int>(run.items.at(0).bottom_nodes.size());
    mass = run.model.body_mass(run.items.at(0).body);
  }
  std::vector<double> sinks;
  int nodes = 0;
  double mass = 0;
};

}  // namespace

TEST_CASE("a registered law goes through the reader, the writer and validation", "[scene][laws][registered]") {
  const SceneSpec s = parsed(cubic_scene({{"k3", 2e13}, {"mu", 0.3}}));
  CHECK(s.contact.law == cubic_law());
  CHECK(scene_law(s.contact.law).name == "cubic");
  CHECK(s.contact.floor.values.at("k3") == 2e13);
  const json written = to_json(s);
  CHECK(written["contact"]["law"] == "cubic");
  CHECK(written["contact"]["floor"]["k3"] == 2e13);
  CHECK(to_json(parse_scene_json(written, "cubic.json")) == written);
  CHECK_NOTHROW(validate(s));
  // The value reaches the law's slot; an item's default is the declared one.
  CHECK(floor_params(s).law_params[ffem_test::CubicSpring::k3] == 2e13);
  CHECK(floor_params(parsed(cubic_scene())).law_params[ffem_test::CubicSpring::k3] == 1e13);
  // Its table: the built-in laws' rows, and its own key marked for it alone.
  const std::string table = contact_law_table(contact_law_registry());
  CHECK_THAT(table, Contains("| `k3` | N/m^3 | (0, 1e+20] | | | | | | | yes | the cubic spring"));
  // An unknown law lists the registered ones, this one among them.
  json quartic = cubic_scene();
  quartic["contact"]["law"] = "quartic";
  CHECK_THAT(input_error([&] { parsed(quartic); }),
             Contains("contact.law") && Contains("\"quartic\"") && Contains("stiff, cubic"));
}

TEST_CASE("a registered law's keys: out of range, undeclared or another law's are errors naming the key and the law",
          "[scene][laws][registered]") {
  CHECK_THAT(input_error([] { parsed(cubic_scene({{"k3", -1.0}})); }),
             Contains("contact.floor.k3") && Contains("(0, 1e+20]") && Contains("-1") && Contains("\"cubic\""));
  for (const char* key : {"alpha_kgf", "stiffness", "damping", "mu_short"}) {
    INFO(key);
    CHECK_THAT(input_error([&] { parsed(cubic_scene({{key, 1.0}})); }),
               Contains(std::string("contact.floor.") + key) && Contains("not used by the contact law \"cubic\""));
  }
  CHECK_THAT(input_error([] { parsed(cubic_scene({{"k4", 1.0}})); }),
             Contains("contact.floor.k4") && Contains("contact law \"cubic\""));
  // Its key under another law.
  json paper = cubic_scene({{"k3", 1e13}});
  paper["contact"]["law"] = "paper";
  CHECK_THAT(input_error([&] { parsed(paper); }),
             Contains("contact.floor.k3") && Contains("not used by the contact law \"paper\""));
  // A spec made in code: validate() checks the law's own values as the reader does.
  SceneSpec s = parsed(cubic_scene());
  s.contact.wall.values["k3"] = 0.0;
  CHECK_THAT(input_error([&] { validate(s); }), Contains("contact.wall.k3") && Contains("\"cubic\"") && Contains("got 0"));
  s.contact.wall.values = {{"k9", 1.0}};
  CHECK_THAT(input_error([&] { validate(s); }), Contains("contact.wall.k9") && Contains("not used by the contact law \"cubic\""));
}

TEST_CASE("a law registered twice, or under a built-in's name, is an error naming it", "[scene][laws][registered]") {
  cubic_law();
  CHECK_THROWS_WITH(register_contact_law<ffem_test::CubicSceneLaw>(),
                    Contains("contact law \"cubic\"") && Contains("already registered"));
  CHECK_THROWS_WITH(register_contact_law<PaperNamedLaw>(), Contains("contact law \"paper\"") && Contains("built-in"));
  CHECK(contact_law_registry().size() == builtin_contact_laws::size + 1);
}

TEST_CASE("every key a registered law declares changes its force", "[scene][laws][registered]") {
  const std::map<std::string, double> values{{"dc_kgf", 77.0}, {"q", 1.5}, {"mu", 0.123}, {"mu_long", 0.234}, {"k3", 3e13}};
  const SceneLawInfo& law = scene_law(cubic_law());
  const auto base = floor_forces(floor_params(parsed(cubic_scene())));
  // Its parts' keys (the paper's damping and friction) and its own, through the same declarations.
  std::vector<std::string> keys;
  for (const auto& p : law.parameters) keys.emplace_back(p.key);
  REQUIRE(keys.size() == values.size());
  for (const std::string& key : keys) {
    INFO("key " << key);
    const auto changed = floor_forces(floor_params(parsed(cubic_scene({{key, values.at(key)}}))));
    CHECK((changed[0] != base[0] || changed[1] != base[1]));
  }
  // The spring alone, approaching: k3 d^3 along z, d = 0.1 mm (the damping acts against the approach).
  const ContactParams p = floor_params(parsed(cubic_scene({{"dc_kgf", 0.0}})));
  CHECK(floor_forces(p)[0].z() == Approx(1e13 * 1e-12).epsilon(1e-9));
  // Two items in contact take the mean; a support point standing for n nodes, n times (per_node).
  ContactParams other = p;
  other.law_params[0] = 3e13;
  CHECK(ContactParams::pair(p, other).law_params[0] == 2e13);
  CHECK(p.law_params_per_node == 1u);
}

TEST_CASE("a block rests where the registered law's cubic spring carries its weight", "[scene][laws][registered]") {
  // Settled first (contact.start "settled": at rest within 1e-5 m/s), then 0.2 s at rest: every bottom
  // node sinks d with n k3 d^3 = m g, n the bottom nodes (the rigid block's support points carry their
  // shares of them; the shares sum to n). At 1e-5 m/s the residual swing is v / omega ~ 2e-8 m of d ~ 1e-4 m.
  json j = cubic_scene({{"k3", 1e13}});
  j["contact"]["start"] = "settled";
  RunOptions o;
  o.write_files = false;
  o.progress = false;
  BottomSink sink;
  const RunSummary r = run_scene(parsed(j), o, {&sink});
  REQUIRE(r.status == "completed");
  REQUIRE(sink.nodes > 0);
  const double expected = std::cbrt(sink.mass * 9.80665 / (sink.nodes * 1e13));
  INFO(sink.nodes << " bottom nodes, expected sink " << expected << " m");
  for (double d : sink.sinks) CHECK(d == Approx(expected).epsilon(1e-3));
}

namespace {
// A part that declares a slot of its own (a spring in law_params[0]) and a record that adds a parameter no
// part reads: the record's goes to the slot after its parts'.
struct SlotSpring {
  static constexpr std::array parameters{
      LawParameter{.key = "k_slot", .unit = "N/m", .lo = 0, .hi = 1e9, .lo_exclusive = true, .default_value = 2e5,
                   .meaning = "a linear spring in slot 0", .per_node = true, .slot = 0}};
  double force(const ContactKinematics& k, const ContactParams& p, double, double) const {
    return p.law_params[0] * (k.L - k.l);
  }
};
struct SlotSceneLaw : SceneLawDefaults {
  static constexpr std::string_view name = "slot_spring";
  using law = ContactLaw<SlotSpring, NoDamping, RegularisedCoulomb>;
  static constexpr std::array<LawParameter, 1> own_parameters{
      {{.key = "extra", .unit = "-", .lo = 0, .hi = 1, .default_value = 0.5, .meaning = "read by no part"}}};
};
constexpr LawParameter unused_parameter(std::string_view key) {
  return {.key = key, .unit = "-", .lo = 0, .hi = 1, .meaning = "unused"};
}
struct CrowdedSceneLaw : SlotSceneLaw {  // 1 part slot and 4 own: one more than ContactParams holds
  static constexpr std::array<LawParameter, 4> own_parameters{unused_parameter("a"), unused_parameter("b"),
                                                              unused_parameter("c"), unused_parameter("d")};
};
}  // namespace

// A part's own parameter and a record's go through the same declarations: the scene keys, the slots'
// defaults, the overrides, the share scaling (the part's per_node slot in the kernel's mask).
TEST_CASE("a part's own parameter and a record's share one mechanism", "[scene][laws][registered]") {
  const SceneLawInfo law = SceneLawInfo::of<SlotSceneLaw>();
  std::vector<std::string_view> keys;
  for (const auto& p : law.parameters) keys.push_back(p.key);
  CHECK(keys == std::vector<std::string_view>{"k_slot", "mu", "mu_long", "extra"});
  CHECK(law.parameter("k_slot")->slot == 0);
  CHECK(law.parameter("extra")->slot == 1);
  ContactParams p;
  law.set_slot_defaults(p);
  CHECK(p.law_params[0] == 2e5);
  CHECK(p.law_params[1] == 0.5);
  CHECK(p.law_params_per_node == 1u);
  law.apply(p, ContactOverrides{{{"k_slot", 3e5}, {"extra", 0.25}, {"mu", 0.4}}});
  CHECK(p.law_params[0] == 3e5);
  CHECK(p.law_params[1] == 0.25);
  CHECK(p.mu == 0.4);
  const unsigned mask = law.kernel->per_node_mask();
  CHECK(mask == 1u << ContactParams::named_fields().size());
  p.scale_per_node(4.0, mask);
  CHECK(p.law_params[0] == 12e5);
  CHECK(p.law_params[1] == 0.25);
  CHECK(p.mu == 0.4);
  CHECK_THROWS_WITH(SceneLawInfo::of<CrowdedSceneLaw>(),
                    Contains("contact law \"slot_spring\"") && Contains("more than 4 parameters of its own"));
}

}  // namespace registered_law_tests
