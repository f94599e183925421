#pragma once
// The boxes the harm tests place: a cabinet-sized item standing at a point.
#include <furniture_fem/furniture/furniture.hpp>

namespace furniture_fem::test {
inline ItemInfo cabinet(double W, double D, double H, const Vec3& at) {
  ItemInfo it;
  it.size = Vec3(W, D, H);
  it.position = at;
  return it;
}
}  // namespace furniture_fem::test
