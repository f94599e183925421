#pragma once
// furniture_fem/io.hpp: the io module (CSV tables, VTU/PVD series).
#include "io/csv.hpp"
#include "io/vtk.hpp"
