#pragma once
// furniture_fem/scene/run_scene.hpp: the calls a program that runs scene files needs.
//
//   SceneSpec  parse_scene(const std::string& path)      a scene file read and checked (reader.hpp)
//   RunSummary run_scene(const SceneSpec&, const RunOptions& = {}, const std::vector<RunObserver*>& extra = {})
//   void check_run_start(const SceneSpec&, const RunOptions&)  what run_scene refuses before it builds the model
//   void check_scene_model(const SceneSpec&)   what it refuses once the model is built: an obstacle through an
//                                              item at t = 0, a dt too long for the explicit contact
//
// Linked with the compiled scene runner (CMake target furniture_fem::scene_compiled, which defines
// FURNITURE_FEM_COMPILED_SCENE for its users), this header declares them and includes only the
// scene's description and the run's options and summary (run_summary.hpp): no solver, no contact, no
// CGAL, no JSON parser, so a program's unit compiles in a fraction of the runner's time and memory
// (docs/performance.md, section 6). Header-only (no macro), it includes the reader and the runner.
// Observers (extra) are declared in observer.hpp.
#define FURNITURE_FEM_SCENE_INTERNAL
#include "detail/compiled_entry_points.hpp"
#undef FURNITURE_FEM_SCENE_INTERNAL

#ifndef FFEM_SCENE_DECLARED_ONLY
#include "reader.hpp"
#include "runner.hpp"
#endif
