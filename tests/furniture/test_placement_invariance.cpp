// An item's mesh does not depend on where it stands: every built-in kind, at full and rigid fidelity,
// placed at 40 random positions and yaws, has the nodes and elements it has at the origin, each node at
// the same place in the item's own frame. Before the element counts were taken from lengths in the
// item's frame (MemberOptions::count_length), a rigid or coarse bookshelf got one of 12 meshes (253 to
// 329 nodes) over 200 placements: its coarse lattice has pieces 2.5 elements long, and the round-off of
// the placed nodes' distance rounded them to 2 or 4 elements.
#include <catch2/catch.hpp>

#include <furniture_fem/furniture/item_kinds.hpp>

#include <functional>
#include <random>
#include <string>
#include <vector>

using namespace furniture_fem;

namespace placement_invariance_tests {  // this file's own names (its group compiles files in batches)

namespace {

using Builder = std::function<std::vector<ItemInfo>(Model&, const Placement&, const BuildOptions&)>;

std::vector<std::pair<std::string, Builder>> every_kind() {
  const auto one = [](auto build) {
    return [build](Model& m, const Placement& p, const BuildOptions& o) { return std::vector<ItemInfo>{build(m, p, o)}; };
  };
  return {
      {"tall_cabinet", one([](Model& m, const Placement& p, const BuildOptions& o) { return build_tall_cabinet(m, p, o); })},
      {"separated_cabinets",
       [](Model& m, const Placement& p, const BuildOptions& o) {
         const auto pair = build_separated_cabinets(m, p, o);
         return std::vector<ItemInfo>{pair.lower, pair.upper};
       }},
      {"side_table", one([](Model& m, const Placement& p, const BuildOptions& o) { return build_side_table(m, p, o); })},
      {"desk", one([](Model& m, const Placement& p, const BuildOptions& o) { return build_desk(m, p, o); })},
      {"office_chair", one([](Model& m, const Placement& p, const BuildOptions& o) { return build_office_chair(m, p, o); })},
      {"bookshelf", one([](Model& m, const Placement& p, const BuildOptions& o) { return build_bookshelf(m, p, 0.8, 0.3, 1.8, 4, o); })},
      {"locker", one([](Model& m, const Placement& p, const BuildOptions& o) { return build_locker(m, p, 0.9, 0.5, 1.8, o); })},
      {"table", one([](Model& m, const Placement& p, const BuildOptions& o) { return build_table(m, p, 1.2, 0.8, 0.7, o); })},
      {"block", one([](Model& m, const Placement& p, const BuildOptions& o) {
         BuildOptions b = o;
         b.fidelity = Fidelity::rigid;  // a block is rigid only
         b.mass_kg = 20.0;
         return build_block(m, p, 0.45, 0.25, 0.65, b);
       })},
  };
}

// The item's nodes in its own frame, in the order they were made.
std::vector<Vec3> local_nodes(const Model& m, const std::vector<ItemInfo>& items) {
  std::vector<Vec3> out;
  for (const auto& item : items)
    for (int n : m.body(item.body).nodes) out.push_back(item.to_local(m.node(n).X));
  return out;
}

}  // namespace

TEST_CASE("an item's mesh is the same wherever it stands", "[furniture][mesh]") {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> coordinate(-3.0, 3.0), yaw_deg(-180.0, 180.0);
  for (const auto& [kind, build] : every_kind())
    for (const Fidelity fidelity : {Fidelity::full, Fidelity::rigid}) {
      BuildOptions opts;
      opts.fidelity = fidelity;
      Model reference_model;
      const std::vector<Vec3> reference = local_nodes(reference_model, build(reference_model, Placement::at(0, 0, 0), opts));
      for (int trial = 0; trial < 40; ++trial) {
        const Placement at = Placement::at(coordinate(rng), coordinate(rng), yaw_deg(rng));
        Model m;
        const std::vector<Vec3> nodes = local_nodes(m, build(m, at, opts));
        INFO(kind << " at fidelity " << to_string(fidelity) << ", placement " << trial);
        REQUIRE(nodes.size() == reference.size());
        CHECK(m.num_elements() == reference_model.num_elements());
        double worst = 0;  // m; the placement's round-off, some 1e-15
        for (std::size_t k = 0; k < nodes.size(); ++k) worst = std::max(worst, (nodes[k] - reference[k]).norm());
        CHECK(worst < 1e-12);
      }
    }
}

}  // namespace placement_invariance_tests
