#pragma once
// furniture_fem/io.hpp: the io module (CSV tables, VTU/PVD series, a results folder's lock).
#include "io/csv.hpp"
#include "io/folder_lock.hpp"
#include "io/vtk.hpp"
