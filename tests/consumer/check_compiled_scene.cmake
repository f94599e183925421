# A program linked to furniture_fem::scene_compiled takes the contact laws' runs from the library:
# detail::run_law is undefined (U) in its object, not compiled there (weak, W), for every law.
# -DOBJECTS=<the program's object files>
string(REPLACE "," ";" objects "${OBJECTS}")
execute_process(COMMAND nm -C ${objects} OUTPUT_VARIABLE symbols RESULT_VARIABLE rc)
if(rc)
  message(FATAL_ERROR "nm failed on ${objects}")
endif()
string(REGEX MATCHALL " U [^\n]*furniture_fem::detail::run_law<[0-9]+ul>\\(" taken "${symbols}")
string(REGEX MATCHALL " [TW] [^\n]*furniture_fem::detail::run_law<[0-9]+ul>\\(" compiled "${symbols}")
list(LENGTH taken n_taken)
list(LENGTH compiled n_compiled)
if(n_compiled GREATER 0 OR NOT n_taken EQUAL LAWS)
  message(FATAL_ERROR "${objects}: ${n_compiled} contact laws' runs compiled in the program, ${n_taken} of ${LAWS} "
                      "taken from furniture_fem::scene_compiled")
endif()
message(STATUS "the ${LAWS} contact laws' runs come from the compiled scene runner")
