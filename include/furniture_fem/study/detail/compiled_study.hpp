#pragma once
// Internal: how the study's headers give their entry points (parse_study_json, run_realisation,
// study_report, StudyFolder's members, run_local ...). Header-only (no macro), each public header includes
// its definitions at its end (study/detail/*_impl.hpp), inline. Linked with the compiled study (CMake
// target furniture_fem::study_compiled, which defines FURNITURE_FEM_COMPILED_STUDY for its users), the
// headers declare them and include none of their heavy dependencies (the scene reader, the observers,
// the figures); the library's units (src/study/*.cpp) define each of them once, out of line.
#ifndef FURNITURE_FEM_STUDY_INTERNAL
#error "furniture_fem/study/detail/compiled_study.hpp is internal: include <furniture_fem/study/runner.hpp>"
#endif

#if defined(FURNITURE_FEM_COMPILED_STUDY) || defined(FURNITURE_FEM_BUILDING_STUDY_LIBRARY)
#define FFEM_STUDY_DECLARED_ONLY 1
#endif
#ifdef FFEM_STUDY_DECLARED_ONLY
#define FFEM_STUDY_ENTRY
#else
#define FFEM_STUDY_ENTRY inline
#endif
