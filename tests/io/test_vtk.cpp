// VTU and PVD writers, read back with a minimal XML scan.
#include <catch2/catch.hpp>

#include <sys/resource.h>

#include <cmath>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "furniture_fem/io/vtk.hpp"
#include "../support/test_files.hpp"

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
  write_vtu(path, m);
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
