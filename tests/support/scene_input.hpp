#pragma once
// A scene from JSON read as a scene file is (parsed, then validated), and the named error a user would
// read from it, for the scene tests' key and value checks.
#include <furniture_fem/scene/reader.hpp>
#include <furniture_fem/scene/validation.hpp>

#include <string>

#include "input_errors.hpp"

namespace ffem_test {

// The scene j as read from a file named `file`: parsed, then validated.
inline furniture_fem::SceneSpec validated_scene(const nlohmann::json& j, const std::string& file) {
  furniture_fem::SceneSpec s = furniture_fem::parse_scene_json(j, file);
  furniture_fem::validate(s);
  return s;
}

// The message of the InputError reading it raises, or "no error".
inline std::string scene_error(const nlohmann::json& j, const std::string& file) {
  return input_error([&] { (void)validated_scene(j, file); });
}

}  // namespace ffem_test
