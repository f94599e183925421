#pragma once
// furniture_fem/study.hpp: the study module (seeded ensembles of scene runs, their statistics).
#include "study/random.hpp"
#include "study/statistics.hpp"
