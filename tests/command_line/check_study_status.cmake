# furniture_study's honest status (docs/study/studies.md, "What a study says at its end"): a study that
# cannot succeed fails when read (exit 1, naming the key, the variant, the motion and the level); a
# study in which no run completed exits with 4 and says why; one in which some runs did not complete
# exits with 3; --resume on a changed study names the keys that differ. Run by ctest as:
#   cmake -DPROGRAM=<furniture_study> -DWORK_DIR=<scratch> -P check_study_status.cmake
cmake_minimum_required(VERSION 3.20)
include(${CMAKE_CURRENT_LIST_DIR}/common.cmake)  # WORK_DIR, failures, fail, run_program

# The exit code and a text that stderr must hold, verbatim.
function(expect what want_code want_text)
  string(FIND "${err}" "${want_text}" at)
  if(NOT code STREQUAL "${want_code}" OR at EQUAL -1)
    fail("${what}: expected exit ${want_code} and on stderr:\n  ${want_text}\ngot exit ${code}:\n${out}${err}")
  else()
    message(STATUS "${what}: exit ${code}, as expected")
  endif()
  set(failures ${failures} PARENT_SCOPE)
endfunction()

# A rigid block at x (m) on the 4 m table, 0.05 s runs of a synthetic motion; the study's other keys.
function(write_study file x rest)
  file(WRITE ${WORK_DIR}/${file} "{\"name\": \"status\", \"seed\": 3,
 \"scene\": {\"items\": [{\"kind\": \"block\", \"name\": \"crate\", \"fidelity\": \"rigid\", \"x\": ${x},
                        \"params\": {\"width\": 0.4, \"depth\": 0.4, \"height\": 0.4, \"mass_kg\": 20.0}}],
           \"ground_motion\": {\"source\": \"synthetic\", \"duration\": 3.0, \"dimensions\": \"1d\"},
           \"contact\": {\"law\": \"stiff\"}, \"duration\": 0.05, \"outputs\": {\"figures\": false}},
 ${rest}}\n")
endfunction()

# The duration past a motion's end: refused before any run, nothing written.
write_study(short.json 0 "\"ground_motions\": [{\"name\": \"long\", \"ground_motion\": {\"source\": \"synthetic\", \"duration\": 3.0}},
   {\"name\": \"brief\", \"ground_motion\": {\"source\": \"synthetic\", \"duration\": 1.0}}], \"duration\": 2.0")
run_program(short.json --out short --quiet)
expect("duration past a motion's end" 1
       "error: short.json: duration: variant 'base', motion 'brief', level 1: the run lasts 2 s but the synthetic motion lasts 1 s")
if(EXISTS ${WORK_DIR}/short)
  fail("duration past a motion's end: the results folder was created")
endif()

# An empty suite of motions, and a motion without a name.
write_study(empty.json 0 "\"ground_motions\": []")
run_program(empty.json --quiet)
expect("ground_motions: []" 1 "error: empty.json: ground_motions: is empty: list at least one")
write_study(unnamed.json 0 "\"ground_motions\": [{\"ground_motion\": {\"source\": \"synthetic\", \"duration\": 3.0}}]")
run_program(unnamed.json --quiet)
expect("a motion without a name" 1 "error: unnamed.json: ground_motions[0].name: required: a name for the motion")

# The block against the +x wall, turned by up to 10 deg: every realisation's scene is refused when
# its run starts (a corner off the table), so no run completes: exit 4 and the first one's reason.
write_study(wall.json 1.8 "\"perturbations\": {\"yaw_deg\": 10.0}, \"realisations\": 3")
run_program(wall.json --out wall --workers 1 --quiet)
expect("no run completed" 4
       "error: study 'status': no run completed (3 of 3 did not); the first, run 0 (realisation 0, variant 'base'), failed: wall.json (realisation 0, variant 'base'): items[0]: item 'crate' lies partly outside the 4 m x 4 m table")
if(NOT err MATCHES "\\[3 of the 3 runs not completed for this reason\\]" OR NOT out MATCHES "status: failed, 3 of 3 runs done")
  fail("no run completed: expected the count for the reason and 'failed' on stdout, got:\n${out}${err}")
endif()
file(READ ${WORK_DIR}/wall/summary.json summary)
string(JSON status GET "${summary}" status)
string(JSON same GET "${summary}" first_not_completed runs_for_this_reason)
if(NOT status STREQUAL "failed" OR NOT same EQUAL 3)
  fail("no run completed: summary.json says status '${status}', ${same} runs for the first reason")
endif()

# Moved along x by up to 0.05 m at the table's edge: those moved outwards are refused, the others
# complete: exit 3, the statistics from those that completed.
write_study(edge.json 1.8 "\"perturbations\": {\"x\": 0.05}, \"realisations\": 6")
run_program(edge.json --out edge --workers 1 --quiet)
expect("some runs not completed" 3 "runs did not complete (the statistics count the ")
if(NOT err MATCHES "furniture_study: ([1-5]) of 6 runs did not complete \\(the statistics count the ([1-5]) that did\\)")
  fail("some runs not completed: expected between 1 and 5 of 6, got:\n${err}")
endif()

# --resume on a changed study: the keys that differ, with old and new values.
write_study(changing.json 0 "\"realisations\": 2")
run_program(changing.json --out changing --workers 1 --quiet)
expect("the study to be changed" 0 "")
write_study(changing.json 0.1 "\"realisations\": 3")
run_program(changing.json --out changing --resume --quiet)
expect("--resume on a changed study" 1
       "changing/study.json: --resume: this folder holds another study: its study.json differs from changing.json in realisations: 3 (was 2); scene.items[0].x: 0.1 (was 0); resume with the same study file, or use another --out")

if(failures GREATER 0)
  message(FATAL_ERROR "${failures} furniture_study status check(s) failed")
endif()
