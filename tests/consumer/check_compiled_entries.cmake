# A program linked to a compiled library takes that library's entry points from it: undefined (U) in its
# objects, not compiled there (T, or weak W), and none of the heavy code behind them compiled there either.
# -DOBJECTS=<the program's object files> -DLIBRARY=<scene or study>
#   scene (furniture_fem::scene_compiled, scene/run_scene.hpp): parse_scene and run_scene; no scene run
#         (detail::run_composed, detail::run_checked_scene), no Simulation and no CGAL code.
#   study (furniture_fem::study_compiled, study/runner.hpp): reading a study, its folder, its workers and its
#         statistics; none of the scene reader, the study's runs, its observers or its figures.
include(${CMAKE_CURRENT_LIST_DIR}/symbol_checks.cmake)
string(REPLACE "," ";" objects "${OBJECTS}")
if(LIBRARY STREQUAL "scene")
  set(entries run_scene parse_scene)
  set(heavy_regex "furniture_fem::detail::run_(composed<[^\n]*>|checked_scene)\\(|furniture_fem::Simulation<|CGAL::")
  set(heavy_what "scene runs, Simulation or CGAL functions")
elseif(LIBRARY STREQUAL "study")
  set(entries parse_study_json StudyFolder::StudyFolder StudyFolder::finish run_local study_report)
  set(heavy_regex "furniture_fem::(parse_scene_json|run_realisation|write_study_figures|LinePlot::|ContactForcePeaks::|detail::check_study_)")
  set(heavy_what "functions of the scene reader, the study's runs or its figures")
else()
  message(FATAL_ERROR "LIBRARY must be scene or study, got '${LIBRARY}'")
endif()
ffem_symbols(symbols ${objects})
set(problems "")
foreach(entry IN LISTS entries)
  ffem_require_taken("${symbols}" "furniture_fem::${entry}\\(" "furniture_fem::${entry}" problems n_taken)
  ffem_forbid_compiled("${symbols}" "furniture_fem::${entry}\\(" "TW" "definitions of furniture_fem::${entry}" problems)
endforeach()
ffem_forbid_compiled("${symbols}" "(${heavy_regex})" "TW" "${heavy_what}" problems)
ffem_report_problems("${problems}" "${objects}"
                     "${entries}: taken from furniture_fem::${LIBRARY}_compiled, none of their code compiled in the program")
