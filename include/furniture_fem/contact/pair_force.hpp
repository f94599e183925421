#pragma once
// furniture_fem/contact/pair_force.hpp: the contact force between two bodies, as the room's contact
// reports it per pair (RoomContact::pair_forces), apart from the contact module's CGAL detection.
#include "../core/model.hpp"

namespace furniture_fem {

// Sum of contact force magnitudes between two bodies (or a body and the floor, the walls, the mesh
// obstacles or the ceiling: body_b one of the ids below) in the last evaluation, for the per-pair
// force histories. A capsule obstacle (RoomContact::add_capsule: a person standing in the room as a
// rigid obstacle, harm/occupant.hpp) is capsule_id(k), k = 0, 1, ... as its owner numbers them.
struct PairForce {
  static constexpr bool checkpoint_as_bytes = true;  // core/checkpoint.hpp
  static constexpr int floor_id = -1, wall_id = -2, obstacle_id = -3, ceiling_id = -4;
  static constexpr int capsule_id(int k) { return -100 - k; }
  static constexpr bool is_capsule(int id) { return id <= -100; }
  static constexpr int capsule_index(int id) { return -100 - id; }
  int body_a, body_b;
  Vec3 force_on_a;
};

}  // namespace furniture_fem
