// A joint between two items whose nodes are apart (RoomContact::joint_force): the law's force on the
// item's node, the opposite force on the anchor node, and the force's moment about the anchor node on
// it, so that the pair feels no net force and no net moment and keeps its momentum and angular momentum
// (docs/restraints/restraints.md, "Between items"). Checked by hand: the strap's tension k (|x - y| - L0)
// along the strap, the bracket's k p n + k_s (d - p n), and the sums over every node of both bodies.
#include <catch2/catch.hpp>

#include <furniture_fem/contact/room_contact.hpp>

#include <vector>

using namespace furniture_fem;

namespace joint_wrench_tests {  // this file's own names (its group compiles files in batches)

namespace {

// Two bars far above the floor (nothing touches it), body 0 from (0, 0, 1) to (0.5, 0, 1), body 1 from
// (0.6, 0.08, 1.1) to (1.1, 0.08, 1.1): the joint from body 0's end to body 1's start, 0.143 m apart and
// off every axis, so that the force's line misses both nodes' lines along the bars.
struct TwoBars {
  Model m;
  int a0 = -1, a1 = -1, b0 = -1, b1 = -1;
  TwoBars() {
    const int sec = m.add_section(Section::hollow_rectangle(0.05, 0.05, 0.002, "50 x 50")), mat = m.add_material(Material::steel());
    const int p = m.add_body("p"), q = m.add_body("q");
    a0 = m.add_node({0, 0, 1}, p), a1 = m.add_node({0.5, 0, 1}, p);
    b0 = m.add_node({0.6, 0.08, 1.1}, q), b1 = m.add_node({1.1, 0.08, 1.1}, q);
    m.add_member("p", a0, a1, sec, mat);
    m.add_member("q", b0, b1, sec, mat);
  }
  Restraint joint(RestraintKind kind) const {
    Restraint r;
    r.name = kind == RestraintKind::strap ? "strap" : "bracket";
    r.kind = kind;
    r.body = 0, r.node = a1, r.anchor_body = 1, r.anchor_node = b0;
    r.rest = m.node(a1).X, r.anchor = m.node(b0).X;
    r.normal = (r.rest - r.anchor).normalized();
    r.p = default_restraint_params(kind);
    return r;
  }
};

struct Wrench {
  Vec3 force = Vec3::Zero(), moment = Vec3::Zero();  // about the origin
};

// Sum over every node: the forces, and their moments about the origin plus the nodal moments.
Wrench total(const std::vector<Vec3>& x, const Eigen::VectorXd& f) {
  Wrench w;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const Vec3 fi = f.segment<3>(6 * i), mi = f.segment<3>(6 * i + 3);
    w.force += fi;
    w.moment += x[i].cross(fi) + mi;
  }
  return w;
}

}  // namespace

TEST_CASE("a joint between items puts no net force or moment on the pair", "[contact][restraints][joined]") {
  TwoBars t;
  // Each body moved rigidly (a shift and a small turn about its first node), the two apart along the
  // joint, so that it stretches (the strap taut) and shears.
  const auto moved = [&](const Vec3& shift_p, double turn_p, const Vec3& shift_q, double turn_q) {
    std::vector<Vec3> x(t.m.num_nodes());
    for (int i = 0; i < t.m.num_nodes(); ++i) {
      const bool on_p = t.m.node(i).body == 0;
      const Vec3 origin = t.m.node(on_p ? t.a0 : t.b0).X;
      const Mat3 R = Eigen::AngleAxisd(on_p ? turn_p : turn_q, Vec3(0.3, -0.2, 1).normalized()).toRotationMatrix();
      x[i] = origin + R * (t.m.node(i).X - origin) + (on_p ? shift_p : shift_q);
    }
    return x;
  };
  std::vector<Mat3> R(t.m.num_nodes(), Mat3::Identity());
  const Eigen::VectorXd v = Eigen::VectorXd::Zero(6 * t.m.num_nodes());
  BodyContact bc;
  for (const RestraintKind kind : {RestraintKind::strap, RestraintKind::l_bracket}) {
    for (const auto& [sp, tp, sq, tq] : {std::tuple{Vec3(-0.004, -0.002, -0.003), 0.004, Vec3(0.003, 0.002, 0.002), -0.005},
                                         std::tuple{Vec3(-0.002, -0.004, -0.001), -0.006, Vec3(0.002, 0.001, 0.004), 0.005}}) {
      const Restraint r = t.joint(kind);
      CAPTURE(r.name, tp, tq);
      // The bracket moved a fifth as far: 1.7e6 N/m across its pull shears it off (2.4 kN) past 1.4 mm.
      const double k = kind == RestraintKind::strap ? 1.0 : 0.2;
      RoomContact contact(t.m, {bc, bc}, {RigidPlane{}});
      contact.set_restraints(RestraintSet({r}));
      const std::vector<Vec3> x = moved(k * sp, k * tp, k * sq, k * tq);
      Eigen::VectorXd f = Eigen::VectorXd::Zero(6 * t.m.num_nodes());
      contact.add_forces(ContactView{t.m, x, v, 0.0, 1e-3, &R}, f);

      // The law's force on the item's node, by hand.
      Vec3 expected;
      if (kind == RestraintKind::strap) {
        const Vec3 e = x[t.a1] - x[t.b0];
        const double stretch = e.norm() - (r.rest - r.anchor).norm();
        REQUIRE(stretch > 1e-4);  // taut: the case means something
        expected = -r.p.stiffness * stretch * e.normalized();
      } else {
        const Vec3 d = (x[t.a1] - r.rest) - (x[t.b0] - r.anchor);
        const double pull = d.dot(r.normal);
        REQUIRE(r.p.stiffness * pull < r.p.strength);  // elastic, and not sheared off
        REQUIRE(r.p.shear_stiffness * (d - pull * r.normal).norm() < r.p.shear_strength);
        expected = -r.p.stiffness * pull * r.normal - r.p.shear_stiffness * (d - pull * r.normal);
      }
      const double F = expected.norm();
      REQUIRE(F > 1.0);
      CHECK((Vec3(f.segment<3>(6 * t.a1)) - expected).norm() <= 1e-9 * F);
      CHECK((Vec3(f.segment<3>(6 * t.b0)) + expected).norm() <= 1e-9 * F);
      // The anchor node carries the moment that keeps the pair's angular momentum; the item's node none.
      CHECK(Vec3(f.segment<3>(6 * t.b0 + 3)).isApprox(-(x[t.a1] - x[t.b0]).cross(expected), 1e-12));
      CHECK(Vec3(f.segment<3>(6 * t.a1 + 3)).norm() == 0.0);
      // Over both bodies: no net force, no net moment about the origin (a lever arm up to 1.2 m).
      const Wrench w = total(x, f);
      CHECK(w.force.norm() <= 1e-12 * F);
      CHECK(w.moment.norm() <= 1e-12 * F * 1.5);
      // A strap pulls along the line between the nodes: no moment about the anchor node. A bracket's shear
      // does not: without the anchor's moment the pair would be turned by at least 1 N m per 100 N here,
      // so the sum above can fail.
      const double lever = (x[t.a1] - x[t.b0]).cross(expected).norm() / F;
      if (kind == RestraintKind::strap)
        CHECK(lever <= 1e-12);
      else
        CHECK(lever > 0.01);
    }
  }
}

}  // namespace joint_wrench_tests
