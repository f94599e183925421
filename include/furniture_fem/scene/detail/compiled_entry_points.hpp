#pragma once
// Internal: the scene module's entry points that the compiled scene runner (CMake target
// furniture_fem::scene_compiled, src/scene/run_scene.cpp) defines once: parse_scene (reader.hpp),
// run_scene and check_run_start (runner.hpp). Its users get FURNITURE_FEM_COMPILED_SCENE and see the
// declarations below only (FFEM_SCENE_DECLARED_ONLY); the library's unit defines them out of line;
// header-only use defines them inline. Users include furniture_fem/scene/run_scene.hpp, not this file.
#ifndef FURNITURE_FEM_SCENE_INTERNAL
#error "furniture_fem/scene/detail/compiled_entry_points.hpp is internal: include <furniture_fem/scene/run_scene.hpp>"
#endif
#include <string>
#include <vector>

#include "../run_summary.hpp"
#include "../spec.hpp"

#if defined(FURNITURE_FEM_COMPILED_SCENE) && !defined(FURNITURE_FEM_BUILDING_SCENE_LIBRARY)
#define FFEM_SCENE_DECLARED_ONLY 1
#endif
#ifdef FURNITURE_FEM_BUILDING_SCENE_LIBRARY
#define FFEM_SCENE_ENTRY_INLINE
#else
#define FFEM_SCENE_ENTRY_INLINE inline
#endif

#ifdef FFEM_SCENE_DECLARED_ONLY
namespace furniture_fem {
class RunObserver;
SceneSpec parse_scene(const std::string& path);
RunSummary run_scene(const SceneSpec& spec, const RunOptions& opt = {}, const std::vector<RunObserver*>& extra = {});
void check_run_start(const SceneSpec& spec, const RunOptions& opt);
void check_scene_model(const SceneSpec& spec);
}  // namespace furniture_fem
#endif
