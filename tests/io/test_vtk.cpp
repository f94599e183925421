// VTU and PVD writers, read back with a minimal XML scan; the binary, zlib-compressed VTU decoded here
// with zlib as VTK's reader decodes it.
#include <catch2/catch.hpp>

#include <sys/resource.h>

#include <zlib.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <csignal>
#include <map>
#include <random>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "furniture_fem/io/vtk.hpp"
#include "../support/test_files.hpp"

namespace vtk_tests {  // this file's own names (its group compiles files in batches)

namespace fs = std::filesystem;
using namespace furniture_fem;

using ffem_test::slurp;
using ffem_test::tmp;

namespace {
std::size_t count(const std::string& s, const std::string& what) {
  std::size_t n = 0;
  for (auto p = s.find(what); p != std::string::npos; p = s.find(what, p + 1)) ++n;
  return n;
}
// The text content of the DataArray whose Name attribute is `name`, inside <section> ... </section>.
std::vector<double> array(const std::string& xml, const std::string& section, const std::string& name) {
  const auto s0 = xml.find("<" + section);
  const auto s1 = xml.find("</" + section + ">");
  REQUIRE(s0 != std::string::npos);
  REQUIRE(s1 != std::string::npos);
  const auto a = xml.find("Name=\"" + name + "\"", s0);
  REQUIRE(a < s1);
  const auto open_end = xml.find('>', a);
  const auto close = xml.find("</DataArray>", open_end);
  std::istringstream in(xml.substr(open_end + 1, close - open_end - 1));
  std::vector<double> v;
  for (double d; in >> d;) v.push_back(d);
  return v;
}
std::string attribute_of_array(const std::string& xml, const std::string& name, const std::string& attr) {
  const auto a = xml.rfind("<DataArray", xml.find("Name=\"" + name + "\""));
  const auto e = xml.find('>', a);
  const auto p = xml.find(attr + "=\"", a);
  if (p == std::string::npos || p > e) return "";
  const auto q = p + attr.size() + 2;
  return xml.substr(q, xml.find('"', q) - q);
}
bool close_rel(double a, double b) { return std::abs(a - b) <= 1e-12 * std::max(std::abs(a), std::abs(b)) || a == b; }
}  // namespace

TEST_CASE("VTU: 3 points, 2 lines, point and cell fields round-trip", "[vtk]") {
  LineMesh m;
  m.points = {Eigen::Vector3d(0.1, 1.0 / 3.0, -2.5e10), Eigen::Vector3d(1, 0, 3.14159265358979e-7),
              Eigen::Vector3d(2, 1e-300, 0)};
  m.lines = {{0, 1}, {1, 2}};
  const std::vector<Eigen::Vector3d> disp = {Eigen::Vector3d(1e-3, -2e-3, 7.0 / 3.0), Eigen::Vector3d(0, 0, 0),
                                             Eigen::Vector3d(-1.5, 2.25, 1e-9)};
  m.add_point_vector("displacement", disp)
      .add_point_scalar("node id", {1, 2, 3})
      .add_cell_scalar("axial force", {1234.5, -0.001})
      .add_cell_vector("moment", {Eigen::Vector3d(1, 2, 3), Eigen::Vector3d(-4, 5.5, 1e20)});
  const std::string path = tmp("mesh.vtu");
  write_vtu(path, m, VtuOptions::ascii());
  REQUIRE(fs::exists(path));
  CHECK_FALSE(fs::exists(path + ".tmp"));
  const std::string xml = slurp(path);

  CHECK(xml.rfind("<?xml", 0) == 0);
  CHECK(xml.find("<VTKFile type=\"UnstructuredGrid\"") != std::string::npos);
  CHECK(xml.find("NumberOfPoints=\"3\"") != std::string::npos);
  CHECK(xml.find("NumberOfCells=\"2\"") != std::string::npos);
  CHECK(count(xml, "<DataArray") == count(xml, "</DataArray>"));
  CHECK(count(xml, "<DataArray") == 4 + 1 + 3);
  CHECK(xml.find("</VTKFile>") != std::string::npos);

  CHECK(array(xml, "Cells", "connectivity") == std::vector<double>{0, 1, 1, 2});
  CHECK(array(xml, "Cells", "offsets") == std::vector<double>{2, 4});
  CHECK(array(xml, "Cells", "types") == std::vector<double>{3, 3});
  CHECK(attribute_of_array(xml, "types", "type") == "UInt8");

  const auto pts = array(xml, "Points", "Points");
  REQUIRE(pts.size() == 9);
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) CHECK(close_rel(pts[std::size_t(3 * i + k)], m.points[std::size_t(i)][k]));

  const auto d = array(xml, "PointData", "displacement");
  REQUIRE(d.size() == 9);
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) CHECK(close_rel(d[std::size_t(3 * i + k)], disp[std::size_t(i)][k]));
  CHECK(attribute_of_array(xml, "displacement", "NumberOfComponents") == "3");
  CHECK(attribute_of_array(xml, "node id", "NumberOfComponents") == "1");
  CHECK(array(xml, "PointData", "node id") == std::vector<double>{1, 2, 3});

  const auto f = array(xml, "CellData", "axial force");
  REQUIRE(f.size() == 2);
  CHECK(close_rel(f[0], 1234.5));
  CHECK(close_rel(f[1], -0.001));
  const auto mo = array(xml, "CellData", "moment");
  REQUIRE(mo.size() == 6);
  CHECK(close_rel(mo[5], 1e20));
  // ParaView colours by the declared active arrays.
  CHECK(xml.find("<PointData Scalars=\"node id\" Vectors=\"displacement\">") != std::string::npos);
}

TEST_CASE("VTU rejects inconsistent meshes and names the path", "[vtk]") {
  LineMesh m;
  m.points = {Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX()};
  m.lines = {{0, 2}};
  CHECK_THROWS_AS(write_vtu(tmp("bad.vtu"), m), InputError);
  m.lines = {{0, 1}};
  m.add_point_scalar("short", {1.0});
  CHECK_THROWS_AS(write_vtu(tmp("bad.vtu"), m), InputError);
  m.point_data.clear();
  m.add_cell_scalar("nan", {NAN});
  try {
    write_vtu(tmp("bad.vtu"), m);
    FAIL("NaN accepted");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()).find("'nan'") != std::string::npos);
  }
  m.cell_data.clear();
  const std::string missing = tmp("no_such_dir/x.vtu");
  try {
    write_vtu(missing, m);
    FAIL("write into a missing folder did not throw");
  } catch (const OutputError& e) {
    CHECK(std::string(e.what()).find(missing) != std::string::npos);
  }
}

namespace {
// While alive, regular files cannot grow beyond `bytes` (writes past it fail with EFBIG, SIGXFSZ
// ignored): a full disk, for this process only.
class FileSizeLimit {
 public:
  explicit FileSizeLimit(rlim_t bytes) {
    getrlimit(RLIMIT_FSIZE, &saved_);
    old_handler_ = std::signal(SIGXFSZ, SIG_IGN);
    rlimit r = saved_;
    r.rlim_cur = bytes;
    ok_ = setrlimit(RLIMIT_FSIZE, &r) == 0;
  }
  ~FileSizeLimit() {
    setrlimit(RLIMIT_FSIZE, &saved_);
    std::signal(SIGXFSZ, old_handler_);
  }
  bool ok() const { return ok_; }

 private:
  rlimit saved_{};
  void (*old_handler_)(int) = nullptr;
  bool ok_ = false;
};
}  // namespace

TEST_CASE("a VTU or PVD write that fails leaves no .tmp file behind", "[vtk]") {
  // Issue 13: a full disk left vtu/room_<step>.vtu.tmp files behind, one per frame.
  LineMesh m;
  for (int i = 0; i < 2000; ++i) m.points.push_back(Eigen::Vector3d(i, 0.5 * i, 1.0 / (i + 1)));
  for (int i = 0; i + 1 < 2000; ++i) m.lines.push_back({i, i + 1});
  SECTION("the disk fills up while writing") {
    const std::string path = tmp("full_disk.vtu");
    fs::remove(path);
    fs::remove(path + ".tmp");
    {
      FileSizeLimit full(4096);  // the mesh's text is about 100 kB
      REQUIRE(full.ok());
      try {
        write_vtu(path, m);
        FAIL("a write past the file size limit did not throw");
      } catch (const OutputError& e) {
        CHECK_THAT(std::string(e.what()), Catch::Contains("error while writing '" + path + ".tmp'"));
      }
    }
    CHECK_FALSE(fs::exists(path + ".tmp"));
    CHECK_FALSE(fs::exists(path));
    write_vtu(path, m);  // without the limit the same write succeeds
    CHECK(fs::file_size(path) > 4096);
  }
  SECTION("the rename fails (a folder where the file should go)") {
    const std::string path = tmp("a_folder.vtu"), pvd_path = tmp("a_folder.pvd");
    for (const auto& p : {path, pvd_path}) {
      fs::remove_all(p);
      fs::create_directories(p + "/inside");
    }
    CHECK_THROWS_WITH(write_vtu(path, m), Catch::Contains("cannot rename '" + path + ".tmp' to '" + path + "'"));
    CHECK_FALSE(fs::exists(path + ".tmp"));
    PvdWriter pvd(pvd_path);
    pvd.add(0.0, "a.vtu");
    CHECK_THROWS_AS(pvd.write(), OutputError);
    CHECK_FALSE(fs::exists(pvd_path + ".tmp"));
  }
}

TEST_CASE("PVD lists the time steps in order", "[vtk]") {
  const std::string path = tmp("series.pvd");
  PvdWriter pvd(path);
  pvd.add(0.0, "frame_0000.vtu").add(0.05, "frame_0001.vtu");
  pvd.write();  // a partial collection is already valid
  pvd.add(0.1, (fs::path(FFEM_TEST_TMP) / "frames" / "frame_0002.vtu").string());  // absolute -> relative
  pvd.write();
  CHECK(pvd.size() == 3);
  const std::string xml = slurp(path);
  CHECK(xml.find("<VTKFile type=\"Collection\"") != std::string::npos);
  std::vector<double> times;
  std::vector<std::string> files;
  for (auto p = xml.find("<DataSet"); p != std::string::npos; p = xml.find("<DataSet", p + 1)) {
    const auto t = xml.find("timestep=\"", p) + 10;
    times.push_back(std::stod(xml.substr(t, xml.find('"', t) - t)));
    const auto f = xml.find("file=\"", p) + 6;
    files.push_back(xml.substr(f, xml.find('"', f) - f));
  }
  CHECK(times == std::vector<double>{0.0, 0.05, 0.1});
  CHECK(files == std::vector<std::string>{"frame_0000.vtu", "frame_0001.vtu", "frames/frame_0002.vtu"});
  CHECK_THROWS_AS(pvd.add(0.1, "again.vtu"), InputError);
  CHECK_THROWS_AS(pvd.add(0.05, "back.vtu"), InputError);
}

namespace {

// A decoded appended array of a binary VTU: its type, components and values (as double).
struct Decoded {
  std::string type;
  int components = 1;
  std::vector<double> values;
  std::vector<std::uint8_t> raw;  // the uncompressed bytes
};

std::string attr(const std::string& element, const std::string& name) {
  const auto p = element.find(" " + name + "=\"");
  if (p == std::string::npos) return "";
  const auto q = p + name.size() + 3;
  return element.substr(q, element.find('"', q) - q);
}

// Decodes every <DataArray format="appended"> of a VTU written with header_type UInt64 and
// vtkZLibDataCompressor, as VTK's reader does: the offset is counted from the byte after '_'; there, a
// header [blocks, block size, last block size (0: full), compressed size per block], then the blocks.
std::map<std::string, Decoded> decode_binary_vtu(const std::string& file) {
  const auto tag = file.find("<AppendedData encoding=\"raw\">");
  REQUIRE(tag != std::string::npos);
  const auto base = file.find('_', tag) + 1;
  const auto u64 = [&](std::size_t at) {
    std::uint64_t v;
    std::memcpy(&v, file.data() + at, 8);
    return v;
  };
  std::map<std::string, Decoded> out;
  for (auto p = file.find("<DataArray"); p < tag; p = file.find("<DataArray", p + 1)) {
    const std::string el = file.substr(p, file.find('>', p) - p);
    REQUIRE(attr(el, "format") == "appended");
    Decoded d;
    d.type = attr(el, "type");
    d.components = attr(el, "NumberOfComponents").empty() ? 1 : std::stoi(attr(el, "NumberOfComponents"));
    std::size_t at = base + std::stoull(attr(el, "offset"));
    const std::uint64_t blocks = u64(at), block = u64(at + 8), last = u64(at + 16);
    std::size_t data = at + 24 + 8 * blocks;
    for (std::uint64_t b = 0; b < blocks; ++b) {
      const std::uint64_t csize = u64(at + 24 + 8 * b);
      uLongf len = static_cast<uLongf>(b + 1 == blocks && last != 0 ? last : block);
      std::vector<std::uint8_t> buf(len);
      REQUIRE(uncompress(buf.data(), &len, reinterpret_cast<const Bytef*>(file.data() + data), static_cast<uLong>(csize)) == Z_OK);
      REQUIRE(len == (b + 1 == blocks && last != 0 ? last : block));
      d.raw.insert(d.raw.end(), buf.begin(), buf.end());
      data += csize;
    }
    const auto put = [&](auto zero) {
      using T = decltype(zero);
      REQUIRE(d.raw.size() % sizeof(T) == 0);
      for (std::size_t i = 0; i < d.raw.size(); i += sizeof(T)) {
        T v;
        std::memcpy(&v, d.raw.data() + i, sizeof(T));
        d.values.push_back(static_cast<double>(v));
      }
    };
    if (d.type == "Float64") put(double{});
    else if (d.type == "Float32") put(float{});
    else if (d.type == "Int32") put(std::int32_t{});
    else if (d.type == "UInt8") put(std::uint8_t{});
    else FAIL("unexpected type " << d.type);
    out[attr(el, "Name")] = std::move(d);
  }
  return out;
}

// A frame like the scene runner's: beams of 2 000 nodes along a room's furniture, shaken (positions
// with every mantissa bit in use), with a displacement vector, a body id and three element forces.
LineMesh shaken_frame(int nodes) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  LineMesh m;
  std::vector<Eigen::Vector3d> disp;
  std::vector<double> body, N, Q, M;
  for (int i = 0; i < nodes; ++i) {
    const double s = 0.01 * (i % 200);  // members of 200 nodes, 1 cm apart
    const Eigen::Vector3d X(0.3 * (i / 200) - 1.5, s * 0.2, 0.05 + s);
    const Eigen::Vector3d d(0.012 * std::sin(3 * s + i / 200) + 1e-5 * u(rng), 0.004 * std::cos(2 * s) + 1e-5 * u(rng),
                            -2e-4 * s + 1e-6 * u(rng));
    m.points.push_back(X + d + Eigen::Vector3d(0.0731, -0.0212, 0.0003));
    disp.push_back(d);
    if (i % 200 != 0) {
      m.lines.push_back({i - 1, i});
      body.push_back(i / 1000);
      N.push_back(-120 * s + 3 * u(rng));
      Q.push_back(std::abs(40 * std::sin(5 * s) + u(rng)));
      M.push_back(std::abs(8 * std::cos(4 * s) + 0.1 * u(rng)));
    }
  }
  m.add_point_vector("displacement", disp).add_cell_scalar("body", body).add_cell_scalar("N", N);
  m.add_cell_scalar("Q", Q).add_cell_scalar("M", M);
  return m;
}

}  // namespace

TEST_CASE("binary VTU: zlib-compressed, decoded to the same points to the bit, and far smaller than ASCII", "[vtk]") {
  const LineMesh m = shaken_frame(2000);
  const std::string bin = tmp("frame_binary.vtu"), txt = tmp("frame_ascii.vtu"), f32 = tmp("frame_float32.vtu");
  write_vtu(bin, m);  // the default: binary, compressed, Float64 points, Float32 fields
  write_vtu(txt, m, VtuOptions::ascii());
  VtuOptions all32;
  all32.float32_points = true;
  write_vtu(f32, m, all32);
  const std::string file = slurp(bin);
  CHECK(file.find("compressor=\"vtkZLibDataCompressor\"") != std::string::npos);
  CHECK(file.find("header_type=\"UInt64\"") != std::string::npos);
  CHECK(file.find("format=\"ascii\"") == std::string::npos);
  CHECK_FALSE(fs::exists(bin + ".tmp"));

  const auto arrays = decode_binary_vtu(file);
  REQUIRE(arrays.size() == 5 + 1 + 3);
  // The points: Float64, the same doubles to the bit.
  const Decoded& pts = arrays.at("Points");
  CHECK(pts.type == "Float64");
  CHECK(pts.components == 3);
  REQUIRE(pts.raw.size() == 3 * m.points.size() * sizeof(double));
  bool same_bits = true;
  for (std::size_t i = 0; i < m.points.size(); ++i)
    same_bits = same_bits && std::memcmp(pts.raw.data() + 24 * i, m.points[i].data(), 24) == 0;
  CHECK(same_bits);
  // The cells.
  CHECK(arrays.at("connectivity").type == "Int32");
  REQUIRE(arrays.at("connectivity").values.size() == 2 * m.lines.size());
  bool same_lines = true;
  for (std::size_t c = 0; c < m.lines.size(); ++c)
    same_lines = same_lines && arrays.at("connectivity").values[2 * c] == m.lines[c][0] &&
                 arrays.at("connectivity").values[2 * c + 1] == m.lines[c][1] &&
                 arrays.at("offsets").values[c] == double(2 * (c + 1)) && arrays.at("types").values[c] == vtk_line;
  CHECK(same_lines);
  // The fields: Float32, each value the double rounded to the nearest float.
  for (const auto* fields : {&m.point_data, &m.cell_data})
    for (const auto& f : *fields) {
      INFO(f.name);
      const Decoded& d = arrays.at(f.name);
      CHECK(d.type == "Float32");
      CHECK(d.components == f.components);
      REQUIRE(d.values.size() == f.values.size());
      bool rounded = true;
      for (std::size_t i = 0; i < f.values.size(); ++i) rounded = rounded && d.values[i] == double(float(f.values[i]));
      CHECK(rounded);
    }
  // The float32 option: the points rounded to floats as well.
  const auto arrays32 = decode_binary_vtu(slurp(f32));
  CHECK(arrays32.at("Points").type == "Float32");
  CHECK(arrays32.at("Points").values.at(4) == double(float(m.points[1].y())));

  // Sizes: configuration 3's frame (13 602 points, 5 938 lines, the same fields) measured 1.53 MB in
  // ASCII, 225 kB binary (6.8 times smaller) and 173 kB with Float32 points (8.9 times).
  const auto size = [](const std::string& p) { return static_cast<double>(fs::file_size(p)); };
  INFO("ASCII " << size(txt) << " B, binary " << size(bin) << " B, binary Float32 " << size(f32) << " B");
  CHECK(size(txt) / size(bin) > 5.0);
  CHECK(size(txt) / size(f32) > 7.0);
}

TEST_CASE("binary VTU: an empty mesh and a multi-block array decode", "[vtk]") {
  LineMesh empty;
  write_vtu(tmp("empty_binary.vtu"), empty);
  const auto e = decode_binary_vtu(slurp(tmp("empty_binary.vtu")));
  CHECK(e.at("Points").values.empty());
  CHECK(e.at("connectivity").values.empty());
  // 30 000 points: 720 000 bytes of Float64 points, 11 blocks of 64 KiB, the last one partial.
  LineMesh big;
  for (int i = 0; i < 30000; ++i) big.points.push_back(Eigen::Vector3d(i * 0.001, std::sqrt(double(i)), -i / 7.0));
  for (int i = 1; i < 30000; ++i) big.lines.push_back({i - 1, i});
  write_vtu(tmp("big_binary.vtu"), big);
  const auto b = decode_binary_vtu(slurp(tmp("big_binary.vtu")));
  REQUIRE(b.at("Points").values.size() == 90000);
  CHECK(b.at("Points").values[3 * 29999 + 2] == -29999 / 7.0);
  CHECK(b.at("offsets").values.back() == 2 * 29999);
}

}  // namespace vtk_tests
