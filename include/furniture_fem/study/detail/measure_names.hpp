#pragma once
// Internal: the intensity measures' names in a study file (study/spec.hpp), read there and written in the report.
#ifndef FURNITURE_FEM_STUDY_INTERNAL
#error "furniture_fem/study/detail/measure_names.hpp is internal: include <furniture_fem/study/spec.hpp>"
#endif
#include "../../scene/json_reader.hpp"
#include "../spec.hpp"

namespace furniture_fem::detail {

inline const json_io::EnumNames<IntensityMeasure, 3> measure_names{
    {{IntensityMeasure::scale, "scale"}, {IntensityMeasure::pga, "pga"}, {IntensityMeasure::pgv, "pgv"}}};

}  // namespace furniture_fem::detail
