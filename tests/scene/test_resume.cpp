// Checkpoint and resume (RunOptions::checkpoint_every, resume; docs/io/output.md, "Checkpoints"): a run
// stopped at a step, or killed after its last checkpoint, and resumed writes the files of the run that
// was never stopped, byte for byte (the histories, the VTU frames, the final states, the figures; of
// summary.json everything but the wall times). A resume that cannot be right is refused, naming why.
// No test reads ../shared: the motions are the built-in synthetic ones.
#include <catch2/catch.hpp>

#include <furniture_fem/scene/reader.hpp>
#include <furniture_fem/scene/scene_runner.hpp>

#include "../support/cubic_law.hpp"
#include "../support/stop_after.hpp"

#include <algorithm>
#include <atomic>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <string>
#include <string_view>
#include <vector>

using namespace furniture_fem;

namespace resume_tests {  // this file's own names (its group compiles files in batches)
namespace fs = std::filesystem;

namespace {

std::string fresh_dir(const std::string& name) {
  const fs::path p = fs::path(FFEM_TEST_TMP) / "resume" / name;
  fs::remove_all(p);
  fs::create_directories(p.parent_path());
  return p.string();
}

std::string slurp(const fs::path& path) {
  std::ifstream f(path, std::ios::binary);
  REQUIRE(f.good());
  return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}

// The paper's configuration 3 (the default main job's room) under the synthetic 3-D motion: stacked
// rigid cabinets (a rigid group), flexible items, item-item pairs. `variant` 1: every item full, the
// stick_slip law (a friction history), iterated to equilibrium; 2: contact at the members' surfaces;
// 3: every item rigid, rigid pairs by their hulls; 4: variant 3 from a settled start (contact.start);
// 5: variant 3 under a law the test program registers (its own parameter k3 in every contact's set);
// 6: every item full, inside the step (a flexible group).
SceneSpec room(int variant) {
  SceneSpec spec = configuration(3, "");
  spec.ground_motion = GroundMotionSpec{};
  spec.ground_motion.source = MotionSource::synthetic;
  spec.ground_motion.pga = 8.0;
  spec.ground_motion.dimensions = MotionDimensions::three_d;
  spec.duration = 0.4;
  spec.outputs.vtu_every = 50;
  if (variant == 1) {
    for (auto& it : spec.items) it.fidelity = Fidelity::full;
    spec.contact.law = law_kind<StickSlipSceneLaw>;
    spec.integrator.iterate_to_equilibrium = true;
    spec.duration = 0.15;
  }
  // Variant 2: floor and wall contact at the members' surfaces (a rigid group's envelope, a flexible
  // node's cube corners; their histories and which cubes are within reach of a plane).
  if (variant == 2) spec.contact.plane_contact_at = PlaneContactAt::surfaces;
  // Variant 3: every item rigid, meeting by their hulls (the hull contacts' records and named
  // histories, the stacked cabinets' rigid group through them).
  if (variant >= 3) {
    for (auto& it : spec.items) it.fidelity = Fidelity::rigid;
    spec.contact.rigid_pairs = RigidPairContact::hulls;
    spec.outputs.sectional_forces.clear();  // a rigid desk has no such member
  }
  // Variant 4: the settled state and its figures (summary.json settled_start) come back from the checkpoint.
  if (variant == 4) spec.contact.start = ContactStart::settled;
  if (variant == 5) spec.contact.law = ffem_test::cubic_law();
  // Variant 6: every item full and inside the step, so the stacked cabinets are a flexible group solved
  // near its kept factorisation (GMRES): that factorisation comes back from the checkpoint.
  if (variant == 6) {
    for (auto& it : spec.items) it.fidelity = Fidelity::full;
    spec.contact.implicit = ImplicitContact::all;
    spec.duration = 0.1;
  }
  // Variant 7: variant 3 with restraints, occupants and an exit: the tall cabinet's two weak brackets into the wall board (they
  // yield and pull out in the run) and a slack strap on the upper cabinet; their histories, regimes and
  // break times come back from the checkpoint (restraints.csv, restraints.png, summary.json).
  if (variant == 7) {
    for (const char* corner : {"top_back_left", "top_back_right"}) {
      RestraintSpec r;
      r.name = std::string("tc_") + corner;
      r.kind = RestraintKind::l_bracket;
      r.item = "tall_cabinet";
      r.point = corner;
      r.wall = "wall_plus_x";
      r.screws = ScrewBase::board;
      r.values = {{"strength", 40.0}, {"softening", 0.002}};
      spec.restraints.push_back(r);
    }
    RestraintSpec strap;
    strap.name = "upper_strap";
    strap.kind = RestraintKind::strap;
    strap.item = "separated_cabinets/upper";
    strap.point = "top_back_left";
    strap.wall = "wall_plus_x";
    strap.values = {{"slack", 0.002}};
    spec.restraints.push_back(strap);
    // And two occupants, one a sensor and one a rigid obstacle: the watches' last intrusions and forces
    // and a strike under way come back from the checkpoint (strikes.csv, summary.json's occupants).
    Occupant clerk;
    clerk.name = "clerk";
    clerk.position = Vec2(-0.1, 0.0);
    clerk.posture = Posture::seated;
    clerk.height = 1.3, clerk.body_radius = 0.3;
    Occupant visitor;
    visitor.name = "visitor";
    visitor.position = Vec2(1.22, -0.5);
    visitor.obstacle = true;  // a rigid obstacle: its strikes' force records come back too
    spec.occupants = {clerk, visitor};
    // And an exit along the aisle in front of the cabinets: its first blocking and narrowest section
    // come back from the checkpoint (exits.csv, summary.json's exits).
    ExitSpec aisle;
    aisle.name = "aisle";
    aisle.path = {Eigen::Vector2d(1.3, -1.5), Eigen::Vector2d(1.3, 1.5)};
    aisle.width = 0.5;
    spec.exits = {aisle};
    spec.outputs.figures = true;
  }
  return spec;
}

using ffem_test::StopAfter;

RunOptions options(const std::string& out, std::atomic<bool>& stop) {
  RunOptions o;
  o.out_dir = out;
  o.progress = false;
  o.stop = &stop;
  return o;
}

// The uninterrupted run of a variant, run once per test program.
const std::string& whole_run(int variant) {
  static std::map<int, std::string> done;
  if (const auto it = done.find(variant); it != done.end()) return it->second;
  std::atomic<bool> never{false};
  const std::string dir = fresh_dir("whole_" + std::to_string(variant));
  StopAfter none(never, -1);
  REQUIRE(run_scene(room(variant), options(dir, never), {&none}).status == "completed");
  return done[variant] = dir;
}

// Every file of the uninterrupted run's folder, the same in the resumed one (summary.json without its
// wall times; run.json records when each part ran).
void require_same_results(const std::string& whole, const std::string& resumed) {
  int files = 0;
  for (const auto& e : fs::recursive_directory_iterator(whole)) {
    if (!e.is_regular_file()) continue;
    const fs::path rel = fs::relative(e.path(), whole);
    INFO(rel.string());
    if (rel == "run.json") continue;
    REQUIRE(fs::exists(fs::path(resumed) / rel));
    if (rel == "summary.json") {
      auto a = nlohmann::json::parse(slurp(e.path())), b = nlohmann::json::parse(slurp(fs::path(resumed) / rel));
      for (auto* j : {&a, &b}) j->erase("wall_seconds"), j->erase("step_time_s");
      REQUIRE(a == b);
    } else {
      REQUIRE(slurp(e.path()) == slurp(fs::path(resumed) / rel));
    }
    ++files;
  }
  CHECK(files >= 10);
  CHECK_FALSE(fs::exists(fs::path(resumed) / "checkpoint.bin"));  // a completed run removes it
}

}  // namespace

TEST_CASE("a run stopped at a step and resumed writes the uninterrupted run's files", "[runner][resume][slow]") {
  for (const auto& [variant, stop_at] : std::vector<std::pair<int, long>>{{0, 1}, {0, 187}, {1, 113}, {2, 211}, {3, 233}, {4, 151}, {5, 97}, {6, 61}, {7, 173}}) {
    INFO("variant " << variant << ", stopped after step " << stop_at);
    const SceneSpec spec = room(variant);
    std::atomic<bool> never{false}, stop{false};
    const std::string& whole = whole_run(variant);
    StopAfter none(never, -1);

    const std::string part = fresh_dir("part_" + std::to_string(variant) + "_" + std::to_string(stop_at));
    StopAfter stopper(stop, stop_at);
    const RunSummary first = run_scene(spec, options(part, stop), {&stopper});
    REQUIRE(first.status == "stopped");
    REQUIRE(first.steps == stop_at);
    REQUIRE(fs::exists(part + "/checkpoint.bin"));
    CHECK(nlohmann::json::parse(slurp(part + "/run.json"))["status"] == "interrupted");

    RunOptions again = options(part, never);
    again.resume = true;
    const RunSummary rest = run_scene(spec, again, {&none});
    REQUIRE(rest.status == "completed");
    CHECK(nlohmann::json::parse(slurp(part + "/run.json"))["resumed_from_t_s"].get<double>() ==
          Approx(stop_at * spec.dt));
    require_same_results(whole, part);
  }
}

TEST_CASE("a run killed after its last checkpoint resumes from it, cutting back what it wrote since",
          "[runner][resume][slow]") {
  // Stopped at step 150 (its checkpoint kept aside), resumed and stopped again at step 200 (rows and
  // frames written after step 150), then the step-150 checkpoint put back: what a kill at step 200
  // leaves of a run whose last periodic checkpoint was at step 150. Resumed twice in all.
  const SceneSpec spec = room(0);
  std::atomic<bool> never{false}, stop{false};
  const std::string& whole = whole_run(0);
  StopAfter none(never, -1);

  const std::string part = fresh_dir("killed_part");
  StopAfter at_150(stop, 150);
  REQUIRE(run_scene(spec, options(part, stop), {&at_150}).status == "stopped");
  fs::copy_file(part + "/checkpoint.bin", part + "/kept.bin");
  stop = false;
  RunOptions again = options(part, stop);
  again.resume = true;
  StopAfter at_200(stop, 200);
  REQUIRE(run_scene(spec, again, {&at_200}).status == "stopped");
  fs::rename(part + "/kept.bin", part + "/checkpoint.bin");

  RunOptions last = options(part, never);
  last.resume = true;
  REQUIRE(run_scene(spec, last, {&none}).status == "completed");
  CHECK(nlohmann::json::parse(slurp(part + "/run.json"))["resumed_from_t_s"].get<double>() == Approx(0.15));
  require_same_results(whole, part);
}

TEST_CASE("a resume that cannot give the uninterrupted run is refused, naming why", "[runner][resume][input]") {
  SceneSpec spec = room(0);
  spec.duration = 0.02;
  std::atomic<bool> never{false}, stop{false};
  const std::string dir = fresh_dir("refused");
  StopAfter stopper(stop, 5);
  REQUIRE(run_scene(spec, options(dir, stop), {&stopper}).status == "stopped");
  StopAfter none(never, -1);
  RunOptions again = options(dir, never);
  again.resume = true;

  SECTION("another scene") {
    SceneSpec other = spec;
    other.dt = 5e-4;
    REQUIRE_THROWS_WITH(run_scene(other, again, {&none}),
                        Catch::Contains("checkpoint.bin") && Catch::Contains("scene.dt") &&
                            Catch::Contains("the checkpoint's run had 0.001") && Catch::Contains("same scene file"));
  }
  SECTION("another run length") {
    again.duration = 0.03;
    REQUIRE_THROWS_WITH(run_scene(spec, again, {&none}), Catch::Contains("duration_s"));
  }
  SECTION("other observers") {
    REQUIRE_THROWS_WITH(run_scene(spec, again), Catch::Contains("observers") && Catch::Contains("checkpoint.bin"));
  }
  SECTION("a damaged checkpoint") {
    const std::string bytes = slurp(dir + "/checkpoint.bin");
    std::ofstream(dir + "/checkpoint.bin", std::ios::binary | std::ios::trunc) << bytes.substr(0, bytes.size() - 100);
    REQUIRE_THROWS_WITH(run_scene(spec, again, {&none}), Catch::Contains("checkpoint.bin") && Catch::Contains("damaged"));
  }
  SECTION("a results file shortened since") {
    fs::resize_file(dir + "/energy.csv", 10);
    REQUIRE_THROWS_WITH(run_scene(spec, again, {&none}),
                        Catch::Contains("energy.csv") && Catch::Contains("cannot go on from the checkpoint"));
  }
  SECTION("a completed run") {
    REQUIRE(run_scene(spec, again, {&none}).status == "completed");
    REQUIRE_THROWS_WITH(run_scene(spec, again, {&none}), Catch::Contains("completed") && Catch::Contains("--resume"));
  }
  SECTION("a folder with no checkpoint") {
    const std::string empty = fresh_dir("no_checkpoint");
    fs::create_directories(empty);
    RunOptions none_there = options(empty, never);
    none_there.resume = true;
    REQUIRE_THROWS_WITH(run_scene(spec, none_there, {&none}), Catch::Contains("no checkpoint"));
  }
}

namespace {

void write_file(const std::string& path, const std::string& bytes) {
  std::ofstream f(path, std::ios::binary | std::ios::trunc);
  f.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  REQUIRE(f.good());
}

// Every byte of a file up to 8 KB; of a longer one, its first and last 4 KB and about 2000 bytes between.
std::vector<std::size_t> positions_to_damage(std::size_t size) {
  const std::size_t edge = 4096, head = std::min(size, edge), tail = std::max(head, size - std::min(size, edge));
  std::vector<std::size_t> at;
  for (std::size_t i = 0; i < head; ++i) at.push_back(i);
  for (std::size_t i = head; i < tail; i += std::max<std::size_t>(1, (tail - head) / 2000)) at.push_back(i);
  for (std::size_t i = tail; i < size; ++i) at.push_back(i);
  return at;
}

// One side table, 20 steps: a checkpoint far smaller than the room's 17 MB.
SceneSpec small_scene() {
  return parse_scene_json(nlohmann::json::parse(R"({
    "name": "checkpoint check",
    "items": [{"kind": "side_table", "x": 0.0, "y": 0.0, "yaw_deg": 0}],
    "ground_motion": {"source": "synthetic", "seed": 3, "pga": 6.0, "dimensions": "3d"},
    "duration": 0.02,
    "dt": 0.001,
    "outputs": {"figures": false, "vtu_every": 10}
  })"),
                          "small.json");
}

}  // namespace

TEST_CASE("a checkpoint with any byte damaged or cut short is refused; the untouched one resumes",
          "[runner][resume][input][checkpoint]") {
  const SceneSpec spec = small_scene();
  std::atomic<bool> never{false}, stop{false};
  const std::string dir = fresh_dir("damaged");
  StopAfter stopper(stop, 5);
  REQUIRE(run_scene(spec, options(dir, stop), {&stopper}).status == "stopped");
  const std::string path = dir + "/checkpoint.bin", good = slurp(path);
  INFO("checkpoint of " << good.size() << " bytes");
  REQUIRE(good.size() > 64);
  CHECK(detail::checked_checkpoint_state(good, path).size() == good.size() - checkpoint_checksum_bytes);

  // The sum is checked before anything is read: every damaged copy is refused by it alone.
  long missed = 0, tried = 0;  // missed: accepted, or refused without naming the file
  std::size_t first_missed = good.size();
  for (const std::size_t i : positions_to_damage(good.size()))
    for (const unsigned flip : {0xffu, 0x01u, 0x80u}) {
      std::string bad = good;
      bad[i] = static_cast<char>(static_cast<unsigned char>(bad[i]) ^ flip);
      ++tried;
      bool named = false;
      try {
        detail::checked_checkpoint_state(bad, path);
      } catch (const InputError& e) {
        named = std::string(e.what()).find("checkpoint.bin") != std::string::npos;
      }
      if (!named && missed++ == 0) first_missed = i;
    }
  INFO(tried << " damaged copies tried; the first missed: byte " << first_missed);
  CHECK(tried >= 3 * std::min<long>(static_cast<long>(good.size()), 2 * 4096 + 2000));
  CHECK(missed == 0);

  // Through a resume: the magic line, the fingerprint, the state, the last state byte, the sum.
  StopAfter none(never, -1);
  RunOptions again = options(dir, never);
  again.resume = true;
  for (const std::size_t i : {std::size_t(0), std::size_t(9), std::size_t(40), good.size() / 2, good.size() - 5,
                              good.size() - 4, good.size() - 1}) {
    INFO("byte " << i << " flipped");
    std::string bad = good;
    bad[i] = static_cast<char>(bad[i] ^ 0x10);
    write_file(path, bad);
    REQUIRE_THROWS_AS(run_scene(spec, again, {&none}), InputError);
    REQUIRE_THROWS_WITH(run_scene(spec, again, {&none}), Catch::Contains("checkpoint.bin") && Catch::Contains("damaged"));
  }
  for (const std::size_t n : {std::size_t(0), std::size_t(1), std::size_t(11), good.size() / 2, good.size() - 4,
                              good.size() - 1}) {
    INFO("cut to " << n << " bytes");
    CHECK_THROWS_AS(detail::checked_checkpoint_state(std::string_view(good).substr(0, n), path), InputError);
    write_file(path, good.substr(0, n));
    REQUIRE_THROWS_WITH(run_scene(spec, again, {&none}), Catch::Contains("checkpoint.bin") && Catch::Contains("damaged"));
  }
  // A damaged checkpoint is refused before the run touches its files: the good one still resumes.
  write_file(path, good);
  REQUIRE(run_scene(spec, again, {&none}).status == "completed");
}

TEST_CASE("a checkpoint of another format is refused as such, not as damaged", "[runner][resume][input][checkpoint]") {
  const SceneSpec spec = small_scene();
  std::atomic<bool> never{false}, stop{false};
  const std::string dir = fresh_dir("format_4");
  StopAfter stopper(stop, 5);
  REQUIRE(run_scene(spec, options(dir, stop), {&stopper}).status == "stopped");
  std::string old = slurp(dir + "/checkpoint.bin");
  old.resize(old.size() - checkpoint_checksum_bytes);  // format 4 had no sum
  old[8 + checkpoint_magic.size() - 1] = '4';
  write_file(dir + "/checkpoint.bin", old);
  StopAfter none(never, -1);
  RunOptions again = options(dir, never);
  again.resume = true;
  REQUIRE_THROWS_WITH(run_scene(spec, again, {&none}),
                      Catch::Contains("checkpoint.bin") && Catch::Contains("another version") &&
                          Catch::Contains("furniture_fem checkpoint 4"));
}

TEST_CASE("a run refuses a results folder another run holds, before it writes there", "[runner][lock]") {
  SceneSpec spec = room(0);
  spec.duration = 0.02;
  std::atomic<bool> never{false};
  const std::string dir = fresh_dir("locked");
  const FolderLock other(dir);  // as another run would hold it
  std::ofstream(dir + "/run.json") << R"({"program": "furniture_fem", "status": "running"})";
  const std::string before = slurp(dir + "/run.json");
  RunOptions opt = options(dir, never);
  opt.overwrite = true;
  REQUIRE_THROWS_WITH(run_scene(spec, opt), Catch::Contains("results folder '" + dir + "' is in use by process"));
  opt.overwrite = false;
  opt.resume = true;
  REQUIRE_THROWS_WITH(run_scene(spec, opt), Catch::Contains("is in use by process"));
  CHECK(slurp(dir + "/run.json") == before);
}

}  // namespace resume_tests
