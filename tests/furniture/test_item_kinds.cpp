// Item kinds as types: the built-in list, declared parameters and their defaults, the registry's rules.
#include <catch2/catch.hpp>

#include <furniture_fem/furniture/item_kinds.hpp>

#include <string>

using namespace furniture_fem;

namespace item_kinds_tests {  // this file's own names (its group compiles files in batches)

TEST_CASE("the built-in kinds are registered in order with their parameters", "[furniture][kinds]") {
  const ItemKindRegistry registry = builtin_item_kind_registry();
  CHECK(registry.names() == "tall_cabinet, separated_cabinets, side_table, desk, office_chair, bookshelf, locker, table, block");
  CHECK(registry.at(ItemKind::desk).parameters.empty());
  CHECK_FALSE(registry.at(ItemKind::separated_cabinets).single_body);
  CHECK(registry.at(ItemKind::separated_cabinets).size(ItemValues("separated_cabinets", {})).z() == Approx(1.85));
  const ItemKindEntry& shelf = registry.at(ItemKind::bookshelf);
  REQUIRE(shelf.parameter("shelves"));
  CHECK(shelf.parameter("shelves")->integer);
  CHECK(shelf.values()["shelves"] == 4);                     // declared default
  CHECK(shelf.values({{"shelves", 2}})["shelves"] == 2);     // given value
  CHECK(shelf.size(shelf.values({{"width", 1.1}})).isApprox(Vec3(1.1, 0.3, 1.8)));
  CHECK_THROWS_AS(shelf.values({{"colour", 1}}), ModelError);
  CHECK_THROWS_AS(shelf.values()["colour"], ModelError);
  CHECK(item_kind_from_string("locker") == ItemKind::locker);
  CHECK_FALSE(item_kind_from_string("sofa"));
}

TEST_CASE("a kind's declared range names the rule", "[furniture][kinds]") {
  const ItemParameter shelves{"shelves", "-", 0, 50, false, 4, "shelf count", true};
  CHECK_FALSE(shelves.violation(3));
  CHECK(shelves.violation(51) == std::string("must lie in [0, 50]"));
  CHECK(shelves.violation(2.5) == std::string("must be an integer"));
  // Past the range of long long: out of range, not "an integer" (the cast to test it was undefined
  // behaviour, and gave "must be an integer" for 1.55e19 shelves in a scene; found by fuzz_scene).
  CHECK(shelves.violation(1.5532558871335012e19) == std::string("must lie in [0, 50]"));
  CHECK(shelves.violation(-1e300) == std::string("must lie in [0, 50]"));
  const ItemParameter mass{"mass", "kg", 0, 100, true, 10, "mass"};
  CHECK(mass.violation(0) == std::string("must lie in (0, 100]"));
}

namespace {
struct StoolKind : ItemKindDefaults {
  static constexpr std::string_view name = "stool";
  static constexpr std::string_view meaning = "a stool, built as a small table";
  static std::vector<ItemParameter> parameters() { return {{"height", "m", 0.3, 0.9, false, 0.45, "seat height"}}; }
  static Vec3 size(const ItemValues& v) { return {0.35, 0.35, v["height"]}; }
  static std::vector<ItemInfo> build(Model& model, const Placement& at, const ItemValues& v, const BuildOptions& o) {
    return {build_table(model, at, 0.35, 0.35, v["height"], o)};
  }
};
}  // namespace

TEST_CASE("a registry takes kind types and refuses a name twice", "[furniture][kinds]") {
  ItemKindRegistry registry = builtin_item_kind_registry();
  registry.add<StoolKind>();
  CHECK_THROWS_AS(registry.add<StoolKind>(), ModelError);
  CHECK_THROWS_AS(registry.add<DeskKind>(), ModelError);
  const ItemKindEntry& stool = registry.at(ItemKind("stool"));
  Model model;
  const auto built = stool.build(model, Placement{}, stool.values(), BuildOptions{});
  REQUIRE(built.size() == 1);
  CHECK(built[0].size.z() == Approx(0.45));
  CHECK_THROWS_AS(builtin_item_kind_registry().at(ItemKind("stool")), ModelError);
}

}  // namespace item_kinds_tests
