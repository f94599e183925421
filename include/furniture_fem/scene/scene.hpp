#pragma once
// furniture_fem/scene/scene.hpp: scenes as data, one header per job: what a run simulates (spec.hpp),
// the parameters of items (item_parameters.hpp; kinds in furniture/item_kinds.hpp), reading and writing
// scene files (reader.hpp, writer.hpp, docs/scene/scene_file.md), validation (validation.hpp), building
// a Model's bodies (build.hpp), the contact laws a scene names (laws/law_list.hpp) and the paper's three
// configurations (paper_configurations.hpp). Nothing here simulates: scene/scene_runner.hpp does.
#include "build.hpp"
#include "item_parameters.hpp"
#include "laws/law_list.hpp"
#include "paper_configurations.hpp"
#include "reader.hpp"
#include "spec.hpp"
#include "validation.hpp"
#include "writer.hpp"
