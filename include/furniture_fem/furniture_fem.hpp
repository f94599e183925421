#pragma once
// furniture_fem/furniture_fem.hpp: everything.
#include "core.hpp"
#include "odeint.hpp"
#include "restraints.hpp"
#include "contact.hpp"
#include "excitation.hpp"
#include "furniture.hpp"
#include "harm.hpp"
#include "io.hpp"
#include "figures.hpp"
#include "scene.hpp"
#include "study.hpp"
