// Readers of the ground-motion formats: each parses a small file written here with a header like the
// real one, and every malformed file throws an InputError naming the file, the line and the field.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

#include <furniture_fem/excitation/excitation.hpp>

namespace readers_tests {  // this file's own names (its group compiles files in batches)

namespace {

std::string tmp_path(const std::string& name) { return std::string(FFEM_TEST_TMP) + "/excitation_" + name; }

std::string write_file(const std::string& name, const std::string& text) {
  const std::string p = tmp_path(name);
  std::ofstream(p, std::ios::binary) << text;
  return p;
}

// Runs f, which must throw an InputError for path at the given line and field, with all three in
// what() ("file:line: field: message").
template <class F>
void require_input_error(F&& f, const std::string& path, long line, const std::string& field) {
  const std::string file = path.substr(path.find_last_of('/') + 1);
  try {
    f();
  } catch (const furniture_fem::InputError& e) {
    const std::string what = e.what();
    INFO("what(): " << what);
    CHECK(what.find(file) != std::string::npos);
    CHECK(what.find(":" + std::to_string(line) + ":") != std::string::npos);
    CHECK(what.find(": " + field + ": ") != std::string::npos);
    CHECK(e.line() == line);
    CHECK(e.field() == field);
    return;
  }
  FAIL("no InputError thrown for " << path);
}

// Fortran E15.7 as in PEER files: "  -.1416764E-03". Returns the text and the value it stands for.
std::string fortran_e(double v, double& exact) {
  if (v == 0) {
    exact = 0;
    return "   .0000000E+00";
  }
  int e = static_cast<int>(std::floor(std::log10(std::abs(v)))) + 1;
  long digits = std::lround(std::abs(v) / std::pow(10.0, e) * 1e7);
  if (digits >= 10000000) {
    digits /= 10;
    ++e;
  }
  exact = (v < 0 ? -1.0 : 1.0) * double(digits) * std::pow(10.0, e - 7);
  char buf[64];
  std::snprintf(buf, sizeof buf, "%s.%07ldE%c%02d", v < 0 ? "-" : "", digits, e < 0 ? '-' : '+', std::abs(e) % 100);
  char out[80];
  std::snprintf(out, sizeof out, "%15s", buf);
  return out;
}

const char* const kKobeHeader =
    "PEER NGA STRONG MOTION DATABASE RECORD\n"
    "Kobe Japan, 1/16/1995, KJMA, 0\n"
    "ACCELERATION TIME SERIES IN UNITS OF G\n";

const char* const kKnetHeader =
    "Origin Time       2011/03/11 14:46:00\n"
    "Lat.              38.103\n"
    "Long.             142.860\n"
    "Depth. (km)       24\n"
    "Mag.              9.0\n"
    "Station Code      TCGH16\n"
    "Station Lat.      36.5481\n"
    "Station Long.     140.0808\n"
    "Station Height(m) 122\n"
    "Record Time       2011/03/11 14:46:21\n"
    "Sampling Freq(Hz) 100Hz\n"
    "Duration Time(s)  300\n"
    "Dir.              N-S\n"
    "Scale Factor      3920(gal)/6182761\n"
    "Max. Acc. (gal)   1197.023\n"
    "Last Correction   2011/03/11 14:46:06\n"
    "Memo.\n";

const char* const kJmaHeader =
    "SITE CODE= 637\n"
    "ALT.LAT.= 34.683 (deg)\n"
    "ALT.LONG.= 135.180 (deg)\n"
    "SAMPLING RATE= 100Hz\n"
    "UNIT  = gal\n"
    "INITIAL TIME = 1995 01 17 05 46 00\n";

}  // namespace

TEST_CASE("PEER AT2 (JMA Kobe header, NPTS = 7500, DT = .020): a = value_g * 9.80665 m/s^2", "[excitation][readers]") {
  // 7500 samples, 5 per line; the Kobe NS peak -.8342289 g placed at sample 427 (t = 8.52 s).
  std::string text = std::string(kKobeHeader) + "NPTS =   7500 , DT =   .020 SEC ,\n";
  std::vector<double> expect;
  for (int i = 0; i < 7500; ++i) {
    double v = i == 426 ? -0.8342289 : 1e-3 * std::sin(0.37 * i) * std::exp(-1e-4 * i);
    if (i == 0) v = -.1416764E-03;
    double exact = 0;
    text += fortran_e(v, exact);
    if (i % 5 == 4) text += "\n";
    expect.push_back(exact * 9.80665);
  }
  const std::string p = write_file("kobe.AT2", text);
  REQUIRE(furniture_fem::detect_format(p) == furniture_fem::Format::peer_at2);
  const furniture_fem::Record r = furniture_fem::read_record(p);
  CHECK(r.name == "Kobe Japan, 1/16/1995, KJMA, 0");
  CHECK(r.dt == Approx(0.02).epsilon(1e-15));
  CHECK(r.t0 == 0.0);
  REQUIRE(r.size() == 7500);
  CHECK(r.acc[0] == Approx(-.1416764E-03 * 9.80665).epsilon(1e-14));
  for (std::size_t i = 0; i < r.size(); ++i) REQUIRE(r.acc[i] == Approx(expect[i]).epsilon(1e-14).margin(1e-300));
  CHECK(r.peak() == Approx(0.8342289 * 9.80665).epsilon(1e-14));  // 8.1810 m/s^2 = 818.10 gal
  CHECK(r.peak_time() == Approx(8.52).epsilon(1e-12));
  CHECK(r.duration() == Approx(7499 * 0.02).epsilon(1e-12));
}

TEST_CASE("PEER AT2 older header '7 0.0200 NPTS, DT' and run-together Fortran numbers", "[excitation][readers]") {
  const std::string p = write_file("old.AT2",
                                   "PEER STRONG MOTION DATABASE RECORD. PROCESSING BY PACIFIC ENGINEERING.\n"
                                   "IMPERIAL VALLEY 05/19/40 0439, EL CENTRO ARRAY #9, 180\n"
                                   "ACCELERATION TIME HISTORY IN UNITS OF G\n"
                                   "    7    0.0200    NPTS, DT\n"
                                   "  .1000000E-01-.2000000E-01  .3000000E-01  .4000000E+00  .5000000E-01\n"
                                   "  -.6000000E-01   .7000000D-02\n");
  const furniture_fem::Record r = furniture_fem::read_peer_at2(p);
  REQUIRE(r.size() == 7);
  CHECK(r.dt == 0.02);
  CHECK(r.acc[1] == Approx(-0.02 * 9.80665));
  CHECK(r.acc[3] == Approx(0.4 * 9.80665));
  CHECK(r.acc[6] == Approx(0.007 * 9.80665));
}

TEST_CASE("K-NET/KiK-net ASCII: a = (count - mean) * 3920/6182761 gal * 0.01 m/s^2, dt = 1/100 Hz", "[excitation][readers]") {
  const long counts[16] = {-19885, -19862, -19850, -19853, -19881, -19888, -19874, -19867,
                           -19860, -19870, -19878, -19880, -19869, -19865, -19871, -16000};
  std::string text = kKnetHeader;
  double mean = 0;
  for (int i = 0; i < 16; ++i) {
    char buf[16];
    std::snprintf(buf, sizeof buf, "%8ld", counts[i]);
    text += buf;
    if (i % 8 == 7) text += "\n";
    mean += double(counts[i]) / 16.0;
  }
  const std::string p = write_file("TCGH161103111446.NS2", text);
  REQUIRE(furniture_fem::detect_format(p) == furniture_fem::Format::knet);
  const furniture_fem::Record r = furniture_fem::read_record(p);
  CHECK(r.name == "TCGH16 N-S");
  CHECK(r.dt == Approx(0.01).epsilon(1e-15));
  REQUIRE(r.size() == 16);
  for (int i = 0; i < 16; ++i) CHECK(r.acc[i] == Approx((double(counts[i]) - mean) * 3920.0 / 6182761.0 * 0.01).epsilon(1e-12));
  double sum = 0;
  for (double a : r.acc) sum += a;
  CHECK(std::abs(sum) < 1e-12);  // mean removed
  // Without the mean removal the raw counts are scaled as they are.
  const furniture_fem::Record raw = furniture_fem::read_knet(p, false);
  CHECK(raw.acc[15] == Approx(-16000.0 * 3920.0 / 6182761.0 * 0.01).epsilon(1e-14));
}

TEST_CASE("JMA CSV: three components NS, EW, UD in gal -> m/s^2 (* 0.01), dt = 1/100 Hz", "[excitation][readers]") {
  const std::string p = write_file("kobe_jma.csv", std::string(kJmaHeader) +
                                                       "NS,EW,UD\n"
                                                       "-0.5,1.25,3.0\n"
                                                       "818.1,-617.5,332.4\n"
                                                       "2.0,-1.0,0.25\n");
  REQUIRE(furniture_fem::detect_format(p) == furniture_fem::Format::jma_csv);
  const auto c = furniture_fem::read_jma_csv(p);
  for (const auto& r : c) {
    REQUIRE(r.size() == 3);
    CHECK(r.dt == Approx(0.01).epsilon(1e-15));
  }
  CHECK(c[0].name == "JMA 637 NS");
  CHECK(c[0].acc[1] == Approx(8.181).epsilon(1e-14));
  CHECK(c[1].acc[1] == Approx(-6.175).epsilon(1e-14));
  CHECK(c[2].acc[1] == Approx(3.324).epsilon(1e-14));
  CHECK(c[2].acc[2] == Approx(0.0025).epsilon(1e-14));
  furniture_fem::ReadOptions ew;
  ew.component = 1;
  CHECK(furniture_fem::read_record(p, furniture_fem::Format::automatic, ew).acc[0] == Approx(0.0125).epsilon(1e-14));

  // A UTF-8 BOM and CRLF line ends (CSV exports on Windows) change nothing.
  std::string crlf = "\xEF\xBB\xBF" + std::string(kJmaHeader) + "NS,EW,UD\n-0.5,1.25,3.0\n0,0,0\n";
  for (std::size_t k = crlf.find('\n'); k != std::string::npos; k = crlf.find('\n', k + 2)) crlf.insert(k, "\r");
  const std::string w = write_file("kobe_jma_crlf.csv", crlf);
  REQUIRE(furniture_fem::detect_format(w) == furniture_fem::Format::jma_csv);
  const auto cw = furniture_fem::read_jma_csv(w);
  CHECK(cw[0].name == "JMA 637 NS");
  CHECK(cw[1].acc[0] == Approx(0.0125).epsilon(1e-14));

  // Columns in another order are mapped by name.
  const std::string q = write_file("jma_order.csv", std::string(kJmaHeader) + " UD, NS, EW\n1,2,3\n0,0,0\n");
  const auto d = furniture_fem::read_jma_csv(q);
  CHECK(d[0].acc[0] == Approx(0.02));
  CHECK(d[1].acc[0] == Approx(0.03));
  CHECK(d[2].acc[0] == Approx(0.01));

  // One sample is no record (it ran before, issue 13; tests/corpus/cases/record_jma/one_sample.json).
  const std::string one = write_file("jma_one_sample.csv", std::string(kJmaHeader) + "NS,EW,UD\n1,2,3\n");
  CHECK_THROWS_AS(furniture_fem::read_jma_csv(one), furniture_fem::InputError);
}

TEST_CASE("columns: (time, gal) pairs give dt = t1 - t0 and t0 = first time; values need dt", "[excitation][readers]") {
  const std::string p = write_file("elcentro.txt",
                                   "        0.02000       -1.40000\n"
                                   "        0.04000      -10.80000\n"
                                   "        0.06000      -10.10000\n"
                                   "        0.08000       -8.80000\n");
  REQUIRE(furniture_fem::detect_format(p) == furniture_fem::Format::columns);
  furniture_fem::ReadOptions gal;
  gal.unit = furniture_fem::Unit::gal;
  const furniture_fem::Record r = furniture_fem::read_record(p, furniture_fem::Format::automatic, gal);
  REQUIRE(r.size() == 4);
  CHECK(r.dt == Approx(0.02).epsilon(1e-14));
  CHECK(r.t0 == Approx(0.02).epsilon(1e-14));
  CHECK(r.acc[1] == Approx(-0.108).epsilon(1e-14));
  CHECK(r.value_at(0.01) == 0.0);  // before the first sample
  CHECK(r.value_at(0.03) == Approx(-0.061).epsilon(1e-12));

  // Units: g and m/s^2.
  furniture_fem::ReadOptions in_g;
  in_g.unit = furniture_fem::Unit::g;
  CHECK(furniture_fem::read_columns(p, in_g).acc[0] == Approx(-1.4 * 9.80665).epsilon(1e-14));
  CHECK(furniture_fem::read_columns(p).acc[0] == Approx(-1.4).epsilon(1e-14));

  // A single column needs dt.
  const std::string single = write_file("single.txt", "# one value per line\n0.5\n0.25\n");
  require_input_error([&] { (void)furniture_fem::read_columns(single); }, single, 2, "columns");
  furniture_fem::ReadOptions dt;
  dt.dt = 0.005;
  const furniture_fem::Record s = furniture_fem::read_columns(single, dt);
  CHECK(s.size() == 2);
  CHECK(s.dt == 0.005);
}

TEST_CASE("columns: comments, a leading '0.02 0.50' line skipped with skip_lines, 5 values per line", "[excitation][readers]") {
  const std::string p = write_file("kobe_unprocessed.txt",
                                   ";Recorded at Kobe station, dt=0.02, time window = 60s, acc. in cm/s/s\n"
                                   ";NS  component, Peak given in unit [g]\n"
                                   "0.02 0.50\n"
                                   " -0.3289795     -0.3588867     -0.4187012     -0.3588867     -0.1794434    \n"
                                   " -818.0220      0.7476807\n");
  REQUIRE(furniture_fem::detect_format(p) == furniture_fem::Format::columns);
  furniture_fem::ReadOptions o;
  o.unit = furniture_fem::Unit::gal;
  o.dt = 0.02;
  o.skip_lines = 3;
  const furniture_fem::Record r = furniture_fem::read_record(p, furniture_fem::Format::columns, o);
  REQUIRE(r.size() == 7);
  CHECK(r.acc[0] == Approx(-0.003289795).epsilon(1e-14));
  CHECK(r.peak() == Approx(8.18022).epsilon(1e-14));
  CHECK(r.peak_time() == Approx(0.10).epsilon(1e-14));
  // The trap skip_lines avoids: without it "0.02 0.50" would be read as two samples.
  o.skip_lines = 0;
  CHECK(furniture_fem::read_record(p, furniture_fem::Format::columns, o).size() == 9);
}

TEST_CASE("write_columns then read_columns gives the record back (17 significant digits)", "[excitation][readers]") {
  furniture_fem::Record r{"round trip", "test", 0.01, {0.1, -2.0 / 3.0, 1e-17, 9.80665, 0.0}, 1.5};
  const std::string p = tmp_path("roundtrip.txt");
  furniture_fem::write_columns(p, r);
  REQUIRE(furniture_fem::detect_format(p) == furniture_fem::Format::columns);
  const furniture_fem::Record back = furniture_fem::read_record(p);
  CHECK(back.name == "excitation_roundtrip");
  REQUIRE(back.size() == r.size());
  for (std::size_t i = 0; i < r.size(); ++i) CHECK(back.acc[i] == r.acc[i]);
  CHECK(back.t0 == r.t0);
  CHECK(back.dt == Approx(r.dt).epsilon(1e-14));
}

TEST_CASE("missing header: InputError names the file, the line and the missing field", "[excitation][errors]") {
  // AT2 whose NPTS/DT line is gone: line 4 is data.
  const std::string at2 = write_file("noheader.AT2", std::string(kKobeHeader) +
                                                         "  -.1416764E-03  -.1418977E-03  -.1421037E-03\n");
  require_input_error([&] { (void)furniture_fem::read_peer_at2(at2); }, at2, 4, "NPTS");
  const std::string short_at2 = write_file("short.AT2", "PEER NGA STRONG MOTION DATABASE RECORD\n");
  require_input_error([&] { (void)furniture_fem::read_record(short_at2); }, short_at2, 4, "NPTS");

  // K-NET without its Scale Factor line: reported at "Memo." (line 16 once the line is removed).
  std::string knet = kKnetHeader;
  knet.erase(knet.find("Scale Factor"), std::string("Scale Factor      3920(gal)/6182761\n").size());
  const std::string kp = write_file("noscale.EW", knet + "  -19885  -19862\n");
  require_input_error([&] { (void)furniture_fem::read_knet(kp); }, kp, 16, "Scale Factor");

  // JMA without SAMPLING RATE: reported at the column line (line 6 once the line is removed).
  std::string jma = kJmaHeader;
  jma.erase(jma.find("SAMPLING RATE"), std::string("SAMPLING RATE= 100Hz\n").size());
  const std::string jp = write_file("norate.csv", jma + "NS,EW,UD\n1,2,3\n");
  require_input_error([&] { (void)furniture_fem::read_jma_csv(jp); }, jp, 6, "SAMPLING RATE");

  // JMA rows before the NS,EW,UD column line.
  const std::string jc = write_file("nocols.csv", std::string(kJmaHeader) + "1,2,3\n");
  require_input_error([&] { (void)furniture_fem::read_jma_csv(jc); }, jc, 7, "NS,EW,UD");
}

TEST_CASE("a 50 kB header line: a named error, not a stack overflow", "[excitation][errors]") {
  // std::regex recursed once per character of these lines and crashed (SIGSEGV) on 50 kB (issue 13,
  // found by fuzzing); the header patterns are now scanned left to right. Each file below failed before.
  const std::string long_digits(50000, '7'), long_blanks(50000, ' ');
  // AT2 line 4: a sample count of 50 000 digits is implausible; blanks before "NPTS" are fine.
  const std::string at2 = write_file("long_npts.AT2", std::string(kKobeHeader) + "NPTS = " + long_digits +
                                                          ", DT = .020 SEC\n   .1000000E+00\n");
  require_input_error([&] { (void)furniture_fem::read_peer_at2(at2); }, at2, 4, "NPTS");
  const std::string padded = write_file("padded.AT2", std::string(kKobeHeader) + long_blanks +
                                                          "NPTS =    2, DT = .020 SEC\n   .1000000E+00   .2000000E+00\n");
  const furniture_fem::Record r = furniture_fem::read_peer_at2(padded);
  CHECK(r.acc.size() == 2);
  CHECK(r.dt == 0.02);
  // K-NET "Sampling Freq" and "Scale Factor", JMA "SAMPLING RATE": 50 kB of junk after the number.
  std::string knet = kKnetHeader;
  knet.replace(knet.find("100Hz"), 5, "100" + std::string(50000, 'x'));
  const std::string kf = write_file("long_freq.NS", knet + "  -19885  -19862\n");
  require_input_error([&] { (void)furniture_fem::read_knet(kf); }, kf, 11, "Sampling Freq(Hz)");
  knet = kKnetHeader;
  knet.replace(knet.find("6182761"), 7, long_digits + "(");
  const std::string ks = write_file("long_scale.NS", knet + "  -19885  -19862\n");
  require_input_error([&] { (void)furniture_fem::read_knet(ks); }, ks, 14, "Scale Factor");
  std::string jma = kJmaHeader;
  jma.replace(jma.find("100Hz"), 5, long_digits + "Hz!");
  const std::string jr = write_file("long_rate.csv", jma + "NS,EW,UD\n1,2,3\n");
  require_input_error([&] { (void)furniture_fem::read_jma_csv(jr); }, jr, 4, "SAMPLING RATE");
}

TEST_CASE("implausible time steps and fewer than two samples: a named error at the header line",
          "[excitation][errors]") {
  // Issue 13: DT = inf, 1e-300, 1e300 or 1e5 s ran, and NPTS = 0 "completed" with a table that never
  // moved. A strong-motion record is sampled every 1e-5 to 1 s and has at least two samples.
  const std::string two = "   .1000000E+00   .2000000E+00\n";
  for (const char* dt : {"1e-300", "1E+300", "1E5", "2.0", "5E-6"}) {
    const std::string p = write_file("dt.AT2", std::string(kKobeHeader) + "NPTS =    2, DT = " + dt + " SEC\n" + two);
    INFO("DT = " << dt);
    require_input_error([&] { (void)furniture_fem::read_peer_at2(p); }, p, 4, "DT");
  }
  for (const char* dt : {"1", "1E-5", ".005"}) {  // the ends of the range are records
    const std::string p = write_file("dt_ok.AT2", std::string(kKobeHeader) + "NPTS =    2, DT = " + dt + " SEC\n" + two);
    CHECK(furniture_fem::read_peer_at2(p).acc.size() == 2);
  }
  for (const char* n : {"0", "1"}) {
    const std::string p = write_file("few.AT2", std::string(kKobeHeader) + "NPTS =    " + n + ", DT = .01 SEC\n" +
                                                    (n[0] == '1' ? "   .1000000E+00\n" : ""));
    require_input_error([&] { (void)furniture_fem::read_peer_at2(p); }, p, 4, "NPTS");
  }
  std::string knet = kKnetHeader;
  knet.replace(knet.find("100Hz"), 5, "0.001Hz");
  const std::string kf = write_file("slow.NS", knet + "  -19885  -19862\n");
  require_input_error([&] { (void)furniture_fem::read_knet(kf); }, kf, 11, "Sampling Freq(Hz)");
  std::string jma = kJmaHeader;
  jma.replace(jma.find("100Hz"), 5, "1e9Hz");
  const std::string jr = write_file("fast.csv", jma + "NS,EW,UD\n1,2,3\n4,5,6\n");
  require_input_error([&] { (void)furniture_fem::read_jma_csv(jr); }, jr, 4, "SAMPLING RATE");
  const std::string cols = write_file("hours.txt", "0 1.0\n3600 2.0\n7200 3.0\n");
  require_input_error([&] { (void)furniture_fem::read_columns(cols); }, cols, 2, "time");
}

TEST_CASE("non-numeric sample: InputError at its line, field 'sample k' (or the column name)", "[excitation][errors]") {
  const std::string at2 = write_file("alpha.AT2", std::string(kKobeHeader) +
                                                      "NPTS =   7 , DT =   .020 SEC ,\n"
                                                      "  -.1416764E-03  -.1418977E-03  -.1421037E-03  -.1423125E-03  -.1425214E-03\n"
                                                      "  -.1427419E-03  -.14x9308E-03\n");
  require_input_error([&] { (void)furniture_fem::read_peer_at2(at2); }, at2, 6, "sample 7");

  const std::string knet = write_file("alpha.NS", std::string(kKnetHeader) + "  -19885  -19862  abc\n");
  require_input_error([&] { (void)furniture_fem::read_knet(knet); }, knet, 18, "sample 3");

  const std::string jma = write_file("alpha.csv", std::string(kJmaHeader) + "NS,EW,UD\n1,2,3\n1.0,abc,2\n");
  require_input_error([&] { (void)furniture_fem::read_jma_csv(jma); }, jma, 9, "EW");

  const std::string cols = write_file("alpha.txt", "0.00 1.0\n0.01 2.O\n");
  require_input_error([&] { (void)furniture_fem::read_columns(cols); }, cols, 2, "acceleration");
}

TEST_CASE("NaN or inf sample: InputError at its line and field", "[excitation][errors]") {
  const std::string at2 = write_file("nan.AT2", std::string(kKobeHeader) +
                                                    "NPTS =   3 , DT =   .020 SEC ,\n"
                                                    "  -.1416764E-03            NaN  -.1421037E-03\n");
  require_input_error([&] { (void)furniture_fem::read_peer_at2(at2); }, at2, 5, "sample 2");
  try {
    (void)furniture_fem::read_peer_at2(at2);
  } catch (const furniture_fem::InputError& e) {
    CHECK(std::string(e.what()).find("NaN") != std::string::npos);
  }
  const std::string cols = write_file("inf.txt", "0.00 1.0\n0.01 inf\n");
  require_input_error([&] { (void)furniture_fem::read_columns(cols); }, cols, 2, "acceleration");
  const std::string big = write_file("overflow.txt", "# overflow to inf\n1e999\n");
  furniture_fem::ReadOptions o;
  o.dt = 0.01;
  require_input_error([&] { (void)furniture_fem::read_columns(big, o); }, big, 2, "sample 1");
}

TEST_CASE("NPTS mismatch: too few samples at the NPTS line 4, too many where they start", "[excitation][errors]") {
  const std::string body =
      "  -.1416764E-03  -.1418977E-03  -.1421037E-03  -.1423125E-03  -.1425214E-03\n"
      "  -.1427419E-03  -.1429308E-03\n";
  const std::string few = write_file("few.AT2", std::string(kKobeHeader) + "NPTS =   8 , DT =   .020 SEC ,\n" + body);
  require_input_error([&] { (void)furniture_fem::read_peer_at2(few); }, few, 4, "NPTS");
  const std::string many = write_file("many.AT2", std::string(kKobeHeader) + "NPTS =   6 , DT =   .020 SEC ,\n" + body);
  require_input_error([&] { (void)furniture_fem::read_peer_at2(many); }, many, 6, "NPTS");
}

TEST_CASE("time not increasing (or not uniform) in (time, value) columns: InputError field 'time'", "[excitation][errors]") {
  const std::string p = write_file("repeat.txt", "# t a\n0.00 1.0\n0.02 2.0\n0.02 3.0\n0.04 4.0\n");
  require_input_error([&] { (void)furniture_fem::read_columns(p); }, p, 4, "time");
  const std::string back = write_file("back.txt", "0.00 1.0\n0.02 2.0\n0.01 3.0\n");
  require_input_error([&] { (void)furniture_fem::read_columns(back); }, back, 3, "time");
  const std::string gap = write_file("gap.txt", "0.00 1.0\n0.01 2.0\n0.03 3.0\n0.04 3.0\n0.05 3.0\n");
  require_input_error([&] { (void)furniture_fem::read_columns(gap); }, gap, 3, "time");
}

TEST_CASE("unknown format: InputError at the first line that is neither a header nor numbers", "[excitation][errors]") {
  const std::string p = write_file("unknown.dat", "# exported by some tool\nHello, this is not a record\n1 2\n");
  require_input_error([&] { (void)furniture_fem::detect_format(p); }, p, 2, "format");
  require_input_error([&] { (void)furniture_fem::read_record(p); }, p, 2, "format");
}

TEST_CASE("empty file: InputError at line 1, field 'file', from every reader", "[excitation][errors]") {
  const std::string p = write_file("empty.AT2", "");
  require_input_error([&] { (void)furniture_fem::detect_format(p); }, p, 1, "file");
  require_input_error([&] { (void)furniture_fem::read_record(p); }, p, 1, "file");
  require_input_error([&] { (void)furniture_fem::read_peer_at2(p); }, p, 1, "file");
  require_input_error([&] { (void)furniture_fem::read_knet(p); }, p, 1, "file");
  require_input_error([&] { (void)furniture_fem::read_jma_csv(p); }, p, 1, "file");
  require_input_error([&] { (void)furniture_fem::read_columns(p); }, p, 1, "file");
  const std::string blank = write_file("blank.txt", "\n   \n\t\n");
  require_input_error([&] { (void)furniture_fem::read_record(blank); }, blank, 1, "file");
  // A file with only comments has no samples.
  const std::string comments = write_file("comments.txt", "# nothing\n; here\n");
  CHECK_THROWS_AS(furniture_fem::read_record(comments), furniture_fem::InputError);
  // A missing file.
  CHECK_THROWS_AS(furniture_fem::read_record(tmp_path("does_not_exist.AT2")), furniture_fem::InputError);
}

TEST_CASE("a sample that overflows once converted to m/s^2: InputError at its line and field (fuzzing)",
          "[excitation][errors]") {
  // 1e308 g is finite in the file but not in m/s^2; every reader gave an infinite sample before
  // (found by tests/fuzz, docs/fuzzing.md).
  const std::string at2 = write_file("overflow_g.AT2", std::string(kKobeHeader) +
                                                           "NPTS =   3 , DT =   .020 SEC ,\n"
                                                           "  -.1416764E-03  -.1421037E-03\n"
                                                           "  1e308\n");
  require_input_error([&] { (void)furniture_fem::read_peer_at2(at2); }, at2, 6, "sample 3");
  try {
    (void)furniture_fem::read_peer_at2(at2);
  } catch (const furniture_fem::InputError& e) {
    CHECK(std::string(e.what()).find("1e+308") != std::string::npos);
  }
  // K-NET: a scale factor whose ratio overflows, and counts whose sum (for the mean) overflows.
  std::string knet = kKnetHeader;
  knet.replace(knet.find("3920(gal)/6182761"), 17, "1e300(gal)/1e-300");
  const std::string ks = write_file("overflow_scale.NS", knet + "1 2 3\n");
  require_input_error([&] { (void)furniture_fem::read_knet(ks); }, ks, 14, "Scale Factor");
  knet = kKnetHeader;
  knet.replace(knet.find("3920(gal)/6182761"), 17, "3920(gal)/1");
  const std::string kb = write_file("overflow_counts.NS", knet + "1 2 3\n1e308 1e308 -1e308\n");
  require_input_error([&] { (void)furniture_fem::read_knet(kb, false); }, kb, 19, "sample 4");
  // Counts whose sum overflows: the mean is still found (an infinite mean made every sample infinite).
  const std::string kc = write_file("huge_counts.NS", std::string(kKnetHeader) + "1 2 3\n1e308 1e308 -1e308\n");
  const auto mean_removed = furniture_fem::read_knet(kc, true);
  for (double a : mean_removed.acc) CHECK(std::isfinite(a));
  // JMA in g, columns in g.
  std::string jma = kJmaHeader;
  jma.replace(jma.find("UNIT  = gal"), 11, "UNIT  = g");
  const std::string jp = write_file("overflow_g.csv", jma + "NS,EW,UD\n1,2,3\n4,1e308,6\n");
  require_input_error([&] { (void)furniture_fem::read_jma_csv(jp); }, jp, 9, "EW");
  furniture_fem::ReadOptions g;
  g.unit = furniture_fem::Unit::g;
  const std::string cp = write_file("overflow_g.txt", "0 1\n0.01 1e308\n0.02 3\n");
  require_input_error([&] { (void)furniture_fem::read_columns(cp, g); }, cp, 2, "acceleration");
  g.dt = 0.01;
  const std::string vp = write_file("overflow_g_values.txt", "1 2\n3 1e308\n");
  require_input_error([&] { (void)furniture_fem::read_columns(vp, g); }, vp, 2, "sample 4");
}

}  // namespace readers_tests
