// Contact at the members' surfaces (RoomContact::surface, docs/contact/contact.md "At the surface"):
// a rigid frame of 50 mm tubes touches the floor at its outer envelope, so it tips about its outer
// bottom edge, at g b/h with b half the envelope's footprint and h the centre of mass's height above
// the floor, as a solid box does; with contact at the centre lines it tips about the bottom members'
// axes, 25 mm inside and above (g (b - c) / (h - c)), 5.5 % lower for the medium box below.
//  1. a suddenly applied constant table acceleration: 1 % below g b/h the block stays, 1 % above it
//     tips, for two sizes and two friction coefficients (stiff parameters);
//  2. at rest 10 s under gravity: it rests on its envelope (the bottom surface at the floor to the
//     penalty's 2.5 um) and stays still;
//  3. the same frame flexible (each node a cube of corners, force and moment on the node inside the
//     implicit step): it rests with the centre lines' penetration (each corner a quarter of its node)
//     and tips near g b/h of its envelope, a little early because the unbraced frame leans;
//  4. which cubes are tested is an economy, not a model: a flexible frame that tips over (its cubes
//     leaving and reaching the floor) moves the same to the bit whatever the reach lists' margin.
// Measured numbers: docs/contact/verification_contact.md (FFEM_REPORT=1 prints them).
#include <catch2/catch.hpp>

#include <vector>

#include "dynamics_scenes.hpp"

using namespace ffem_dyn;

namespace surface_contact_tests {  // this file's own names (its group compiles files in batches)

namespace {


// A rigid box frame whose floor and wall contact acts at its members' surfaces.
struct SurfaceBlock {
  using Sim = Simulation<AsiGaussTimoshenko, Newmark, DirectLdltSolver, RoomContact>;
  std::unique_ptr<Model> model = std::make_unique<Model>();
  Box box;
  std::unique_ptr<Sim> sim;
  SurfaceBlock(const BoxSpec& spec, double mu, bool surface, bool rigid = true, int refresh_interval_steps = 1,
               double margin = 0.01 /* RoomContact's default */) {
    const int sec = model->add_section(tube()), mat = model->add_material(elastic_steel());
    box = add_box(*model, "block", sec, mat, spec);
    RoomContact contact(*model, {same_everywhere(stiff_params(box, mu))}, {floor_plane()}, SpringDashpotLaw{});
    contact.margin = margin;
    contact.set_surface(*model, surface);
    SimulationOptions options = options_dt(1e-3);
    options.refresh_interval_steps = refresh_interval_steps;
    sim = std::make_unique<Sim>(*model, paper_newmark, options, std::move(contact));
    if (rigid) sim->set_rigid(box.body);
  }
  // Rests 0.3 s, then the table accelerates by A (m/s^2) for 2 s: the largest rise of the higher of
  // the two bottom edges (heel, toe) above the floor, and its rise at the end.
  struct EdgeRise {
    double largest = 0, last = 0;
  };
  EdgeRise sudden_load(double A) {
    sim->run_until(0.3);
    const double t0 = sim->time();
    sim->set_table_acceleration([=](double t) { return Vec3(t > t0 ? A : 0.0, 0, 0); });
    EdgeRise rise;
    sim->run_until(t0 + 2.0, [&](const auto& s, const StepInfo&) {
      rise.last = std::max(mean_z(s, box.heel), mean_z(s, box.toe)) - tube_half_width;
      rise.largest = std::max(rise.largest, rise.last);
    });
    return rise;
  }
  // The lowest point of the envelope: the lowest node's centre less the half width, turned.
  double lowest_surface_z() const {
    double z = 1e300;
    for (int n : box.corners) z = std::min(z, sim->positions()[n].z());
    return z - tube_half_width;
  }
};

}  // namespace

TEST_CASE("at the members' surfaces a rigid frame tips at g b/h of its envelope", "[contact_dynamics][rocking][surface]") {
  const BoxSpec medium_box{0.4, 0.3, 0.8, Vec3::Zero(), 0, 0.05};
  const BoxSpec tall_box{0.45, 0.4, 1.2, Vec3::Zero(), 0, 0.1};
  for (const auto& [spec, label] : {std::pair{medium_box, "medium"}, std::pair{tall_box, "tall"}})
    for (const double mu_factor : {1.5, 3.0})  // mu = factor b/h: it tips before it slides
      for (const double level : {0.99, 1.01}) {
        // The frame is symmetric top to bottom: its centre of mass is at mid-height of the envelope.
        const double b = 0.5 * spec.bx + tube_half_width, h = tube_half_width + 0.5 * spec.h;
        SurfaceBlock block(spec, mu_factor * b / h, true);
        REQUIRE(std::abs(block.box.cog.z() - h) < 1e-9);
        const auto [largest, last] = block.sudden_load(level * g0 * b / h);
        report("S1 surface contact, %s box (b/h %.4f, mu %.2f b/h), %.2f g b/h: largest edge rise %.3e m, at 2 s %.3e m",
               label, b / h, mu_factor, level, largest, last);
        INFO(label << " level " << level << " mu " << mu_factor << " b/h");
        if (level > 1) {
          CHECK(largest > 0.05);
          CHECK(last > spec.bx * b / h / std::sqrt(1 + b * b / (h * h)));  // past the unstable equilibrium
        } else {
          CHECK(largest < 0.01);
          CHECK(last < 1e-3);
        }
      }
}

TEST_CASE("at the members' surfaces a rigid frame rests on its envelope and stays still", "[contact_dynamics][rest][surface]") {
  for (const BoxSpec& spec : {BoxSpec{0.4, 0.3, 0.8, Vec3::Zero(), 0, 0.05}, BoxSpec{0.9, 0.45, 1.8, Vec3::Zero(), 0, 0.1}}) {
    SurfaceBlock block(spec, 0.5, true);
    const Vec3 c0 = centre_of_mass(*block.sim, block.box.body);
    block.sim->run_until(10.0);
    const Vec3 c1 = centre_of_mass(*block.sim, block.box.body);
    report("S2 surface contact at rest 10 s, %.2f x %.2f x %.2f m: drift %.3e m, sink %.3e m, lowest surface z %.3e m, speed %.3e m/s",
           spec.bx, spec.by, spec.h, (c1 - c0).head<2>().norm(), c0.z() - c1.z(), block.lowest_surface_z(),
           max_speed(*block.sim, block.box.body));
    CHECK((c1 - c0).head<2>().norm() < 1e-4);
    // The stiff parameters: 2.5 um under the weight; the surface starts at the floor.
    CHECK(std::abs(block.lowest_surface_z()) < 1e-5);
    CHECK(max_speed(*block.sim, block.box.body) < 1e-3);
  }
}

// A flexible frame: every node's cube corners touch the floor, each a quarter of the node, their
// moments on the node's rotation inside the implicit step (its 6 x 6 term). At rest it sinks as with
// contact at the centre lines (the same stiffness per node) and stays still; under a sudden load it
// tips near g b/h of the envelope. The unbraced frame leans under the load (its centre of mass moves
// towards the toe), so it tips a little early: measured between 0.97 and 0.99 for the medium frame,
// 0.97 and 0.985 for the tall one; at the centre lines both tip at 0.97 (g (b - c)/(h - c) is 0.945 and
// 0.935 of g b/h). Rigid, the same frames stand at 0.99.
TEST_CASE("at the members' surfaces a flexible frame rests on its envelope and tips near g b/h",
          "[contact_dynamics][rocking][surface][flexible]") {
  const BoxSpec medium_box{0.4, 0.3, 0.8, Vec3::Zero(), 0, 0.05};
  const BoxSpec tall_box{0.45, 0.4, 1.2, Vec3::Zero(), 0, 0.1};
  for (const auto& [spec, label] : {std::pair{medium_box, "medium"}, std::pair{tall_box, "tall"}}) {
    const double b = 0.5 * spec.bx + tube_half_width, h = tube_half_width + 0.5 * spec.h;
    double sink[2] = {0, 0};
    for (const bool surface : {false, true}) {
      SurfaceBlock block(spec, 1.5 * b / h, surface, false);
      const Vec3 c0 = centre_of_mass(*block.sim, block.box.body);
      block.sim->run_until(3.0);
      const Vec3 c1 = centre_of_mass(*block.sim, block.box.body);
      sink[surface] = c0.z() - c1.z();
      report("S3 flexible %s frame at rest 3 s, %s: sink %.4e m, drift %.3e m, speed %.3e m/s, contacts %d", label,
             surface ? "surfaces" : "centre lines", sink[surface], (c1 - c0).head<2>().norm(),
             max_speed(*block.sim, block.box.body), block.sim->contact().active_contacts());
      CHECK((c1 - c0).head<2>().norm() < 1e-6);
      CHECK(max_speed(*block.sim, block.box.body) < 1e-6);
      if (surface) CHECK(std::abs(block.lowest_surface_z()) < 1e-5);
    }
    // Each of the four corners under a node takes a quarter of it: the same sink to 2 %.
    CHECK(std::abs(sink[1] - sink[0]) < 0.02 * sink[0]);
    // Refactorised every step, and every 20 steps (the changed 6 x 6 terms then go in by Woodbury).
    struct Case {
      bool surface;
      double level;
      int refresh;
    };
    for (const auto& [surface, level, refresh] : {Case{true, 0.97, 1}, Case{true, 1.01, 1}, Case{false, 0.97, 1},
                                                  Case{true, 0.97, 20}, Case{true, 1.01, 20}}) {
      SurfaceBlock block(spec, 1.5 * b / h, surface, false, refresh);
      const auto [largest, last] = block.sudden_load(level * g0 * b / h);
      report("S3 flexible %s frame, %s, %.2f g b/h, refactorised every %d steps: largest edge rise %.3e m, at 2 s %.3e m",
             label, surface ? "surfaces" : "centre lines", level, refresh, largest, last);
      INFO(label << (surface ? " surfaces" : " centre lines") << " level " << level << " refresh " << refresh);
      if (surface && level < 1) {
        CHECK(largest < 0.01);
        CHECK(last < 1e-3);
      } else {
        CHECK(largest > 0.05);
      }
    }
  }
}

// The reach lists (RoomContact::cubes_in_reach) skip the cubes that cannot reach a plane before their
// body's nodes move by `margin`. With margin 0 the lists are made again at every evaluation in which a
// node moved (a cube leaving reach then leaves its list at once); with 1 m every cube is always on
// them. A flexible frame rocked by a short pulse (its heel's cubes leave the floor's reach and land
// again) must move the same to the bit. (A list that left out the cubes within the margin fails.)
TEST_CASE("at the members' surfaces the reach lists do not change a flexible frame's motion",
          "[contact_dynamics][rocking][surface][flexible]") {
  const BoxSpec medium_box{0.4, 0.3, 0.8, Vec3::Zero(), 0, 0.05};
  const double b = 0.5 * medium_box.bx + tube_half_width, h = tube_half_width + 0.5 * medium_box.h;
  std::vector<std::vector<Vec3>> end;
  for (const double margin : {0.01, 0.0, 1.0}) {
    SurfaceBlock block(medium_box, 1.5 * b / h, true, false, 20, margin);
    auto& sim = *block.sim;
    sim.run_until(0.3);
    const double t0 = sim.time(), A = 2.0 * g0 * b / h, T = 0.15;
    sim.set_table_acceleration([=](double t) { return Vec3(t > t0 && t < t0 + T ? A : 0.0, 0, 0); });
    double largest = 0, last = 0;
    sim.run_until(t0 + 3.0, [&](const auto& s, const StepInfo&) {
      last = std::max(mean_z(s, block.box.heel), mean_z(s, block.box.toe)) - tube_half_width;
      largest = std::max(largest, last);
    });
    report("S4 rocked flexible frame, margin %.2f m: largest edge rise %.3e m, at the end %.3e m", margin, largest, last);
    CHECK(largest > 0.06);  // the heel's cubes leave the floor's reach (1.75 c = 44 mm) ...
    CHECK(last < 1e-3);     // ... and land again
    const auto& x = sim.positions();
    end.emplace_back(x.begin(), x.end());
  }
  for (std::size_t k = 1; k < end.size(); ++k)
    for (std::size_t n = 0; n < end[0].size(); ++n) REQUIRE(end[k][n] == end[0][n]);
}

}  // namespace surface_contact_tests
