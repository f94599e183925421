#pragma once
// furniture_fem/ffem.hpp: the short alias `ffem` for the furniture_fem namespace, for those who want
// it (the examples in docs/ use it). Opt-in: no other header declares it, so it cannot clash with a
// name of the includer's.
namespace furniture_fem {}
namespace ffem = furniture_fem;
