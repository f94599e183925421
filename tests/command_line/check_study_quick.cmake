# The example study CI runs (examples/studies/quick.json), twice, in two processes whose heaps differ
# (other --out folder names, one worker and two): the same realisations.csv, byte for byte. Before the
# support faces were made independent of CGAL's hull listing (contact/detail/support_points.hpp), the
# rigid tall cabinet of realisation 0 (yaw -89.139 deg) slid 0.00097 m in one process and 0.00120 m in
# another. Run by ctest (tests/command_line/CMakeLists.txt) as:
#   cmake -DPROGRAM=<furniture_study> -DSTUDY=<quick.json> -DWORK_DIR=<scratch> -P check_study_quick.cmake
cmake_minimum_required(VERSION 3.20)
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR})
set(folders a a_folder_whose_name_is_longer_so_that_the_heap_lies_otherwise)
set(workers 1 2)
foreach(k 0 1)
  list(GET folders ${k} folder)
  list(GET workers ${k} n)
  execute_process(COMMAND ${PROGRAM} ${STUDY} --out ${folder} --workers ${n} --quiet
                  WORKING_DIRECTORY ${WORK_DIR} TIMEOUT 500 RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT code EQUAL 0)
    message(FATAL_ERROR "quick study into ${folder} with ${n} worker(s): exit ${code}: ${out}${err}")
  endif()
endforeach()
list(GET folders 0 first)
list(GET folders 1 second)
file(READ ${WORK_DIR}/${first}/realisations.csv a)
file(READ ${WORK_DIR}/${second}/realisations.csv b)
if(NOT a STREQUAL b)
  execute_process(COMMAND diff ${first}/realisations.csv ${second}/realisations.csv WORKING_DIRECTORY ${WORK_DIR}
                  OUTPUT_VARIABLE difference)
  message(FATAL_ERROR "quick study: realisations.csv differs between two processes:\n${difference}")
endif()
message(STATUS "quick study: the same realisations.csv from two processes")
