#pragma once
// furniture_fem/scene/scene_runner.hpp: run a scene (scene.hpp) end to end; the public entry of the runner.
//
//   RunSummary run_scene(const SceneSpec&, const RunOptions& = {}, const std::vector<RunObserver*>& extra = {})
//
// The runner is a short loop (runner.hpp) over a list of observers (observer.hpp: begin, after_step,
// end), picked from the scene's outputs and the RunOptions (observers.hpp): a progress bar; the final
// state of every item and the sectional force peaks (in the RunSummary); and, unless
// RunOptions::write_files is false, marker, sectional-force, energy and contact-force histories
// (CSV), a VTU/PVD time series, final_state.json, summary.json and PNG figures, with run.json written
// first and last into a results folder it may write into (results_folder.hpp). A user adds an
// output by writing a RunObserver and passing it as `extra` (docs/io/output.md,
// examples/step-6-custom-observer). The scene's simulation itself: scene_simulation.hpp.
#include "observer.hpp"
#include "observers.hpp"
#include "results_folder.hpp"
#include "run_checkpoint.hpp"
#include "runner.hpp"
#include "scene_simulation.hpp"
