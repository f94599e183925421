// The compiled study (CMake target furniture_fem::study_compiled): a study's results (study/report.hpp:
// the statistics and their files; study/runner.hpp: the results folder, the workers, realisations.csv,
// the figures, summary.json).
#define FURNITURE_FEM_BUILDING_STUDY_LIBRARY
#include <furniture_fem/study/runner.hpp>

#define FURNITURE_FEM_STUDY_INTERNAL
#include <furniture_fem/study/detail/report_impl.hpp>
#define FURNITURE_FEM_STUDY_INTERNAL
#include <furniture_fem/study/detail/runner_impl.hpp>
