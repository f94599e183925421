#pragma once
// furniture_fem/furniture/named_points.hpp: the points of a built item that a scene can name (a
// restraint's point, docs/restraints/restraints.md): its builder's markers (ItemInfo::markers, e.g. a
// desk's "top_front_centre") and the points of its outer box that every item has:
//   corners        {top, bottom}_{front, back}_{left, right}
//   edge middles   {top, bottom}_{front, back}_centre, {top, bottom}_{left, right}_centre
//   face middles   top_centre, bottom_centre
// In the item frame (ItemInfo): x across the width, left at -W/2 as seen standing in front of it; y from
// the front (-D/2) to the back (+D/2); z up from the base (0) to the top (H). A builder's marker of the
// same name wins.
#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "furniture.hpp"

namespace furniture_fem {

namespace detail {
struct BoxPointAxis {
  std::string_view word;
  double fraction;  // of the half size along the axis (z: of the height, from the base)
};
inline constexpr std::array<BoxPointAxis, 2> box_heights = {{{"top", 1.0}, {"bottom", 0.0}}};
inline constexpr std::array<BoxPointAxis, 3> box_depths = {{{"front", -1.0}, {"back", 1.0}, {"", 0.0}}};
inline constexpr std::array<BoxPointAxis, 3> box_sides = {{{"left", -1.0}, {"right", 1.0}, {"", 0.0}}};

// Every box point's name with its place as fractions (x and y of the half sizes, z of the height).
template <class F>
void for_each_box_point(F&& f) {
  for (const auto& h : box_heights)
    for (const auto& d : box_depths)
      for (const auto& w : box_sides) {
        std::string name(h.word);
        if (!d.word.empty()) name.append("_").append(d.word);
        if (!w.word.empty()) name.append("_").append(w.word);
        if (d.word.empty() || w.word.empty()) name += "_centre";
        f(name, Vec3(w.fraction, d.fraction, h.fraction));
      }
}
}  // namespace detail

// The point `name` of the item in its frame, or none.
inline std::optional<Vec3> named_point_local(const ItemInfo& item, std::string_view name) {
  if (const Marker* m = item.marker(name)) return m->local_point;
  std::optional<Vec3> found;
  detail::for_each_box_point([&](const std::string& box_name, const Vec3& f) {
    if (box_name == name) found = Vec3(0.5 * item.size.x() * f.x(), 0.5 * item.size.y() * f.y(), item.size.z() * f.z());
  });
  return found;
}

// Every name named_point_local takes for the item (its markers first), for error messages.
inline std::vector<std::string> named_point_names(const ItemInfo& item) {
  std::vector<std::string> names;
  for (const Marker& m : item.markers) names.push_back(m.name);
  detail::for_each_box_point([&](const std::string& box_name, const Vec3&) { names.push_back(box_name); });
  return names;
}

}  // namespace furniture_fem
