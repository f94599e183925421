# Units linked to furniture_fem::scene_compiled that build a scene's simulation themselves
# (SceneSimulation<Solver>; test_points_and_block among test_scene's) take that simulation's
# constructor and step from the library (scene/scene_simulation.hpp declares them extern): undefined
# (U) in their objects, compiled (weak, W) in none. -DOBJECTS=<test_scene's object files (its batches
# of files, or one per file)>.
string(REPLACE "," ";" OBJECT "${OBJECTS}")
execute_process(COMMAND nm -C ${OBJECT} OUTPUT_VARIABLE symbols RESULT_VARIABLE rc)
if(rc)
  message(FATAL_ERROR "nm failed on ${OBJECT}")
endif()
set(scene_sim "furniture_fem::Simulation<furniture_fem::ShiftedIntegrationTimoshenko<furniture_fem::GaussPairPlacement>, furniture_fem::RuntimeIntegrator, [^\n]*>::step\\(\\)")
string(REGEX MATCHALL " U ${scene_sim}" taken "${symbols}")
string(REGEX MATCHALL " [TW] ${scene_sim}" compiled "${symbols}")
list(LENGTH taken n_taken)
list(LENGTH compiled n_compiled)
if(n_taken EQUAL 0)
  message(FATAL_ERROR "${OBJECT}: no scene simulation's step taken from furniture_fem::scene_compiled")
endif()
if(n_compiled GREATER 0)
  list(GET compiled 0 first)
  message(FATAL_ERROR "${OBJECT}: ${n_compiled} scene simulations' steps compiled in the unit, e.g.${first}")
endif()
message(STATUS "${n_taken} scene simulations' steps taken from the compiled scene runner, none compiled")
