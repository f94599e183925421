// Model module: section properties against the paper's Table 1, and bad input that must fail loudly
// with a message naming the member / element / node and the offending value.
#include <catch2/catch.hpp>

#include <furniture_fem/core/simulation.hpp>

#include <cmath>
#include <limits>
#include <string>

using namespace furniture_fem;
using Catch::Matchers::Contains;

namespace model_tests {  // this file's own names (its group compiles files in batches)

namespace {

// The message of the ModelError thrown by f (any other exception escapes and fails the test).
template <class F>
std::string model_error_of(F&& f) {
  try {
    f();
  } catch (const ModelError& e) {
    return e.what();
  }
  return "<no ModelError thrown>";
}

struct Table1Row {
  const char* member;
  double a_mm, b_mm, area_mm2, Ix_mm4, Iy_mm4;
};

}  // namespace

TEST_CASE("hollow rectangles reproduce the type-1 sections of Table 1", "[model][sections]") {
  // Table 1 of the paper (type 1 = hollow rectangle a x b, wall 2 mm): area and the second moments
  // about the strong (Ix) and weak (Iy) axes. Copied from /work/shared/paper/table1_sections.csv.
  const Table1Row rows[] = {
      {"all members of cabinets and desk", 50, 30, 304, 1.016e5, 4.513e4},
      {"front columns of side table", 170, 40, 824, 2.654e6, 2.613e5},
      {"beams of side table", 445, 40, 1924, 3.644e7, 6.587e5},
      {"backrest of office chair", 300, 80, 1504, 1.575e7, 1.972e6},
      {"seat surface of office chair", 400, 80, 1904, 3.337e7, 2.580e6},
  };
  // The table rounds to 3-4 significant digits: 0.5 % covers its rounding.
  for (const auto& r : rows) {
    INFO(r.member);
    const Section s = Section::hollow_rectangle(r.a_mm * 1e-3, r.b_mm * 1e-3, 2e-3, r.member);
    CHECK(s.A * 1e6 == Approx(r.area_mm2).epsilon(0.005));
    CHECK(s.Iz * 1e12 == Approx(r.Ix_mm4).epsilon(0.005));  // strong axis: bending across hy = a
    CHECK(s.Iy * 1e12 == Approx(r.Iy_mm4).epsilon(0.005));  // weak axis
    CHECK(s.Iz >= s.Iy);
  }
}

TEST_CASE("plastic moduli and torsion constant of the 50 x 30 tube", "[model][sections]") {
  const Section s = Section::hollow_rectangle(0.05, 0.03, 0.002);
  // Zp = (b h^2 - b_i h_i^2) / 4 for bending across h; Bredt J = 4 Am^2 t / perimeter of the mid line.
  CHECK(s.Zpz == Approx((0.03 * 0.05 * 0.05 - 0.026 * 0.046 * 0.046) / 4).epsilon(1e-12));
  CHECK(s.Zpy == Approx((0.05 * 0.03 * 0.03 - 0.046 * 0.026 * 0.026) / 4).epsilon(1e-12));
  const double am = 0.048 * 0.028;
  CHECK(s.J == Approx(4 * am * am * 0.002 / (2 * (0.048 + 0.028))).epsilon(1e-12));
  CHECK(s.Zpz / (s.Iz / 0.025) > 1.0);  // shape factor of a hollow section, above 1
}

TEST_CASE("bad input throws ModelError naming the culprit and the value", "[model][errors]") {
  Model m;
  const int b = m.add_body("cabinet");
  const int sec = m.add_section(Section::hollow_rectangle(0.05, 0.03, 0.002, "tube"));
  const int mat = m.add_material(Material::steel());

  SECTION("zero-length member") {
    const int a = m.add_node({0, 0, 0}, b), c = m.add_node({0, 0, 0}, b);
    const std::string msg = model_error_of([&] { m.add_member("left post", a, c, sec, mat); });
    CHECK_THAT(msg, Contains("member 'left post'") && Contains("zero length") && Contains("(0 m)"));
  }
  SECTION("a target length giving more elements than an integer holds") {
    // lround of 1e300 is undefined: it gave one element, silently (issue 13).
    const int a = m.add_node({0, 0, 0}, b), c = m.add_node({1, 0, 0}, b);
    MemberOptions tiny;
    tiny.elements = 0;
    tiny.target_length = 1e-300;
    const std::string msg = model_error_of([&] { m.add_member("left post", a, c, sec, mat, tiny); });
    CHECK_THAT(msg, Contains("member 'left post'") && Contains("target_length 1e-300 m") && Contains("at most 1e6"));
  }
  SECTION("duplicate element") {
    const int a = m.add_node({0, 0, 0}, b), c = m.add_node({1, 0, 0}, b);
    MemberOptions one;
    one.elements = 1;
    one.pairs = false;
    m.add_member("shelf", a, c, sec, mat, one);
    m.add_member("shelf copy", c, a, sec, mat, one);
    const std::string msg = model_error_of([&] { m.validate(); });
    CHECK_THAT(msg, Contains("member 'shelf copy' element 0") && Contains("duplicates") &&
                        Contains("member 'shelf' element 0") && Contains("(nodes 0, 1)"));
    // The solver validates the model when it is composed.
    CHECK_THAT(model_error_of([&] { Simulation<ConventionalTimoshenko> sim(m); }), Contains("duplicates"));
  }
  SECTION("non-positive or NaN section values") {
    CHECK_THAT(model_error_of([] { Section::hollow_rectangle(0.05, 0.03, 0.0, "flat tube"); }),
               Contains("section 'flat tube'") && Contains("t = 0"));
    CHECK_THAT(model_error_of([] { Section::hollow_rectangle(0.05, -0.03, 0.002, "negative"); }),
               Contains("section 'negative'") && Contains("hz = -0.03"));
    const double nan = std::numeric_limits<double>::quiet_NaN();
    CHECK_THAT(model_error_of([&] { Section::from_properties("rear column", nan, 1e-7, 1e-7, 0.05, 0.05); }),
               Contains("section 'rear column'") && Contains("A must be positive") && Contains("nan"));
    Section s = Section::hollow_rectangle(0.05, 0.03, 0.002, "edited");
    s.Iz = -1e-8;
    CHECK_THAT(model_error_of([&] { m.add_section(s); }),
               Contains("section 'edited'") && Contains("Iz") && Contains("-1e-08"));
  }
  SECTION("non-positive or NaN material values") {
    Material soft;
    soft.name = "soft steel";
    soft.E = -2e9;
    CHECK_THAT(model_error_of([&] { m.add_material(soft); }),
               Contains("material 'soft steel'") && Contains("E must be positive") && Contains("-2e+09"));
    Material heavy;
    heavy.name = "lead";
    heavy.rho = std::numeric_limits<double>::quiet_NaN();
    CHECK_THAT(model_error_of([&] { m.add_material(heavy); }),
               Contains("material 'lead'") && Contains("rho") && Contains("nan"));
    Material rubber;
    rubber.name = "rubber";
    rubber.nu = 0.5;
    CHECK_THAT(model_error_of([&] { m.add_material(rubber); }),
               Contains("material 'rubber'") && Contains("nu") && Contains("(got 0.5)"));
  }
  SECTION("NaN node coordinates") {
    m.add_node({0, 0, 0}, b);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    CHECK_THAT(model_error_of([&] { m.add_node({0.5, nan, 1.0}, b); }),
               Contains("node 1 of body 'cabinet'") && Contains("not finite") && Contains("(0.5, nan, 1)"));
  }
  SECTION("unconnected node") {
    const int a = m.add_node({0, 0, 0}, b), c = m.add_node({1, 0, 0}, b);
    m.add_node({1, 2, 3}, b);
    m.add_member("rail", a, c, sec, mat);
    const std::string msg = model_error_of([&] { m.validate(); });
    CHECK_THAT(msg, Contains("node 2 of body 'cabinet'") && Contains("(1, 2, 3)") && Contains("not connected"));
  }
  SECTION("odd element count with pairs") {
    const int a = m.add_node({0, 0, 0}, b), c = m.add_node({1, 0, 0}, b);
    MemberOptions three;
    three.elements = 3;
    CHECK_THAT(model_error_of([&] { m.add_member("top board", a, c, sec, mat, three); }),
               Contains("member 'top board'") && Contains("even element count") && Contains("got 3"));
  }
  SECTION("ASI-Gauss elements without pairs") {
    const int a = m.add_node({0, 0, 0}, b), c = m.add_node({1, 0, 0}, b);
    MemberOptions unpaired;
    unpaired.elements = 3;
    unpaired.pairs = false;
    m.add_member("back", a, c, sec, mat, unpaired);
    CHECK_THAT(model_error_of([&] { Simulation<AsiGaussTimoshenko> sim(m); }),
               Contains("member 'back' element 0") && Contains("pairs"));
    // The one-point element does not need pairs.
    CHECK_NOTHROW(Simulation<ConventionalTimoshenko>(m));
  }
}

TEST_CASE("a pair count rounds up when the length decides the element count", "[model]") {
  Model m;
  const int b = m.add_body("desk");
  const int sec = m.add_section(Section::hollow_rectangle(0.05, 0.03, 0.002));
  const int mat = m.add_material(Material::steel());
  const int a = m.add_node({0, 0, 0}, b), c = m.add_node({0.25, 0, 0}, b);
  const int mem = m.add_member("leg", a, c, sec, mat);  // 0.25 m / 0.05 m = 5, rounded up to 6
  CHECK(m.member(mem).element_count == 6);
  for (int e = 0; e < 6; ++e) {
    CHECK(m.elements()[e].slot == (e % 2 == 0 ? PairSlot::first : PairSlot::second));
    CHECK(m.elements()[e].partner == (e % 2 == 0 ? e + 1 : e - 1));
  }
  CHECK(m.body_mass(b) == Approx(7850 * 304e-6 * 0.25).epsilon(1e-12));
}

}  // namespace model_tests
