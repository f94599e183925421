// The shared text helpers (core/text.hpp) and the exception hierarchy (core/errors.hpp).
#include <catch2/catch.hpp>

#include <furniture_fem/core/errors.hpp>
#include <furniture_fem/core/text.hpp>

#include <cmath>
#include <limits>
#include <string>

using namespace furniture_fem;

namespace text_tests {  // this file's own names (its group compiles files in batches)

TEST_CASE("parse_finite takes a whole finite number and nothing else", "[text]") {
  double x = -7;
  CHECK(text::parse_finite("0.05", x));
  CHECK(x == 0.05);
  CHECK(text::parse_finite("+1.5e3", x));
  CHECK(x == 1500.0);
  CHECK(text::parse_finite("-2", x));
  CHECK(x == -2.0);
  x = -7;
  for (const char* bad : {"0.05xyz", "nan", "NaN", "inf", "-inf", "1e400", "", " ", " 1", "1 ", "+-1", "++1", "+",
                          "-", "1,5", "0x10"}) {
    INFO("'" << bad << "'");
    CHECK_FALSE(text::parse_finite(bad, x));
    CHECK(x == -7);  // left as it was
  }
}

TEST_CASE("parse_double also takes NaN and infinity, never trailing garbage", "[text]") {
  double x = 0;
  CHECK(text::parse_double("nan", x));
  CHECK(std::isnan(x));
  CHECK(text::parse_double("-inf", x));
  CHECK(x == -std::numeric_limits<double>::infinity());
  CHECK(text::parse_double("1.25", x));
  CHECK(x == 1.25);
  CHECK_FALSE(text::parse_double("0.05xyz", x));
  CHECK_FALSE(text::parse_double("1e400", x));
  CHECK_FALSE(text::parse_double("", x));
  CHECK_FALSE(text::parse_double("\t", x));
}

TEST_CASE("parse_integer takes a whole decimal integer", "[text]") {
  long k = 0;
  CHECK(text::parse_integer("42", k));
  CHECK(k == 42);
  CHECK(text::parse_integer("+3", k));
  CHECK(k == 3);
  CHECK(text::parse_integer("-3", k));
  CHECK(k == -3);
  for (const char* bad : {"4.0", "4x", "", " ", "+-3", "99999999999999999999999"}) {
    INFO("'" << bad << "'");
    CHECK_FALSE(text::parse_integer(bad, k));
  }
}

TEST_CASE("trim, split and case", "[text]") {
  CHECK(text::trim("  a b \t\r\n") == "a b");
  CHECK(text::trim("") == "");
  CHECK(text::trim(" \t ") == "");
  CHECK(text::is_blank(" \t\f\v"));
  CHECK_FALSE(text::is_blank(" x "));
  const auto w = text::split_words("  v 1.0\t2  3 ");
  REQUIRE(w.size() == 4);
  CHECK(w[0] == "v");
  CHECK(w[3] == "3");
  CHECK(text::split_words("   ").empty());
  const auto f = text::split_fields(R"(a,"b,c","say ""hi""",)");
  REQUIRE(f.size() == 4);
  CHECK(f[1] == "b,c");
  CHECK(f[2] == "say \"hi\"");
  CHECK(f[3] == "");
  CHECK(text::lowercase("SoLiD 1") == "solid 1");
  CHECK(text::uppercase("Gal/s") == "GAL/S");
  CHECK(text::strip_comment("  v 1 2 3 # a vertex ") == "v 1 2 3");
  CHECK(text::strip_comment("# only a comment") == "");
  CHECK(text::strip_comment("keep # this", '\0') == "keep # this");
}

TEST_CASE("split_lines numbers lines from 1 and strips the CR of CRLF", "[text]") {
  const text::Lines t = text::split_lines("mesh.off", "OFF\r\n3 1 0\r\n\r\nlast");
  REQUIRE(t.size() == 4);
  CHECK(t.line(1) == "OFF");
  CHECK(t.line(3) == "");
  CHECK(t.line(4) == "last");
  CHECK(text::split_lines("f", "a\n").size() == 2);  // a text ending in a newline has an empty last line
  CHECK(text::split_lines("f", "").size() == 1);
}

TEST_CASE("one exception hierarchy: input, model, simulation and output errors", "[errors]") {
  CHECK_THROWS_AS(throw ModelError("member 'post': zero length (0 m)"), InputError);
  CHECK_THROWS_AS(throw InputError("f.csv", 3, "x", "'0.05xyz' is not a number"), Error);
  CHECK_THROWS_AS(throw SimulationError(1.5, "NaN"), Error);
  CHECK_THROWS_AS(throw OutputError("cannot write 'a.png'"), Error);
  CHECK_THROWS_AS(throw InputError("bad argument"), std::runtime_error);
  const InputError e("f.csv", 3, "x", "'0.05xyz' is not a number");
  CHECK(std::string(e.what()) == "f.csv:3: x: '0.05xyz' is not a number");
  CHECK(e.line() == 3);
  CHECK(e.field() == "x");
}

}  // namespace text_tests
