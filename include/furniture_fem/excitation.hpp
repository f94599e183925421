#pragma once
// furniture_fem/excitation.hpp: the excitation module (ground-motion records, processing, spectra, synthetic motions).
#include "excitation/excitation.hpp"
#include "excitation/known_records.hpp"
