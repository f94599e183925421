// The compiled scene runner (CMake target furniture_fem::scene_compiled): the run of a scene
// (runner.hpp, detail::run_checked_scene), compiled once for every contact law: the law is a run-time
// kernel of the registry (scene/laws/law_list.hpp), so a law registered later by a user's program runs
// here too. A program linking the target gets FURNITURE_FEM_COMPILED_SCENE and compiles none of it.
// The scene simulation itself (its constructor and step) is compiled in two other units, one per linear
// solver (scene_simulation.hpp declares them extern), so this one holds the run loop, the observers, the
// reader and the laws' set-up. parse_scene, run_scene, check_run_start, check_scene_model and
// detail::run_checked_scene are defined here, out of line (scene/detail/compiled_entry_points.hpp).
#define FURNITURE_FEM_BUILDING_SCENE_LIBRARY
#include <furniture_fem/scene/reader.hpp>
#include <furniture_fem/scene/scene_runner.hpp>
