# Units linked to furniture_fem::scene_compiled that build a scene's simulation themselves
# (SceneSimulation<Solver>; test_points_and_block among test_scene's) take that simulation's
# constructor and step from the library (scene/scene_simulation.hpp declares them extern): undefined
# (U) in their objects, compiled (weak, W) in none. -DOBJECTS=<test_scene's object files (its batches
# of files, or one per file)>.
include(${CMAKE_CURRENT_LIST_DIR}/symbol_checks.cmake)
string(REPLACE "," ";" objects "${OBJECTS}")
ffem_symbols(symbols ${objects})
set(scene_sim "furniture_fem::Simulation<furniture_fem::ShiftedIntegrationTimoshenko<furniture_fem::GaussPairPlacement>, furniture_fem::RuntimeIntegrator, [^\n]*>::step\\(\\)")
set(problems "")
ffem_require_taken("${symbols}" "${scene_sim}" "a scene simulation's step" problems n_taken)
ffem_forbid_compiled("${symbols}" "${scene_sim}" "TW" "scene simulations' steps" problems)
ffem_report_problems("${problems}" "${objects}"
                     "${n_taken} scene simulations' steps taken from the compiled scene runner, none compiled")
