#pragma once
// furniture_fem/furniture.hpp: the furniture module (parametric builders of the paper's items).
#include "furniture/furniture.hpp"
#include "furniture/item_kinds.hpp"
