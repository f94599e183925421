#pragma once
// furniture_fem/odeint.hpp: Boost.Odeint steppers driving a Simulation (core + Boost).
#include "odeint/odeint_adapter.hpp"
