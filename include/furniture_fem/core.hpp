#pragma once
// furniture_fem/core.hpp: the core module (model, elements, integrators, linear solvers, simulation, modal analysis; Eigen only).
#include "core/errors.hpp"
#include "core/text.hpp"
#include "core/model.hpp"
#include "core/elements.hpp"
#include "core/integrators.hpp"
#include "core/solvers.hpp"
#include "core/statics.hpp"
#include "core/simulation.hpp"
#include "core/modal.hpp"
