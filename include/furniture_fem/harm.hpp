#pragma once
// furniture_fem/harm.hpp: the harm module (docs/harm/harm.md): what falling furniture does to the people
// in a room and to its way out. The geometry of an item's box where it is now (harm/item_box.hpp).
#include "harm/item_box.hpp"
#include "harm/impact_form.hpp"
#include "harm/occupant.hpp"
#include "harm/strike.hpp"
