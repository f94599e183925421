#pragma once
// furniture_fem/restraints.hpp: the restraints module (docs/restraints/restraints.md): fastening devices
// (l_bracket, strap, mat, pole) between a point of an item and the room, their force laws, regimes,
// failure and energy (restraints/restraint.hpp), and a room's set of them (restraints/restraint_set.hpp).
#include "restraints/restraint.hpp"
#include "restraints/restraint_set.hpp"
