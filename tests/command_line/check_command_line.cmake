# Runs furniture_quake with good and bad command lines and checks each exit code and message; run by
# ctest (tests/command_line/CMakeLists.txt) as:
#   cmake -DPROGRAM=<furniture_quake> -DVERSION=<project version> -DSCENE=<a scene file needing no other file>
#         -DWORK_DIR=<scratch folder> -P check_command_line.cmake
# Everything runs in WORK_DIR, so a check that wrongly starts a run writes nothing elsewhere.
cmake_minimum_required(VERSION 3.20)
include(${CMAKE_CURRENT_LIST_DIR}/common.cmake)  # WORK_DIR, failures, run_program

# check(<expected exit code> <regex the output must match> <arguments...>): stdout and stderr are
# matched together except that --help and --version must print on stdout (see check_stdout).

function(verdict expected_code regex text args)
  if(NOT code STREQUAL expected_code OR NOT text MATCHES "${regex}")
    message(SEND_ERROR "furniture_quake ${args}: expected exit ${expected_code} and '${regex}', "
                       "got exit ${code}\n--- stdout:\n${out}--- stderr:\n${err}")
    math(EXPR failures "${failures} + 1")
    set(failures ${failures} PARENT_SCOPE)
  else()
    message(STATUS "ok: furniture_quake ${args} -> ${code}")
  endif()
endfunction()

macro(check expected_code regex)
  run_program(${ARGN})
  verdict(${expected_code} "${regex}" "${out}${err}" "${ARGN}")
endmacro()

macro(check_stdout expected_code regex)
  run_program(${ARGN})
  verdict(${expected_code} "${regex}" "${out}" "${ARGN}")
endmacro()

# --help and --version: stdout, exit 0.
check_stdout(0 "Usage:.*--duration.*--output-interval.*--overwrite.*--config.*Exit codes: 0 done, 1 bad input.*2 usage.*3 diverged.*130 interrupted" --help)
check_stdout(0 "Usage:" -h)
check_stdout(0 "furniture_fem. ${VERSION}" --version)

# Usage errors: exit 2, the option and the value named.
foreach(bad -1 0 abc nan inf 1e300 0.05xyz)
  check(2 "usage error: --duration: .*${bad}" --duration ${bad} --quiet --no-figures)
endforeach()
check(2 "usage error: --duration: .*not a finite number: 'nan'" --duration nan)
check(2 "usage error: --duration: .*at most 1e6 .got 1e300." --duration 1e300)
check(2 "usage error: --duration.*required" --duration)
foreach(bad -0.01 0 abc nan inf 1e300)
  check(2 "usage error: --output-interval: .*${bad}" --output-interval ${bad} --duration 0.05)
endforeach()
foreach(bad 0 4 1.5 x)
  check(2 "usage error: --config: not 1, 2 or 3: '${bad}'" --config ${bad})
endforeach()
check(2 "usage error: .*--bogus" --bogus)
foreach(bad -1 abc nan 1e300)
  check(2 "usage error: --checkpoint-every: .*${bad}" --checkpoint-every ${bad} --duration 0.05)
endforeach()
check(2 "usage error: --out excludes --resume" --resume somewhere --out elsewhere)
check(2 "usage error: --overwrite excludes --resume" --resume somewhere --overwrite)
check(1 "error: nowhere: --resume: no such results folder" ${SCENE} --resume nowhere --quiet)
check(2 "usage error: .*--config.*scene|usage error: .*scene.*--config" scene.json --config 1)
check(2 "usage error: --records.*--config" --records somewhere)
check(2 "usage error: .*second.json" first.json second.json)

# A folder named empty or with a control character: a usage error naming the option, not the default
# folder (results/default, which the run without a scene would write).
foreach(args "--out ''" "--resume ''" "--out \"$(printf 'a\\nb')\"" "--config 3 --records ''")
  execute_process(COMMAND sh -c "\"$0\" --duration 0.05 --quiet --no-figures ${args}" ${PROGRAM}
                  WORKING_DIRECTORY ${WORK_DIR} TIMEOUT 120 RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
  verdict(2 "usage error: --(out|resume|records): must not (be empty|hold control characters)" "${out}${err}" "${args}")
endforeach()
if(EXISTS ${WORK_DIR}/results)
  fail("a folder option refused, yet ${WORK_DIR}/results was written")
endif()

# Bad input: exit 1, the file named.
check(1 "error: .*no_such_scene.json" no_such_scene.json)
# A missing record of the paper's configurations says where to get it; FFEM_RECORDS is the default folder.
check(1 "ground_motion.files.x: record file not found: \"no_records/jma_kobe_1995_NS_PEER_RSN1106_KJM000.AT2\"; get it from the PEER NGA-West2 database.*RSN1106_KOBE_KJM000.AT2"
      --config 3 --records no_records --quiet)
set(program_saved "${PROGRAM}")
set(PROGRAM ${CMAKE_COMMAND} -E env FFEM_RECORDS=records_from_env ${program_saved})
check(1 "record file not found: \"records_from_env/jma_kobe_1995_NS_PEER_RSN1106_KJM000.AT2\"" --config 3 --quiet)
set(PROGRAM "${program_saved}")

# A short run completes (exit 0); Ctrl-C and SIGTERM during a run stop it cleanly (exit 130). The
# signal is sent to the program itself: `exec` keeps the shell's pid, and a foreground program
# (unlike a script's background job) has SIGINT at its default.
check(0 "completed at t = 0.050 s" --duration 0.05 --quiet --no-figures --out short)

# What a run will take (docs/command_line.md): its steps and the explicit contact's stable step before
# the first step, on stderr; with --quiet nothing of it for a run projected under a minute.
# (check is a macro: a backslash in its regex is lost, so "." stands for the parentheses.)
check(0 "run: 50 steps of dt = 0.001 s from t = 0 s to 0.05 s .the explicit contact's stable step: 0.00128313 s, item 'office_chair'."
      --duration 0.05 --no-figures --out forecast)
run_program(--duration 0.05 --quiet --no-figures --out forecast_quiet)
if(NOT code STREQUAL "0" OR err MATCHES "run: ")
  fail("furniture_quake --duration 0.05 --quiet: a short quiet run said what it will take (exit ${code}):\n${err}")
endif()

# The results folder (docs/io/output.md): run.json says how the run ended; a folder a run wrote is written
# again without asking; a non-empty folder no run wrote is refused (exit 1, nothing touched) unless
# --overwrite, which keeps the user's files.
macro(expect_file path want)
  if(${want} AND NOT EXISTS ${WORK_DIR}/${path})
    message(SEND_ERROR "${path} is missing")
    math(EXPR failures "${failures} + 1")
  elseif(NOT ${want} AND EXISTS ${WORK_DIR}/${path})
    message(SEND_ERROR "${path} exists and should not")
    math(EXPR failures "${failures} + 1")
  endif()
endmacro()
macro(expect_run_status folder status)
  file(READ ${WORK_DIR}/${folder}/run.json record)
  string(JSON got GET "${record}" status)
  if(NOT got STREQUAL "${status}")
    message(SEND_ERROR "${folder}/run.json: status '${got}', expected '${status}'")
    math(EXPR failures "${failures} + 1")
  endif()
endmacro()
expect_run_status(short done)
file(WRITE ${WORK_DIR}/short/marker_stale.png "stale")
check(0 "completed at t = 0.050 s" --duration 0.05 --quiet --no-figures --out short)
expect_file(short/marker_stale.png FALSE)
file(WRITE ${WORK_DIR}/foreign/notes.txt "mine")
file(WRITE ${WORK_DIR}/foreign/energy.csv "not the program's")
check(1 "error: results folder 'foreign': is not empty and was not written by furniture_fem.*--overwrite"
      --duration 0.05 --quiet --no-figures --out foreign)
expect_file(foreign/run.json FALSE)
file(READ ${WORK_DIR}/foreign/energy.csv kept)
if(NOT kept STREQUAL "not the program's")
  message(SEND_ERROR "foreign/energy.csv was changed by a refused run")
  math(EXPR failures "${failures} + 1")
endif()
# --overwrite does not remove or replace a user's file named as an output in a folder no run wrote.
check(1 "error: results folder 'foreign': was not written by furniture_fem .*energy.csv.*move those files"
      --duration 0.05 --quiet --no-figures --out foreign --overwrite)
file(READ ${WORK_DIR}/foreign/energy.csv kept)
if(NOT kept STREQUAL "not the program's")
  message(SEND_ERROR "foreign/energy.csv was changed by --overwrite in a folder no run wrote")
  math(EXPR failures "${failures} + 1")
endif()
file(REMOVE ${WORK_DIR}/foreign/energy.csv)
check(0 "completed at t = 0.050 s" --duration 0.05 --quiet --no-figures --out foreign --overwrite)
expect_file(foreign/notes.txt TRUE)
expect_run_status(foreign done)
file(WRITE ${WORK_DIR}/a_file "x")
check(1 "error: results folder 'a_file': exists and is not a folder" --duration 0.05 --quiet --no-figures --out a_file)
# A run past the motion's end: bad input naming the option (issue 12).
check(1 "command line: --duration: the run lasts 11 s but the synthetic motion lasts 10 s" --duration 11 --quiet --no-figures --out too_long)
# 10 s: the built-in motion's length (a longer run is an error, issue 12); minutes of wall time.
foreach(signal TERM INT)
  set(run "(sleep 1; kill -${signal} $$) & exec \"$0\" --duration 10 --quiet --no-figures --out stopped_${signal}")
  execute_process(COMMAND sh -c "${run}" ${PROGRAM} WORKING_DIRECTORY ${WORK_DIR} TIMEOUT 120
                  RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
  verdict(130 "interrupt" "${out}${err}" "SIG${signal} after 1 s")
  expect_run_status(stopped_${signal} interrupted)
endforeach()

# One run per folder (docs/command_line.md, "A folder in use"): two runs started together on one folder,
# one is refused (exit 1); while a run goes on, a second one with --overwrite and a --resume are refused,
# naming its process; after it is killed with SIGKILL, its lock is gone and a run goes ahead.
set(run "\"$0\" --duration 1 --quiet --no-figures --out together & p=$!
         \"$0\" --duration 1 --quiet --no-figures --out together & q=$!
         wait $p; a=$?; wait $q; echo \"codes $a $?\"")
execute_process(COMMAND sh -c "${run}" ${PROGRAM} WORKING_DIRECTORY ${WORK_DIR} TIMEOUT 300
                RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
verdict(0 "codes (0 1|1 0)" "${out}" "two runs started together on one folder")
verdict(0 "in use by process [0-9]+|still writing there" "${err}" "two runs started together on one folder")
set(run "\"$0\" --duration 10 --quiet --no-figures --checkpoint-every 0.2 --out busy & p=$!
         i=0; while [ ! -f busy/checkpoint.bin ] && [ $i -lt 1200 ]; do sleep 0.1; i=$((i + 1)); done
         \"$0\" --duration 10 --quiet --no-figures --out busy --overwrite; a=$?
         \"$0\" --duration 10 --quiet --no-figures --checkpoint-every 0.2 --resume busy; b=$?
         echo \"holder $p overwrite $a resume $b\"; kill -KILL $p; wait $p
         \"$0\" --duration 0.05 --quiet --no-figures --out busy --overwrite; echo \"after the kill $?\"")
execute_process(COMMAND sh -c "${run}" ${PROGRAM} WORKING_DIRECTORY ${WORK_DIR} TIMEOUT 300
                RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
string(REGEX MATCH "holder ([0-9]+)" holder "${out}")
set(holder "${CMAKE_MATCH_1}")
verdict(0 "holder ${holder} overwrite 1 resume 1.*after the kill 0" "${out}" "--overwrite and --resume on a busy folder")
string(REGEX MATCHALL "error: results folder 'busy' is in use by process ${holder} " named "${err}")
list(LENGTH named named)
if(NOT holder OR NOT named EQUAL 2)
  message(SEND_ERROR "a busy folder: expected two refusals naming process '${holder}', got:\n${err}")
  math(EXPR failures "${failures} + 1")
endif()

# SIGTERM while the scene is read: the scene is a FIFO, so the program waits in the reading phase until
# the test writes the scene into it, after the signal. It must end at once after reading, nothing run.
set(run "mkfifo fifo.json; \"$0\" fifo.json --quiet --no-figures --out fifo & p=$!; sleep 0.5; kill -TERM $p;
         sleep 0.3; cat \"$1\" > fifo.json; wait $p")
execute_process(COMMAND sh -c "${run}" ${PROGRAM} ${SCENE} WORKING_DIRECTORY ${WORK_DIR} TIMEOUT 120
                RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
verdict(130 "interrupted while reading the scene; nothing run" "${out}${err}" "SIGTERM while reading")
if(EXISTS ${WORK_DIR}/fifo)
  message(SEND_ERROR "SIGTERM while reading: the run started (${WORK_DIR}/fifo exists)")
  math(EXPR failures "${failures} + 1")
endif()

if(failures GREATER 0)
  message(FATAL_ERROR "${failures} command line check(s) failed")
endif()
