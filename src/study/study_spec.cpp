// The compiled study (CMake target furniture_fem::study_compiled), its first unit: the study file read,
// checked and written (study/spec.hpp: parse_study_json, parse_study, to_json, study_scene). The scene
// reader and validation are parsed here once; a program linking the target includes neither.
#define FURNITURE_FEM_BUILDING_STUDY_LIBRARY
#include <furniture_fem/study/spec.hpp>

#define FURNITURE_FEM_STUDY_INTERNAL
#include <furniture_fem/study/detail/spec_impl.hpp>
