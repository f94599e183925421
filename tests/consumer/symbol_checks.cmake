# The consumer tests' symbol checks, shared by check_*.cmake: what a program's objects take from a
# compiled library (undefined, U in `nm -C`) and what they must not compile themselves (defined: text T
# or weak W; with local ones t and w where asked). Each function appends what it finds wrong to the list
# named by `problems_var`; ffem_report_problems ends the script with them.

# The demangled symbols of the objects, in `out`.
function(ffem_symbols out)
  execute_process(COMMAND nm -C ${ARGN} OUTPUT_VARIABLE symbols RESULT_VARIABLE rc)
  if(rc)
    message(FATAL_ERROR "nm failed on ${ARGN}")
  endif()
  set(${out} "${symbols}" PARENT_SCOPE)
endfunction()

# At least one undefined symbol matching `regex` (anywhere on its line); `count_var` gets how many.
# (Parameter names end in _var: a list named like a parameter would be shadowed by it.)
function(ffem_require_taken symbols regex what problems_var count_var)
  string(REGEX MATCHALL " U [^\n]*${regex}" taken "${symbols}")
  list(LENGTH taken n)
  set(found "${${problems_var}}")
  if(n EQUAL 0)
    list(APPEND found "${what} not taken from the library")
  endif()
  set(${problems_var} "${found}" PARENT_SCOPE)
  set(${count_var} ${n} PARENT_SCOPE)
endfunction()

# No defined symbol of the `types` letters (TW, or TWtw) matching `regex`.
function(ffem_forbid_compiled symbols regex types what problems_var)
  string(REGEX MATCHALL " [${types}] [^\n]*${regex}[^\n]*" compiled "${symbols}")
  list(LENGTH compiled n)
  set(found "${${problems_var}}")
  if(n GREATER 0)
    list(GET compiled 0 first)
    list(APPEND found "${n} ${what} compiled in the program, e.g.${first}")
  endif()
  set(${problems_var} "${found}" PARENT_SCOPE)
endfunction()

# Fails with the problems found (a list), prefixed by `context`; else prints `passed`.
function(ffem_report_problems found context passed)
  if(found)
    list(JOIN found "; " text)
    message(FATAL_ERROR "${context}: ${text}")
  endif()
  message(STATUS "${passed}")
endfunction()
