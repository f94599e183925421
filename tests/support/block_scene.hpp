#pragma once
// A one-item scene (a rigid 20 kg block, "crate") under a given ground motion, no figures: for tests
// of what a scene does with its motion.
#include <nlohmann/json.hpp>

namespace ffem_test {

inline nlohmann::json block_scene(const nlohmann::json& motion, double duration = 1.0) {
  return {{"name", "block"},
          {"items", {{{"kind", "block"}, {"name", "crate"}, {"fidelity", "rigid"}, {"params", {{"mass_kg", 20.0}}}}}},
          {"ground_motion", motion},
          {"duration", duration},
          {"outputs", {{"figures", false}}}};
}

}  // namespace ffem_test
