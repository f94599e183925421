// Item kinds as types: a kind registered from C++ is read, validated and built like the built-in ones,
// its declared ranges and defaults hold, and docs/scene/scene_file.md shows the generated parameter tables.
#include <catch2/catch.hpp>

#include <furniture_fem/scene/scene.hpp>

#include "../support/test_files.hpp"

#include <string>

using namespace furniture_fem;
using nlohmann::json;
using Catch::Matchers::Contains;

namespace item_kinds_tests {  // this file's own names (its group compiles files in batches)

namespace {

// A refrigerator, built as a closed locker of its own size.
struct TestFridgeKind : ItemKindDefaults {
  static constexpr std::string_view name = "test_fridge";
  static constexpr std::string_view meaning = "a refrigerator, built as a closed locker";
  static std::vector<ItemParameter> parameters() {
    return {{"width", "m", 0.4, 1.2, false, 0.6, "outer width"},
            {"depth", "m", 0.4, 1.0, false, 0.65, "outer depth"},
            {"height", "m", 0.5, 2.5, false, 1.6, "outer height"}};
  }
  static Vec3 size(const ItemValues& v) { return {v["width"], v["depth"], v["height"]}; }
  static std::vector<ItemInfo> build(Model& model, const Placement& at, const ItemValues& v, const BuildOptions& o) {
    return {build_locker(model, at, v["width"], v["depth"], v["height"], o)};
  }
};

void register_test_fridge() {
  if (!item_kind_registry().find(TestFridgeKind::name)) register_item_kind<TestFridgeKind>();
}

json fridge_scene(const json& params = json::object()) {
  json item = {{"kind", "test_fridge"}, {"name", "fridge"}, {"x", 0.0}, {"y", 0.0}};
  if (!params.empty()) item["params"] = params;
  return {{"items", json::array({item})}};
}

std::string parse_error(const json& j) {
  try {
    const SceneSpec s = parse_scene_json(j, "kinds.json");
    validate(s);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace

TEST_CASE("a kind registered from C++ is read, validated and built", "[scene][kinds]") {
  register_test_fridge();
  CHECK_THROWS_AS(register_item_kind<TestFridgeKind>(), ModelError);  // one kind per name

  const SceneSpec scene = parse_scene_json(fridge_scene(), "kinds.json");
  REQUIRE(scene.items.size() == 1);
  CHECK(scene.items[0].kind == ItemKind(TestFridgeKind::name));
  CHECK(item_kind_from_string("test_fridge") == ItemKind(TestFridgeKind::name));
  CHECK_NOTHROW(validate(scene));
  Model model;
  const auto items = build_scene(scene, model);
  REQUIRE(items.size() == 1);
  CHECK(items[0].kind == ItemKind(TestFridgeKind::name));
  CHECK(items[0].size.isApprox(Vec3(0.6, 0.65, 1.6)));
  CHECK(model.num_bodies() == 1);

  // Round trip: the kind's values are written and read back.
  const SceneSpec sized = parse_scene_json(fridge_scene({{"height", 1.8}, {"mass_kg", 70}}), "kinds.json");
  CHECK(to_json(parse_scene_json(to_json(sized), "again")) == to_json(sized));
  CHECK(to_json(sized)["items"][0]["params"]["height"] == 1.8);
}

TEST_CASE("a kind's parameter ranges and keys give named errors", "[scene][kinds]") {
  register_test_fridge();
  const std::string too_tall = parse_error(fridge_scene({{"height", 3.0}}));
  CHECK_THAT(too_tall, Contains("kinds.json") && Contains("items[0].params.height") && Contains("[0.5, 2.5]") &&
                           Contains("got 3"));
  const std::string shelves = parse_error(fridge_scene({{"shelves", 2}}));
  CHECK_THAT(shelves, Contains("items[0].params.shelves") && Contains("not a parameter of kind \"test_fridge\"") &&
                          Contains("height"));
  CHECK_THAT(parse_error(fridge_scene({{"height", "tall"}})), Contains("items[0].params.height") && Contains("\"tall\""));

  // A scene made in C++ is checked by validate() instead.
  SceneSpec scene = parse_scene_json(fridge_scene(), "kinds.json");
  scene.items[0].params.kind_values["height"] = 0.2;
  try {
    validate(scene);
    FAIL("validate accepted a height below the kind's range");
  } catch (const InputError& e) {
    CHECK_THAT(std::string(e.what()), Contains("items[0].params.height") && Contains("0.2"));
  }
  scene.items[0].kind = ItemKind("wardrobe");
  try {
    validate(scene);
    FAIL("validate accepted an unregistered kind");
  } catch (const InputError& e) {
    CHECK_THAT(std::string(e.what()), Contains("items[0].kind") && Contains("wardrobe") && Contains("test_fridge"));
  }
}

TEST_CASE("a kind's declared default is what is built when the key is absent", "[scene][kinds]") {
  register_test_fridge();
  const auto built_height = [](const json& params) {
    Model model;
    return build_scene(parse_scene_json(fridge_scene(params), "kinds.json"), model).at(0).size.z();
  };
  CHECK(built_height(json::object()) == 1.6);
  CHECK(built_height({{"height", 1.2}}) == 1.2);

  // A built-in kind: the bookshelf's shelves default to 4 and a given count changes the mesh.
  const auto elements = [](const json& params) {
    json item = {{"kind", "bookshelf"}, {"x", 0.0}, {"y", 0.0}};
    if (!params.empty()) item["params"] = params;
    Model model;
    build_scene(parse_scene_json({{"items", json::array({item})}}, "kinds.json"), model);
    return model.elements().size();
  };
  CHECK(elements(json::object()) == elements({{"shelves", 4}}));
  CHECK(elements({{"shelves", 2}}) < elements(json::object()));
  CHECK(to_json(parse_scene_json(fridge_scene(), "kinds.json"))["items"][0].count("params") == 0);
}

TEST_CASE("the item parameter tables of docs/scene/scene_file.md are the generated ones", "[scene][kinds][docs]") {
  const auto in_docs = ffem_test::docs_block("scene/scene_file.md", "item_parameter_tables()");
  REQUIRE(in_docs);
  INFO("regenerate the block in docs/scene/scene_file.md from item_parameter_tables()");
  CHECK(*in_docs == "\n" + item_parameter_tables() + "\n");
  // Registered kinds of users do not enter the docs table.
  register_test_fridge();
  CHECK(item_parameter_tables().find("test_fridge") == std::string::npos);
  CHECK(item_parameter_tables(item_kind_registry()).find("test_fridge") != std::string::npos);
}

}  // namespace item_kinds_tests
