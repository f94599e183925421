// CSV writer and reader: round trip, flushing while the writer is alive, and files cut mid-row.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "furniture_fem/io/csv.hpp"
#include "../support/test_files.hpp"

namespace csv_tests {  // this file's own names (its group compiles files in batches)

namespace fs = std::filesystem;
using namespace furniture_fem;

using ffem_test::slurp;
using ffem_test::tmp;

namespace {
void spit(const std::string& path, const std::string& text) {
  std::ofstream f(path, std::ios::binary | std::ios::trunc);
  f << text;
}
double value(int row, int col) {  // awkward values: thirds, tiny, huge, negative, zero
  const double base[] = {1.0 / 3.0, 1e-300, -2.5e10, 3.14159265358979e-7, 0.0};
  return base[(row + col) % 5] * (1 + row * 1e-3) + (col == 0 ? row * 0.001 : 0.0);
}
}  // namespace

TEST_CASE("CSV round trip to 1e-12 relative", "[csv]") {
  const std::string path = tmp("series.csv");
  {
    CsvWriter w(path, {"t", "x", "force, N", "say \"hi\""});
    for (int r = 0; r < 1000; ++r) w.row({value(r, 0), value(r, 1), value(r, 2), value(r, 3)});
    CHECK(w.rows() == 1000);
  }
  const CsvTable t = read_csv(path);
  CHECK(t.columns() == std::vector<std::string>{"t", "x", "force, N", "say \"hi\""});
  REQUIRE(t.rows() == 1000);
  CHECK_FALSE(t.truncated());
  for (int c = 0; c < 4; ++c) {
    const auto& col = t.column(t.columns()[std::size_t(c)]);
    for (int r = 0; r < 1000; ++r) {
      const double a = col[std::size_t(r)], b = value(r, c);
      INFO("row " << r << " col " << c);
      CHECK(std::abs(a - b) <= 1e-12 * std::abs(b));
    }
  }
  CHECK(t.has("x"));
  CHECK_FALSE(t.has("y"));
  CHECK_THROWS_AS(t.column("y"), InputError);
}

TEST_CASE("CSV writer flushes rows while it is still open", "[csv]") {
  const std::string path = tmp("flush.csv");
  SECTION("every 2 rows") {
    CsvWriter w(path, {"t", "u"}, CsvOptions{15, 2, 1e9});
    for (int i = 0; i < 5; ++i) w.row({double(i), i * 0.5});
    const CsvTable t = read_csv(path);  // the writer is alive: this is what a killed run leaves
    CHECK(t.rows() == 4);
    CHECK(t.column("u").back() == 1.5);
  }
  SECTION("held back until flush() when the thresholds are large") {
    CsvWriter w(path, {"t", "u"}, CsvOptions{15, 1000000, 1e9});
    for (int i = 0; i < 5; ++i) w.row({double(i), i * 0.5});
    CHECK(read_csv(path).rows() == 0);  // the header alone is on disk
    w.flush();
    CHECK(read_csv(path).rows() == 5);
  }
  SECTION("by time for slow runs") {
    CsvWriter w(path, {"t"}, CsvOptions{15, 1000000, 0.0});
    w.row({1.0});
    CHECK(read_csv(path).rows() == 1);
  }
}

TEST_CASE("CSV file cut mid-row reads all complete rows", "[csv]") {
  const std::string path = tmp("cut.csv");
  {
    CsvWriter w(path, {"t", "x", "y"});
    for (int i = 0; i < 50; ++i) w.row({i * 0.01, std::sin(i * 0.1), std::cos(i * 0.1)});
  }
  const std::string full = slurp(path);
  // Cut inside the last row, and then inside a number of the row before.
  const auto last_nl = full.rfind('\n', full.size() - 2);
  for (std::size_t cut : {last_nl + 5, last_nl - 3}) {
    spit(path, full.substr(0, cut));
    const CsvTable t = read_csv(path);
    const std::size_t expect = cut > last_nl ? 49 : 48;
    INFO("cut at byte " << cut);
    CHECK(t.truncated());
    REQUIRE(t.rows() == expect);
    for (std::size_t i = 0; i < expect; ++i) CHECK(std::abs(t.column("x")[i] - std::sin(double(i) * 0.1)) <= 1e-14);
  }
  spit(path, full.substr(0, full.find('\n') / 2));  // cut inside the header
  CHECK_THROWS_AS(read_csv(path), InputError);
}

TEST_CASE("CSV errors name the file and line", "[csv]") {
  const std::string path = tmp("bad.csv");
  spit(path, "# produced by hand\nt,x\n0,1\n\n1,2,3\n");
  try {
    read_csv(path);
    FAIL("row with 3 fields accepted");
  } catch (const InputError& e) {
    CHECK(e.line() == 5);
    CHECK(std::string(e.what()).find(path) != std::string::npos);
  }
  spit(path, "t,x\n0,abc\n");
  try {
    read_csv(path);
    FAIL("non-number accepted");
  } catch (const InputError& e) {
    CHECK(e.field() == "x");
  }
  spit(path, "t,x\r\n0,\r\n+1.5,nan\r\n");  // CRLF, empty field, explicit NaN
  const CsvTable t = read_csv(path);
  REQUIRE(t.rows() == 2);
  CHECK(std::isnan(t.column("x")[0]));
  CHECK(t.column("t")[1] == 1.5);
  CHECK(std::isnan(t.column("x")[1]));

  CsvWriter w(tmp("rows.csv"), {"a", "b"});
  CHECK_THROWS_AS(w.row({1.0}), InputError);
  CHECK_THROWS_AS(CsvWriter(tmp("no_such_dir/x.csv"), {"a"}), OutputError);
}

TEST_CASE("CSV columns named by items and partners read back by name", "[csv]") {
  // contact_forces.csv's columns: "<item>|<partner>_f?", with whatever an item's name holds.
  const std::string path = tmp("named_columns.csv");
  const std::vector<std::string> cols{"t", "pair/lower|floor_fz", "my desk, oak|walls_fx", "a \"b\"|pair/upper_fy"};
  {
    CsvWriter w(path, cols);
    w.row({0.0, -491.25, 0.0, 0.375});
    w.row({0.01, -490.5, 2e-300, -7.5});
  }
  const CsvTable t = read_csv(path);
  CHECK(t.columns() == cols);
  CHECK(t.column("pair/lower|floor_fz") == std::vector<double>{-491.25, -490.5});
  CHECK(t.column("my desk, oak|walls_fx") == std::vector<double>{0.0, 2e-300});
  CHECK(t.column("a \"b\"|pair/upper_fy") == std::vector<double>{0.375, -7.5});
}

}  // namespace csv_tests
