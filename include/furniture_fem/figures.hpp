#pragma once
// furniture_fem/figures.hpp: the figures module (line plots, room views, PNG).
#include "figures/plot.hpp"
