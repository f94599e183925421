// ContactLawKernel (contact/contact_law_kernel.hpp): a law behind the run-time interface gives the law's own
// force to the bit, its own parameter checks, and the history and clamping the law's type states; RoomContact
// refuses a null kernel by name.
#include <catch2/catch.hpp>

#include <furniture_fem/contact/contact_law_kernel.hpp>
#include <furniture_fem/contact/room_contact.hpp>

#include <string>

using namespace furniture_fem;

namespace law_kernel_tests {  // this file's own names (its group compiles files in batches)

namespace {
template <class Law>
void check_kernel(const ContactParams& p, bool history, bool clamps) {
  const Law law{};
  const auto kernel = make_contact_law_kernel(law);
  CHECK(kernel->has_history() == history);
  CHECK(kernel->clamps_tensile() == clamps);
  // Approaching, sticking and slipping, inside and outside the contact distance.
  for (const double l : {0.03, 0.02, 0.01})
    for (const Vec3& v : {Vec3(3e-5, 4e-5, -2e-3), Vec3(0.3, 0.4, -0.01), Vec3(-0.2, 0.1, 0.05)}) {
      ContactKinematics k;
      k.L = 0.025;
      k.l = l;
      k.n = Vec3::UnitZ();
      k.v = v;
      k.long_axis = Vec3::UnitX();
      k.dt = 1e-3;
      ContactState s_law, s_kernel;
      s_law.normal = s_kernel.normal = Vec3::UnitZ();
      const ContactForce a = law.force(k, p, s_law), b = kernel->force(k, p, s_kernel);
      CHECK(a.in_contact == b.in_contact);
      CHECK(a.on_a == b.on_a);  // to the bit: the same code
      CHECK(a.K == b.K);
      CHECK(a.C == b.C);
      CHECK(a.sticking == b.sticking);
      CHECK(s_law.normal == s_kernel.normal);
    }
}
}  // namespace

TEST_CASE("a law's kernel gives the law's force, checks, history and clamping", "[contact][laws][kernel]") {
  ContactParams p = ContactParams::paper(20.0, 0.4);
  p.k_lin = p.k_t = 2e4;
  p.c_lin = p.c_t = 50;
  p.k_hc = 1e5;
  check_kernel<PaperLaw>(p, false, false);  // the paper's normal response may pull (clamp_tensile false)
  check_kernel<StickSlipLaw>(p, true, false);
  check_kernel<SpringDashpotLaw>(p, false, true);
  check_kernel<HuntCrossleyLaw>(p, false, true);

  // The parts' own checks: the stick-slip friction needs a tangential spring, the paper's law does not.
  ContactParams no_spring = ContactParams::paper(20.0, 0.4);
  no_spring.k_t = 0;
  CHECK_NOTHROW(make_contact_law_kernel(PaperLaw{})->validate(no_spring));
  CHECK_THROWS(StickSlipLaw::validate(no_spring));
  CHECK_THROWS(make_contact_law_kernel(StickSlipLaw{})->validate(no_spring));
  ContactParams negative = p;
  negative.alpha = -1;
  CHECK_THROWS_WITH(make_contact_law_kernel(PaperLaw{})->validate(negative), Catch::Contains("alpha"));
}

TEST_CASE("RoomContact refuses a null law kernel", "[contact][laws][kernel]") {
  Model m;
  const int body = m.add_body("bar");
  const int sec = m.add_section(Section::hollow_rectangle(0.05, 0.05, 0.002)), mat = m.add_material(Material::steel());
  m.add_member("bar", m.add_node({0, 0, 0.5}, body), m.add_node({0.5, 0, 0.5}, body), sec, mat);
  CHECK_THROWS_WITH(RoomContact(m, {BodyContact{}}, {RigidPlane{}}, std::shared_ptr<const ContactLawKernel>{}),
                    Catch::Contains("no contact law"));
  CHECK_NOTHROW(RoomContact(m, {BodyContact{}}, {RigidPlane{}}, make_contact_law_kernel(SpringDashpotLaw{})));
}

}  // namespace law_kernel_tests
