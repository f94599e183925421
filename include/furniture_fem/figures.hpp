#pragma once
// furniture_fem/figures.hpp: the figures module (line plots, room views; PNG, SVG, PDF through cairo).
#include "figures/plot.hpp"
