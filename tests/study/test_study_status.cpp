// A study's honest status (issue 51): what a run would refuse at its start fails when the study is
// read, naming the study's key, the variant, the motion and the level; an empty suite of motions and
// an unnamed motion are errors; a study in which runs did not complete says why (the first one's
// reason and how many share it) and summary.json says "failed" when none completed; --resume on a
// changed study names the keys that differ; a scene without a ground_motion runs its default motion.
#include <catch2/catch.hpp>

#include <furniture_fem/study/realisation.hpp>
#include <furniture_fem/study/runner.hpp>

#include "../support/test_files.hpp"

#include <filesystem>
#include <fstream>
#include <string>

using namespace furniture_fem;
using nlohmann::json;

namespace study_status_tests {  // this file's own names (its group compiles files in batches)

namespace {

// A rigid block at the table's centre, shaken by a synthetic motion of `motion_s` seconds.
json synthetic(double motion_s, int seed = 1) {
  return {{"source", "synthetic"}, {"seed", seed}, {"duration", motion_s}, {"dimensions", "1d"}};
}
json block_scene(double duration) {
  return {{"name", "block"},
          {"items", {{{"kind", "block"}, {"name", "crate"}, {"fidelity", "rigid"},
                      {"params", {{"width", 0.4}, {"depth", 0.4}, {"height", 0.4}, {"mass_kg", 20.0}}}}}},
          {"ground_motion", synthetic(3.0)},
          {"contact", {{"law", "stiff"}}},
          {"duration", duration},
          {"outputs", {{"figures", false}}}};
}
json two_motion_study() {
  return {{"name", "short"},
          {"scene", block_scene(1.0)},
          {"ground_motions", {{{"name", "long"}, {"ground_motion", synthetic(3.0)}},
                              {{"name", "brief"}, {"ground_motion", synthetic(1.0, 2)}}}},
          {"duration", 2.0}};
}

std::string error_of(const json& study) {
  try {
    (void)parse_study_json(study, "study.json");
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

TEST_CASE("a study whose duration passes a motion's end fails when read, naming the motion", "[study][status]") {
  // The study's own duration: its key.
  CHECK(error_of(two_motion_study()) ==
        "study.json: duration: variant 'base', motion 'brief', level 1: the run lasts 2 s but the synthetic motion "
        "lasts 1 s (ground_motion.duration): shorten the run to at most 1 s, lengthen ground_motion.duration, or set "
        "ground_motion.pad_after_end: true to run on with the table at rest after the motion");
  // The scene's duration, under a variant and the second of three levels that scale the motion.
  json j = two_motion_study();
  j.erase("duration");
  j["scene"]["duration"] = 2.0;
  j["intensity"] = {{"measure", "pga"}, {"levels", {1.0, 2.5, 4.0}}};
  j["compare"] = {{{"name", "paper"}}, {{"name", "stiff"}, {"scene", {{"contact", {{"law", "stiff"}}}}}}};
  CHECK(error_of(j) ==
        "study.json: scene.duration: variant 'paper', motion 'brief', level 1: the run lasts 2 s but the synthetic "
        "motion lasts 1 s (ground_motion.duration): shorten the run to at most 1 s, lengthen ground_motion.duration, or "
        "set ground_motion.pad_after_end: true to run on with the table at rest after the motion");
  // Asked for with pad_after_end: read without a word.
  j["ground_motions"][1]["ground_motion"]["pad_after_end"] = true;
  CHECK(error_of(j) == "no error");
}

TEST_CASE("a record window that a start-time perturbation moves past the record's end fails when read",
          "[study][status]") {
  // A 1 s record (columns, m/s^2), runs of 0.5 s: fine from the start, not from 0.8 s on.
  const std::string dir = ffem_test::tmp("study_status_record");
  std::filesystem::create_directories(dir);
  {
    std::ofstream f(dir + "/pulse.txt");
    for (int i = 0; i <= 100; ++i) f << i * 0.01 << " " << (i % 2 ? 1.0 : -1.0) << "\n";
  }
  json j = {{"name", "late"},
            {"scene", block_scene(0.5)},
            {"ground_motions", {{{"name", "pulse"},
                                 {"ground_motion", {{"source", "file"}, {"format", "columns"}, {"units", "m/s2"},
                                                    {"files", {{"x", "pulse.txt"}}}, {"dimensions", "1d"}}}}}},
            {"perturbations", {{"start_time", 0.8}}}};
  const auto error_in = [&](const json& study) {
    try {
      (void)parse_study_json(study, dir + "/late.json", dir);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  CHECK(error_in(j) ==
        dir + "/late.json: perturbations.start_time: variant 'base', motion 'pulse', level 1: a realisation's record "
              "window may start up to 0.8 s later, and then scene.duration: the run lasts 0.5 s but the record ends "
              "0.2 s after the run's start (ground_motion.window from 0.8 s of record time): shorten the run to at most "
              "0.2 s, move or widen ground_motion.window, or set ground_motion.pad_after_end: true to run on with the "
              "table at rest after the motion");
  j["perturbations"]["start_time"] = 0.4;
  CHECK(error_in(j) == "no error");
  // The window itself past the record's end: the motion's key in the suite.
  j["ground_motions"][0]["ground_motion"]["window"] = {{"start", 0.0}, {"end", 1.5}};
  CHECK_THAT(error_in(j), Catch::Matchers::StartsWith(dir + "/late.json: ground_motions[0].ground_motion.window.end: "
                                                            "variant 'base', motion 'pulse', level 1: 1.5 s is past the end "
                                                            "of record 'pulse'"));
}

TEST_CASE("an empty suite of motions and an unnamed motion are errors naming the key", "[study][status]") {
  json j = two_motion_study();
  j["duration"] = 1.0;
  REQUIRE(error_of(j) == "no error");
  j["ground_motions"] = json::array();
  CHECK(error_of(j) ==
        "study.json: ground_motions: is empty: list at least one {\"name\", \"ground_motion\"}, or leave the key out to "
        "run the scene's own ground_motion");
  j = two_motion_study();
  j["duration"] = 1.0;
  j["ground_motions"][1].erase("name");
  CHECK(error_of(j) ==
        "study.json: ground_motions[1].name: required: a name for the motion, e.g. \"kobe_ns\" (it labels the results "
        "and keys the realisations' random draws)");
}

TEST_CASE("a run's reason for not completing, its numbers aside", "[study][status]") {
  RunResult a, b, c;
  a.status = b.status = c.status = "failed";
  a.diagnosis = "s.json (realisation 3, variant 'v1'): items[0]: item 'crate_2' corner (2.03, -0.2) m is off the 4 m table";
  b.diagnosis = "s.json (realisation 12, variant 'v1'): items[0]: item 'crate_2' corner (-1.5e-3, 0.2) m is off the 4 m table";
  c.diagnosis = "s.json (realisation 12, variant 'v1'): items[1]: item 'crate_2' corner (-1.5e-3, 0.2) m is off the 4 m table";
  CHECK(failure_reason(a) == "failed: s.json (realisation #, variant 'v1'): items[0]: item 'crate_2' corner (#, #) m is "
                             "off the # m table");
  CHECK(failure_reason(b) == failure_reason(a));
  CHECK(failure_reason(c) != failure_reason(a));  // another item
  RunResult ok;
  ok.status = "completed";
  const StudyFailures f = study_failures({ok, a, c, b});
  CHECK(f.completed == 1);
  CHECK(f.not_completed == 3);
  CHECK(f.first.diagnosis == a.diagnosis);
  CHECK(f.same_reason == 2);
}

TEST_CASE("a study in which no run completed says failed, and why", "[study][status]") {
  // The block against the +x wall: any turn puts a corner off the table, so every realisation's scene
  // is refused when its run starts (the unperturbed scene, checked when the study is read, is fine).
  json j = {{"name", "against_the_wall"},
            {"scene", block_scene(0.05)},
            {"perturbations", {{"yaw_deg", 10.0}}},
            {"realisations", 3}};
  j["scene"]["items"][0]["x"] = 1.8;
  const StudySpec s = parse_study_json(j, "wall.json");
  StudyOptions o;
  o.out_dir = ffem_test::tmp("study_status_failed");
  std::filesystem::remove_all(o.out_dir);
  o.workers = 1;
  o.progress = false;
  CHECK(run_study(s, o) == "failed");
  const json summary = json::parse(ffem_test::slurp(o.out_dir + "/summary.json"));
  CHECK(summary["status"] == "failed");
  CHECK(summary["not_completed"] == 3);
  CHECK(summary["first_not_completed"]["run"] == 0);
  CHECK(summary["first_not_completed"]["status"] == "failed");
  CHECK(summary["first_not_completed"]["runs_for_this_reason"] == 3);
  CHECK_THAT(summary["first_not_completed"]["diagnosis"].get<std::string>(),
             Catch::Matchers::StartsWith("wall.json (realisation 0, variant 'base'): items[0]: item 'crate' lies partly "
                                         "outside the 4 m x 4 m table"));
}

TEST_CASE("--resume on a changed study names the keys that differ, old and new", "[study][status]") {
  json j = two_motion_study();
  j["duration"] = 0.05;
  j["realisations"] = 1;
  StudyOptions o;
  o.out_dir = ffem_test::tmp("study_status_changed");
  std::filesystem::remove_all(o.out_dir);
  o.workers = 1;
  o.progress = false;
  const std::atomic<bool> stop{true};  // the folder and study.json, no run
  REQUIRE(run_study(parse_study_json(j, "first.json"), o, &stop) == "stopped");
  j["duration"] = 0.04;
  j["seed"] = 5;
  j["ground_motions"][1]["name"] = "other";
  j["intensity"] = {{"levels", {1.0, 2.0}}};
  o.resume = true;
  CHECK_THROWS_WITH(StudyFolder(parse_study_json(j, "second.json"), o),
                    o.out_dir + "/study.json: --resume: this folder holds another study: its study.json differs from "
                                "second.json in duration: 0.04 (was 0.05); ground_motions[1].name: \"other\" (was "
                                "\"brief\"); intensity.levels[1]: 2.0 (was (absent)); seed: 5 (was 1); resume with the "
                                "same study file, or use another --out");
  // More than four: the rest counted.
  j["realisations"] = 2;
  j["name"] = "changed";
  CHECK_THROWS_WITH(StudyFolder(parse_study_json(j, "third.json"), o),
                    Catch::Matchers::EndsWith("; name: \"changed\" (was \"short\"); and 2 more; resume with the same "
                                              "study file, or use another --out"));
}

TEST_CASE("a study of a scene without a ground_motion runs the scene's default motion at each level",
          "[study][status]") {
  // Each run failed with "cannot use value() with null" before, and the study still said "completed".
  json j = {{"name", "default_motion"}, {"scene", block_scene(0.05)}, {"intensity", {{"levels", {0.5, 2.0}}}}};
  j["scene"].erase("ground_motion");
  const StudySpec s = parse_study_json(j, "default_motion.json");
  const json scene = realisation_scene_json(s, realisation_parameters(s, 1), 0);
  CHECK(scene["ground_motion"] == json{{"level", 2.0}});
  const RunResult r = run_realisation(s, 1);
  CHECK(r.status == "completed");
  CHECK(r.t_end == Approx(0.05).margin(1e-12));
}

}  // namespace study_status_tests
