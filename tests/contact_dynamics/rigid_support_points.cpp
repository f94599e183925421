// A rigid body's reduced contact geometry against planes (RoomContact::set_rigid, called by
// Simulation::set_rigid): only the vertices of its nodes' convex hull are tested, those of the face
// turned towards the plane each standing for its share of that face's nodes. Checked against the same
// rigid block with every node tested (RoomContact::set_rigid(..., false)): the same rest, the same
// sliding, the same rocking, within the bounds given (measured numbers: FFEM_REPORT=1).
#include <catch2/catch.hpp>

#include "dynamics_scenes.hpp"

using namespace ffem_dyn;

namespace rigid_support_points_tests {  // this file's own names (its group compiles files in batches)

namespace {

// A rigid block, its floor contact at the hull's vertices (reduced) or at every node.
BlockScene<PaperLaw> rigid_block(const BoxSpec& spec, bool reduced, double mu = 0.3) {
  BlockScene<PaperLaw> s(spec, [&](const Box& b) { return paper_params(b.mass, mu, 0.03); }, true, options_dt(1e-3),
                         paper_newmark);
  if (!reduced) s.sim->contact().set_rigid(*s.model, s.box.body, false);
  return s;
}

}  // namespace

TEST_CASE("a rigid box frame touches planes at its eight corners only", "[contact_dynamics][rigid]") {
  auto s = rigid_block(BoxSpec{}, true);
  std::vector<int> corners = s.box.corners;
  std::sort(corners.begin(), corners.end());
  CHECK(s.sim->contact_model().plane_nodes() == corners);
  auto full = rigid_block(BoxSpec{}, false);
  CHECK(full.sim->contact_model().plane_nodes().size() == static_cast<size_t>(full.model->num_nodes()));
}

TEST_CASE("a rigid block rests on its four bottom corners as on its 28 bottom nodes", "[contact_dynamics][rigid]") {
  // Each bottom corner stands for 7 of the 28 bottom nodes: the same penetration g = W / (28 alpha) and
  // the same total force as with every node (paper law, alpha = W, q = 1).
  double g_of[2] = {0, 0};
  for (const bool reduced : {true, false}) {
    auto s = rigid_block(BoxSpec{}, reduced);
    s.sim->run_until(2.0);
    const double g = 1 - mean_z(*s.sim, s.box.bottom) / tube_half_width;
    const Eigen::VectorXd f = contact_force_vector(*s.sim);
    double Fz = 0;
    for (int k = 0; k < s.model->num_nodes(); ++k) Fz += f[6 * k + 2];
    g_of[reduced] = g;
    report("rigid rest (%s): g %.10f, closed form %.10f, sum Fz / W - 1 = %.2e", reduced ? "corners" : "every node", g,
           1.0 / s.box.bottom.size(), Fz / s.weight() - 1);
    CHECK(std::abs(g * s.box.bottom.size() - 1) < 1e-6);
    CHECK(std::abs(Fz / s.weight() - 1) < 1e-6);
  }
  CHECK(std::abs(g_of[1] / g_of[0] - 1) < 1e-9);
}

TEST_CASE("a rigid block slides on its corners as on every node", "[contact_dynamics][rigid]") {
  // Table at 1.5 mu g for 1 s after 0.5 s of rest: the block slides back at (1.5 - 1) mu g relative to
  // the table. Friction is mu N at every contact, so the sliding is the same but for how the friction's
  // moment is carried: by four corners instead of the edges' nodes, whose heel side unloads differently
  // (the paper's damping and the regularised friction see other normal forces there). Measured: 0.25 %
  // of the 0.75 m slid; the bound is twice that.
  Vec3 slid[2];
  for (const bool reduced : {true, false}) {
    auto s = rigid_block(BoxSpec{}, reduced);
    s.sim->run_until(0.5);
    const double A = 1.5 * 0.3 * g0;
    s.sim->set_table_acceleration([=](double t) { return Vec3(t < 1.5 ? A : 0.0, 0, 0); });
    const Vec3 c0 = s.com();
    s.sim->run_until(1.5);
    slid[reduced] = s.com() - c0;
    report("rigid sliding (%s): %.6f m along x, %.2e m along z", reduced ? "corners" : "every node", slid[reduced].x(),
           slid[reduced].z());
  }
  CHECK(slid[1].x() < -0.5 * 0.5 * 0.3 * g0 * 0.9);  // about (1.5 - 1) mu g t^2 / 2 = 0.74 m back
  CHECK(std::abs(slid[1].x() / slid[0].x() - 1) < 5e-3);
}

TEST_CASE("a raised rigid block rocks on its corners as on its pivot lines", "[contact_dynamics][rigid]") {
  // The block stands on its two bottom edges along Y (raise): each bottom corner stands for half of one
  // pivot line. A pulse of 1 g for 0.2 s rocks it (it tips above about 0.6 g; no sliding at mu = 2);
  // the largest lift of the heel agrees with every node's: rocked on a pivot line, its two corners carry
  // what the line's nodes carried (half the bottom face's nodes each way). Measured: 21.5 mm both, the
  // same to 1 um; the bound (2 %) leaves room for the lifting corners, which keep their face's share.
  BoxSpec spec;
  spec.raise = 0.05;
  spec.h = 0.6;
  double lift[2] = {0, 0};
  for (const bool reduced : {true, false}) {
    auto s = rigid_block(spec, reduced, 2.0);
    s.sim->run_until(0.3);
    const double z0 = mean_z(*s.sim, s.box.heel);
    s.sim->set_table_acceleration([](double t) { return Vec3(t > 0.3 && t < 0.5 ? g0 : 0.0, 0, 0); });
    s.sim->run_until(1.5, [&](const auto& sim, const StepInfo&) { lift[reduced] = std::max(lift[reduced], mean_z(sim, s.box.heel) - z0); });
    report("rigid rocking (%s): largest heel lift %.6f m", reduced ? "corners" : "every node", lift[reduced]);
  }
  CHECK(lift[1] > 0.002);  // it rocks: twice the resting penetration and more
  CHECK(std::abs(lift[1] / lift[0] - 1) < 0.02);
}

}  // namespace rigid_support_points_tests
