# furniture_study's command line (examples/furniture_study): exit codes and messages, the same
# realisations.csv after a SIGKILL and --resume as in one go, and, when MPI is there, under
# `mpiexec -n 2`. Run by ctest (tests/command_line/CMakeLists.txt) as:
#   cmake -DPROGRAM=<furniture_study> -DWORK_DIR=<scratch> [-DMPIEXEC=<mpiexec>] -P check_study.cmake
cmake_minimum_required(VERSION 3.20)
include(${CMAKE_CURRENT_LIST_DIR}/common.cmake)  # WORK_DIR, failures, fail

# A study of 160 short runs (a rigid block sliding under a constant table acceleration, 2 s each):
# long enough to be killed in the middle.
file(WRITE ${WORK_DIR}/blocks.json [=[
{"name": "blocks", "seed": 11,
 "scene": {"name": "block",
           "items": [{"kind": "block", "name": "crate", "fidelity": "rigid",
                      "params": {"width": 0.4, "depth": 0.4, "height": 0.4, "mass_kg": 20.0,
                                 "mu_floor_long": 0.15, "mu_floor_short": 0.15}}],
           "ground_motion": {"source": "points", "x": [[0.0, 2.4], [2.0, 2.4], [2.0001, 0.0]]},
           "contact": {"law": "stiff"}, "duration": 2.0, "outputs": {"figures": false}},
 "intensity": {"measure": "scale", "levels": [0.5, 1.0, 1.5, 2.0]},
 "perturbations": {"friction": 0.3, "x": 0.05, "y": 0.05},
 "realisations": 40}
]=])

function(run_study)
  execute_process(COMMAND ${ARGN} WORKING_DIRECTORY ${WORK_DIR} TIMEOUT 300
                  RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
  set(code "${code}" PARENT_SCOPE)
  set(text "${out}${err}" PARENT_SCOPE)
endfunction()

# Exit codes and messages.
run_study(${PROGRAM} --help)
if(NOT code EQUAL 0 OR NOT text MATCHES "--resume")
  fail("--help: expected exit 0 and the options, got ${code}: ${text}")
endif()
run_study(${PROGRAM})
if(NOT code EQUAL 2 OR NOT text MATCHES "study is required")
  fail("no study file: expected exit 2, got ${code}: ${text}")
endif()
file(WRITE ${WORK_DIR}/bad.json "{\"name\": \"bad\", \"scene\": {}, \"realisations\": -1}\n")
run_study(${PROGRAM} bad.json)
if(NOT code EQUAL 1 OR NOT text MATCHES "bad.json: realisations")
  fail("bad study: expected exit 1 naming bad.json and the key, got ${code}: ${text}")
endif()
# An empty --out is a usage error, not the default folder study_blocks.
run_study(sh -c "\"$0\" blocks.json --out '' --quiet" ${PROGRAM})
if(NOT code EQUAL 2 OR NOT text MATCHES "--out: must not be empty" OR EXISTS ${WORK_DIR}/study_blocks)
  fail("--out '': expected exit 2 naming --out and no study_blocks folder, got ${code}: ${text}")
endif()
run_study(${PROGRAM} blocks.json --scene-of 45 --out run45.json)
if(NOT code EQUAL 0 OR NOT EXISTS ${WORK_DIR}/run45.json)
  fail("--scene-of: expected exit 0 and run45.json, got ${code}: ${text}")
else()
  file(READ ${WORK_DIR}/run45.json scene)
  string(JSON level GET "${scene}" ground_motion level)
  if(NOT level EQUAL 1.0)  # run 45 = realisation 45 = level index 1 (1.0)
    fail("--scene-of 45: expected ground_motion.level 1.0, got ${level}")
  endif()
endif()

# The reference: the whole study in one go, one worker.
run_study(${PROGRAM} blocks.json --out one --workers 1 --quiet)
if(NOT code EQUAL 0)
  fail("one worker: exit ${code}: ${text}")
endif()
file(READ ${WORK_DIR}/one/realisations.csv reference)
# A folder's realisations.csv must be the reference, byte for byte.
function(expect_reference folder what)
  file(READ ${WORK_DIR}/${folder}/realisations.csv produced)
  if(NOT produced STREQUAL reference)
    fail("realisations.csv ${what} differs from the study run in one go by one worker")
  endif()
  set(failures ${failures} PARENT_SCOPE)
endfunction()

# Killed (SIGKILL at the time-out) in the middle, then resumed: the same file.
execute_process(COMMAND ${PROGRAM} blocks.json --out killed --workers 2 --quiet WORKING_DIRECTORY ${WORK_DIR}
                TIMEOUT 2 RESULT_VARIABLE code OUTPUT_QUIET ERROR_QUIET)
file(GLOB done_before ${WORK_DIR}/killed/runs/run_*.json)
list(LENGTH done_before n_before)
message(STATUS "killed after ${n_before} of 160 runs (exit: ${code})")
run_study(${PROGRAM} blocks.json --out killed --workers 2 --resume --quiet)
if(NOT code EQUAL 0)
  fail("--resume: exit ${code}: ${text}")
endif()
expect_reference(killed "after a kill and --resume")
file(READ ${WORK_DIR}/killed/summary.json summary)
string(JSON resumed_from GET "${summary}" resumed_from_previous)
if(n_before GREATER 0 AND n_before LESS 160 AND NOT resumed_from EQUAL n_before)
  fail("--resume: expected ${n_before} runs kept from before the kill, summary says ${resumed_from}")
endif()
run_study(${PROGRAM} blocks.json --out killed --quiet)
if(NOT code EQUAL 1 OR NOT text MATCHES "--resume continues it")
  fail("a finished study's folder without --resume: expected exit 1, got ${code}: ${text}")
endif()

# One study per folder (docs/study/studies.md): a --resume started while the study runs is refused,
# naming its process; once that process is killed (SIGKILL), --resume goes on: no stale lock.
set(run "\"$0\" blocks.json --out busy --workers 1 --quiet & p=$!
         i=0; while [ ! -f busy/study.json ] && [ $i -lt 600 ]; do sleep 0.1; i=$((i + 1)); done
         \"$0\" blocks.json --out busy --resume --quiet; a=$?
         echo \"holder $p resume $a\"; kill -KILL $p; wait $p
         \"$0\" blocks.json --out busy --resume --quiet; echo \"after the kill $?\"")
execute_process(COMMAND sh -c "${run}" ${PROGRAM} WORKING_DIRECTORY ${WORK_DIR} TIMEOUT 300
                RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
string(REGEX MATCH "holder ([0-9]+)" holder "${out}")
set(holder "${CMAKE_MATCH_1}")
if(NOT holder OR NOT out MATCHES "holder ${holder} resume 1.*after the kill 0" OR
   NOT err MATCHES "results folder 'busy' is in use by process ${holder} ")
  fail("a busy study folder: expected --resume refused naming process '${holder}', then a resume after the kill; "
       "got:\n${out}${err}")
else()
  message(STATUS "a busy study folder: --resume refused, naming process ${holder}; resumed after its SIGKILL")
  expect_reference(busy "after a refused --resume, a kill and --resume")
endif()

# Under MPI: two ranks, the same file; the hand-out's cost in summary.json.
if(MPIEXEC)
  set(ENV{OMPI_ALLOW_RUN_AS_ROOT} 1)
  set(ENV{OMPI_ALLOW_RUN_AS_ROOT_CONFIRM} 1)
  run_study(${MPIEXEC} -n 2 --oversubscribe ${PROGRAM} blocks.json --out mpi --quiet)
  if(NOT code EQUAL 0)
    fail("mpiexec -n 2: exit ${code}: ${text}")
  else()
    expect_reference(mpi "under mpiexec -n 2")
    file(READ ${WORK_DIR}/mpi/summary.json summary)
    string(JSON ranks GET "${summary}" ranks)
    string(JSON handout GET "${summary}" handout_seconds_mean)
    message(STATUS "mpiexec -n 2: ranks ${ranks}, mean hand-out wait ${handout} s")
    if(NOT ranks EQUAL 2)
      fail("mpiexec -n 2: summary.json says ${ranks} ranks")
    endif()
  endif()
endif()

if(failures GREATER 0)
  message(FATAL_ERROR "${failures} furniture_study check(s) failed")
endif()
