// The built-in scene contact laws, walked from their one list (scene/laws/law_list.hpp): every law's name through
// the reader and the writer, every key it declares accepted and felt in its force, every key it does not
// declare a named error, and docs/scene/scene_file.md's key table the generated one, its law row complete.
#include <catch2/catch.hpp>

#include <furniture_fem/scene/scene.hpp>
#include <furniture_fem/scene/scene_simulation.hpp>

#include "../support/floor_probes.hpp"
#include "../support/input_errors.hpp"
#include "../support/test_files.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <string>

using namespace furniture_fem;
using nlohmann::json;
using Catch::Matchers::Contains;
using ffem_test::input_error;

namespace contact_laws_tests {  // this file's own names (its group compiles files in batches)

namespace {

// One side table; `contact` as given.
json law_scene(const json& contact) {
  return {{"items", json::array({{{"kind", "side_table"}}})}, {"contact", contact}, {"solver", "direct"}};
}

// A value in each key's range, away from the defaults (small enough for stick_slip to stick at the slow speed);
// every key a built-in law declares has one (checked).
const std::map<std::string_view, double> key_values{{"alpha_kgf", 123.0}, {"dc_kgf", 77.0},      {"q", 1.5},
                                                    {"mu", 0.123},        {"mu_long", 0.234},    {"mu_short", 0.05},
                                                    {"stiffness", 3.3e3}, {"damping", 4.5}};

// The floor parameters the scene gives its item.
ContactParams floor_params(const SceneSpec& s) {
  Model model;
  const auto items = build_scene(s, model);
  return scene_body_contacts(s, model, items).at(items.at(0).body).floor;
}

// The law's force on a node 5 mm into the floor (ffem_test::floor_probes).
template <class Law>
std::vector<Vec3> floor_forces(const ContactParams& p) {
  std::vector<Vec3> out;
  for (const ContactKinematics& k : ffem_test::floor_probes(0.005)) {
    ContactState state;
    out.push_back(Law{}.force(k, p, state).on_a);
  }
  return out;
}

// The record of docs/contact/contact.md, "Adding a contact law", is one: its parts declare its keys. A record
// with a hand-kept key list is not, nor one whose own key is one of its parts'.
struct CubicPenalty {
  double force(const ContactKinematics&, const ContactParams& p, double g, double) const { return p.alpha * g * g * g; }
};
struct CubicSceneLaw : SceneLawDefaults {
  static constexpr std::string_view name = "cubic";
  using law = ContactLaw<CubicPenalty, PaperSignDamping, PaperSignFriction>;
};
struct HandListedSceneLaw : CubicSceneLaw {
  static constexpr std::array<std::string_view, 1> parameters{"alpha_kgf"};
};
struct OwnQSceneLaw : CubicSceneLaw {
  static constexpr std::array<LawParameter, 1> own_parameters{{{.key = "q", .unit = "-", .lo = 0, .hi = 1, .meaning = "a second q"}}};
};
static_assert(SceneContactLaw<CubicSceneLaw>);
static_assert(!SceneContactLaw<HandListedSceneLaw>);
static_assert(!SceneContactLaw<OwnQSceneLaw>);
// Its keys are its parts': the damping's dc_kgf and q, the friction's mu and mu_long (CubicPenalty declares none).
static_assert(contact_law_parameters<CubicSceneLaw::law>.size() == 4);

// Every key any built-in law declares, and the rule keys.
std::vector<std::string_view> all_keys() {
  const ContactLawRegistry builtin = builtin_contact_law_registry();
  std::vector<std::string_view> keys;  // views of the declarations, which are static
  for (const auto& law : builtin.laws())
    for (const auto& p : law.kernel->parameters())
      if (std::find(keys.begin(), keys.end(), p.key) == keys.end()) keys.push_back(p.key);
  return keys;
}

template <class F>
void for_each_law(F&& f) {
  [&]<class... R>(LawList<R...>) { (f.template operator()<R>(), ...); }(builtin_contact_laws{});
}

}  // namespace

TEST_CASE("every contact law's name goes through the reader and the writer", "[scene][laws]") {
  for_each_law([]<class R>() {
    const std::string name(R::name);
    INFO("law " << name);
    const SceneSpec s = parse_scene_json(law_scene({{"law", name}}), "laws.json");
    CHECK(s.contact.law == law_kind<R>);
    CHECK(scene_law(s.contact.law).name == R::name);
    const json written = to_json(s);
    CHECK(written["contact"]["law"] == name);
    CHECK(to_json(parse_scene_json(written, "laws.json")) == written);
    // The law's default applies to a scene file and to a spec built in C++ alike (nothing set): every
    // item inside the step unless the law says otherwise (issue 52).
    const ImplicitContact expected = R::default_implicit.value_or(ImplicitContact::all);
    CHECK(implicit_contact(s.contact) == expected);
    SceneSpec in_cpp;
    in_cpp.contact.law = law_kind<R>;
    CHECK(implicit_contact(in_cpp.contact) == expected);
    CHECK(to_json(in_cpp)["contact"]["implicit"] == json_io::enum_name(detail::implicit_contact_names, expected));
    // stick_length is written and read only for laws that use it.
    CHECK(written["contact"].contains("stick_length") == R::own_stick_spring.empty());
    const std::string stick =
        input_error([&] { parse_scene_json(law_scene({{"law", name}, {"stick_length", 1e-4}}), "laws.json"); });
    CHECK((stick == "no error") == R::own_stick_spring.empty());
    // Either linear solver with every law (the law is a kernel of the one scene simulation).
    json cg = law_scene({{"law", name}});
    cg["solver"] = "cg";
    CHECK(parse_scene_json(cg, "laws.json").solver == SolverKind::cg);
  });
  CHECK_THAT(input_error([] { parse_scene_json(law_scene({{"law", "coulomb"}}), "laws.json"); }),
             Contains("expected one of: paper, paper_anisotropic, spring_dashpot, hunt_crossley, stick_slip, stiff"));
}

// CG was built for the paper's two laws only while each law and solver was its own instantiation of the
// simulation (issue 48). Now every law runs with either solver: the direct solver refactorised every step
// and CG (relative residual 1e-10 a solve) step the side table under the synthetic motion to the same
// node positions, to a hundred-millionth of how far the nodes moved, after 0.3 s.
TEST_CASE("every contact law runs with either linear solver, to the same motion", "[scene][laws][solvers]") {
  for_each_law([]<class R>() {
    const std::string name(R::name);
    INFO("law " << name);
    SceneSpec s = parse_scene_json(law_scene({{"law", name}}), "laws.json");
    SceneSimulation<DirectLdltSolver> direct(s, 1, 1);
    s.solver = SolverKind::cg;
    SceneSimulation<ConjugateGradientSolver> cg(s, 1, 1);
    for (int i = 0; i < 300; ++i) {
      direct.sim->step();
      cg.sim->step();
    }
    double apart = 0, moved = 0;
    for (int n = 0; n < direct.model->num_nodes(); ++n) {
      apart = std::max(apart, (direct.sim->position(n) - cg.sim->position(n)).norm());
      moved = std::max(moved, (direct.sim->position(n) - direct.model->node(n).X).norm());
    }
    INFO("largest node displacement " << moved << " m, largest difference " << apart << " m");
    // Moved: 7 to 18 mm, and 4.6 um under `stiff` (the item holds: its elastic deformation only);
    // apart: 8e-11 of that at most (2026-12-06). CG stops at a relative residual of 1e-10 a step.
    CHECK(moved > 1e-6);
    CHECK(apart < 1e-8 * moved);
  });
}

// Generated from the declarations: each key a law's parts declare, given on the floor, reaches each field
// it names as the declaration stores it (kgf in N: 9.80665 times; Hunt-Crossley's stiffness over
// sqrt(0.025 m)) and changes the force on a node 5 mm into the floor.
TEST_CASE("every key a contact law declares is read and changes its force", "[scene][laws]") {
  for (std::string_view key : all_keys()) REQUIRE(key_values.count(key) == 1);
  for_each_law([]<class R>() {
    const std::string name(R::name);
    const SceneLawInfo& law = scene_law(law_kind<R>);
    const auto base = floor_forces<typename R::law>(floor_params(parse_scene_json(law_scene({{"law", name}}), "laws.json")));
    REQUIRE(!law.parameters.empty());
    for (const LawParameter& declared : law.parameters) {
      const std::string key(declared.key);
      INFO("law " << name << ", key " << key);
      const double value = key_values.at(key);
      const SceneSpec s = parse_scene_json(law_scene({{"law", name}, {"floor", {{key, value}}}}), "laws.json");
      CHECK(s.contact.floor.values.at(key) == value);
      const ContactParams p = floor_params(s);
      CHECK(p.value(declared) == declared.stored(value));
      const auto changed = floor_forces<typename R::law>(p);
      CHECK((changed[0] != base[0] || changed[1] != base[1]));
    }
  });
  // The stored forms, against their closed forms.
  CHECK(part_parameters::alpha_kgf.stored(2.0) == 2.0 * 9.80665);
  CHECK(HuntCrossley::parameters[0].stored(3.3e3) == 3.3e3 / std::sqrt(0.025));
}

// A contact standing for n nodes (a rigid item's support point) takes n times each value a law declares
// per_node, and the others as they are: the paper's alpha and Dc, the springs and dashpots.
TEST_CASE("a contact law's per-node parameters scale with the node share, the others do not", "[scene][laws]") {
  for_each_law([]<class R>() {
    INFO("law " << R::name);
    const SceneLawInfo& law = scene_law(law_kind<R>);
    ContactParams p = floor_params(parse_scene_json(law_scene({{"law", std::string(R::name)}}), "laws.json"));
    p.mu_long = 0.3, p.mu_short = 0.2;  // distinct from mu, so that a mixed-up field shows
    ContactParams scaled = p;
    scaled.scale_per_node(3.0, law.kernel->per_node_mask());
    int per_node = 0;
    for (const LawParameter& d : law.kernel->parameters()) {
      INFO("key " << d.key);
      CHECK(scaled.value(d) == (d.per_node ? 3.0 : 1.0) * p.value(d));
      per_node += d.per_node;
    }
    CHECK(per_node >= 1);
    CHECK(scaled.mu == p.mu);
    CHECK(scaled.v_reg == p.v_reg);
  });
  const unsigned paper = make_contact_law_kernel<PaperLaw>()->per_node_mask();
  CHECK(paper == (ContactParams::storage_bit(part_parameters::alpha_kgf) | ContactParams::storage_bit(part_parameters::dc_kgf)));
}

TEST_CASE("every key a contact law does not declare is an error naming the key and the law", "[scene][laws]") {
  for_each_law([]<class R>() {
    const std::string name(R::name);
    const SceneLawInfo& law = scene_law(law_kind<R>);
    for (std::string_view other : all_keys()) {
      if (law.reads(other)) continue;
      const std::string key(other);
      // A key its item rule sets (stiff's stiffness and damping) says why.
      const std::string expected = "not used by the contact law \"" + name + "\"" + (law.set_by_rule(key) ? ": it sets" : "");
      for (const std::string pair : {"floor", "wall", "item"}) {
        INFO("law " << name << ", " << pair << "." << key);
        const json j = law_scene({{"law", name}, {pair, {{key, key_values.at(key)}}}});
        CHECK_THAT(input_error([&] { parse_scene_json(j, "laws.json"); }),
                   Contains("contact." + pair + "." + key) && Contains(expected));
        // The same given in code, to validate().
        SceneSpec s = parse_scene_json(law_scene({{"law", name}}), "laws.json");
        (pair == "floor" ? s.contact.floor : pair == "wall" ? s.contact.wall : s.contact.item).values[key] = 1.0;
        CHECK_THAT(input_error([&] { validate(s); }), Contains("contact." + pair + "." + key) && Contains(expected));
      }
    }
    // A floor-only key elsewhere.
    for (const LawParameter& p : law.parameters) {
      if (!p.floor_only) continue;
      INFO("law " << name << ", wall." << p.key);
      const json j = law_scene({{"law", name}, {"wall", {{std::string(p.key), 0.1}}}});
      CHECK_THAT(input_error([&] { parse_scene_json(j, "laws.json"); }), Contains("contact.wall." + std::string(p.key)));
    }
    for (std::string_view item_key : R::unused_item_parameters) {
      const std::string key(item_key);
      INFO("law " << name << ", item parameter " << key);
      json j = law_scene({{"law", name}});
      j["items"][0]["params"] = {{key, 1.0}};
      CHECK_THAT(input_error([&] { validate(parse_scene_json(j, "laws.json")); }),
                 Contains("items[0].params." + key) && Contains("not used by contact law \"" + name + "\""));
    }
  });
}

TEST_CASE("the contact key table of docs/scene/scene_file.md is the generated one", "[scene][laws][docs]") {
  const auto in_docs = ffem_test::docs_block("scene/scene_file.md", "contact_law_table()");
  REQUIRE(in_docs);
  INFO("regenerate the block in docs/scene/scene_file.md from contact_law_table()");
  CHECK(*in_docs == "\n" + contact_law_table() + "\n");
  // The `law` row of the contact table names every law.
  const std::string page = ffem_test::docs_page("scene/scene_file.md");
  const auto row = page.find("| `law` | string |");
  REQUIRE(row != std::string::npos);
  const std::string law_row = page.substr(row, page.find('\n', row) - row);
  const ContactLawRegistry builtin = builtin_contact_law_registry();
  for (const auto& law : builtin.laws()) CHECK_THAT(law_row, Contains("`" + std::string(law.name) + "`"));
}

}  // namespace contact_laws_tests
