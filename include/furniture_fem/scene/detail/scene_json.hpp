#pragma once
// Internal: the scene module's names for the strict JSON reader (furniture_fem/scene/json_reader.hpp).
#ifndef FURNITURE_FEM_SCENE_INTERNAL
#error "furniture_fem/scene/detail/scene_json.hpp is internal: include <furniture_fem/scene/scene.hpp>"
#endif
#include "../json_reader.hpp"

namespace furniture_fem::detail {
using namespace json_io;
}  // namespace furniture_fem::detail
