// step-9: a contact law of your own.
//
// What is new relative to step-8: the contact law. This file defines one (a Hertz spring, with a
// stiffness of its own, under the paper's damping and friction), registers it, and from then on scene
// files and study variants name it as they name a built-in law: configuration 3 runs under it, and a
// small study compares it with the paper's law on the same realisations. Nothing in the library is
// edited, and the program compiles none of the solver: it links the compiled scene runner, whose one
// run path takes any registered law as a run-time kernel (docs/contact/contact.md, "Adding a contact law"),
// and the compiled study, whose runs take that path.
#include <furniture_fem/scene/laws/law_list.hpp>
#include <furniture_fem/scene/paper_configurations.hpp>
#include <furniture_fem/scene/run_scene.hpp>
#include <furniture_fem/study/runner.hpp>

#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <string_view>

using namespace furniture_fem;

namespace {

// The normal part: k_hertz d^1.5 on the overlap d = L - l. It declares the parameter it reads, k_hertz,
// kept in the law's slot 0 (ContactParams::law_params[0]); the paper's parts declare theirs (dc_kgf, q, mu,
// mu_long), and the law's scene keys are those of its parts.
struct HertzSpring {
  static constexpr std::array parameters{
      LawParameter{.key = "k_hertz", .unit = "N/m^1.5", .lo = 0, .hi = 1e15, .lo_exclusive = true, .default_value = 3e7,
                   .meaning = "Hertz spring k_hertz (L - l)^1.5 per node", .per_node = true, .slot = 0},
  };
  double force(const ContactKinematics& k, const ContactParams& p, double, double) const {
    const double d = k.L - k.l;
    return p.law_params[0] * d * std::sqrt(d);
  }
  double stiffness(const ContactKinematics& k, const ContactParams& p, double, double) const {
    return 1.5 * p.law_params[0] * std::sqrt(k.L - k.l);
  }
};

// The scene law: its name and its composed law.
struct HertzPaperSceneLaw : SceneLawDefaults {
  static constexpr std::string_view name = "hertz_paper";
  using law = ContactLaw<HertzSpring, PaperSignDamping, PaperSignFriction>;
};

const char* study_json = R"({
  "name": "step-9",
  "seed": 9,
  "scene": {
    "name": "tall cabinet alone",
    "items": [{"kind": "tall_cabinet", "name": "cabinet", "fidelity": "rigid"}],
    "ground_motion": {"source": "synthetic", "duration": 3.0, "dimensions": "3d"},
    "duration": 3.0,
    "outputs": {"figures": false}
  },
  "intensity": {"measure": "pga", "levels": [4.0, 8.0]},
  "perturbations": {"x": 0.01, "yaw_deg": 1.0, "friction": 0.1},
  "realisations": 4,
  "compare": [{"name": "paper", "scene": {"contact": {"law": "paper"}}},
              {"name": "hertz", "scene": {"contact": {"law": "hertz_paper", "floor": {"k_hertz": 3e7}}}}]
})";

}  // namespace

int main() {
  // 1. Register: from here on "hertz_paper" is a contact law of scene files and studies.
  const ContactLawKind hertz = register_contact_law<HertzPaperSceneLaw>();
  const std::string table = contact_law_table(contact_law_registry());
  const auto row = table.find("| `k_hertz`");
  std::printf("its key, as docs/scene/scene_file.md's table would show it:\n%s\n",
              table.substr(row, table.find('\n', row) - row).c_str());

  // 2. Configuration 3 under it: 1 s of a synthetic 3-D motion (no record files needed).
  SceneSpec room = configuration(3, "");
  room.ground_motion = GroundMotionSpec{};
  room.ground_motion.source = MotionSource::synthetic;
  room.ground_motion.pga = 6.0;
  room.ground_motion.dimensions = MotionDimensions::three_d;
  room.duration = 1.0;
  room.contact.law = hertz;
  // Every item's floor contact inside the implicit step (the scene default; configuration 3 keeps the
  // paper's explicit contact for its finite-element items, and the Hertz spring, stiffer at rest than the
  // paper's penalty, would need dt ~ 0.1 ms there: run_scene refuses dt = 1 ms, naming the chair).
  room.contact.implicit = ImplicitContact::all;
  room.outputs.folder = "step-9-out";
  room.outputs.figures = false;
  RunOptions opt;
  opt.overwrite = true;
  opt.progress = false;
  const RunSummary sum = run_scene(room, opt);
  std::printf("\nconfiguration 3 under hertz_paper: %s, %ld steps; results in step-9-out\n", sum.status.c_str(),
              sum.steps);
  for (const auto& f : sum.items)
    std::printf("  %-26s %-15s slide %.3f m, tilt %.1f deg\n", f.name.c_str(), f.state.c_str(), f.slide, f.tilt_deg);

  // 3. A study: the paper's law and this one on the same realisations.
  const StudySpec study = parse_study_json(nlohmann::json::parse(study_json), "step-9 study");
  StudyOptions sopt;
  sopt.out_dir = "step-9-results";
  sopt.overwrite = true;
  sopt.progress = false;
  std::printf("\nstudy: %ld runs (%d levels x %d realisations x %d laws)\n", study.num_runs(), study.num_levels(),
              study.realisations, study.num_variants());
  StudyFolder folder(study, sopt);
  run_local(folder, folder.pending(), 2, nullptr, false);
  folder.finish("completed", {});
  const StudyReport report = study_report(study, folder.results());
  for (const auto& d : report.distributions)
    if (d.outcome == "slide_m")
      std::printf("  %-6s PGA %.0f m/s^2: median slide %.3f m\n", d.variant.c_str(), d.level, d.distribution.median);
  for (const auto& p : report.probabilities)
    if (p.state == std::string("overturned"))
      std::printf("  %-6s PGA %.0f m/s^2: overturned %ld of %ld\n", p.variant.c_str(), p.level, p.estimate.successes,
                  p.estimate.trials);
  std::printf("results in step-9-results (realisations.csv, comparisons.csv, ...)\n");
}
