// The compiled study (CMake target furniture_fem::study_compiled): one run of a study and its record
// (study/outcomes.hpp: run_realisation through the compiled scene runner, with the observers that
// collect its outcomes; failure_reason, study_failures, the record's JSON). The law is a run-time kernel
// of the registry, so a law a program registers before its study runs here too.
#define FURNITURE_FEM_BUILDING_STUDY_LIBRARY
#include <furniture_fem/study/outcomes.hpp>

#define FURNITURE_FEM_STUDY_INTERNAL
#include <furniture_fem/study/detail/outcomes_impl.hpp>
