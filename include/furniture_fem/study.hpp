#pragma once
// furniture_fem/study.hpp: the study module (seeded ensembles of scene runs, their statistics).
#include "study/random.hpp"
#include "study/statistics.hpp"
#include "study/spec.hpp"
#include "study/realisation.hpp"
#include "study/outcomes.hpp"
#include "study/report.hpp"
#include "study/figures.hpp"
#include "study/runner.hpp"
