#pragma once
// furniture_fem/scene.hpp: the scene module (scene files, building, running a scene and writing its results).
#include "scene/scene.hpp"
#include "scene/scene_runner.hpp"
