#pragma once
// furniture_fem/io/vtk.hpp: ParaView output for beam models.
//
// write_vtu() writes one state of a line mesh as a VTK XML UnstructuredGrid (.vtu): points, two-node
// VTK_LINE cells, and named point/cell fields (scalars or 3-vectors). By default the data are binary,
// appended raw after the XML and zlib-compressed (vtkZLibDataCompressor, UInt64 headers), the points
// Float64 (to the bit), the fields Float32; VtuOptions::ascii() writes the text format instead.
// PvdWriter collects such files into a time series (.pvd) that ParaView opens as one animated data set.
// Both files are written to "<path>.tmp" and renamed, so a reader (or a Ctrl-C) never sees half a file.
#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <system_error>
#include <vector>
#include <zlib.h>

#include "../core/errors.hpp"

namespace furniture_fem {

inline constexpr int vtk_line = 3;  // VTK cell type of a two-node line

struct LineMesh {
  struct Field {
    std::string name;
    int components = 1;          // 1 (scalar) or 3 (vector)
    std::vector<double> values;  // components * (points or cells), interleaved x y z
  };
  std::vector<Eigen::Vector3d> points;
  std::vector<std::array<int, 2>> lines;  // point indices
  std::vector<Field> point_data, cell_data;

  LineMesh& add_point_scalar(std::string name, std::vector<double> v) {
    point_data.push_back({std::move(name), 1, std::move(v)});
    return *this;
  }
  LineMesh& add_point_vector(std::string name, const std::vector<Eigen::Vector3d>& v) {
    point_data.push_back({std::move(name), 3, flatten(v)});
    return *this;
  }
  LineMesh& add_cell_scalar(std::string name, std::vector<double> v) {
    cell_data.push_back({std::move(name), 1, std::move(v)});
    return *this;
  }
  LineMesh& add_cell_vector(std::string name, const std::vector<Eigen::Vector3d>& v) {
    cell_data.push_back({std::move(name), 3, flatten(v)});
    return *this;
  }

 private:
  static std::vector<double> flatten(const std::vector<Eigen::Vector3d>& v) {
    std::vector<double> out;
    out.reserve(v.size() * 3);
    for (const auto& p : v) out.insert(out.end(), {p.x(), p.y(), p.z()});
    return out;
  }
};

// How write_vtu() encodes the data.
struct VtuOptions {
  // true: binary, appended raw after the XML, zlib-compressed; false: ASCII text, every value written
  // with the shortest text that reads back to the same double.
  bool binary = true;
  bool float32_fields = true;   // binary: the point and cell fields as Float32 (7 significant digits)
  bool float32_points = false;  // binary: the points as Float32 too (default Float64: to the bit)
  int compression_level = 6;    // zlib, 1 (fastest) .. 9 (smallest)
  static VtuOptions ascii() {
    VtuOptions o;
    o.binary = false;
    return o;
  }
};

namespace detail::vtk {

inline std::string xml_escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

// Shortest text that reads back to the same double (std::to_chars), so values round-trip exactly.
inline void put_number(std::string& out, double v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, r.ptr);
}

// Writes via "<path>.tmp" + rename; errors name the path. A failed write or rename removes the .tmp
// file (a full disk left one behind per frame; issue 13).
inline void write_atomically(const std::string& path, const std::string& text, const char* who) {
  const std::string tmp = path + ".tmp";
  const auto fail = [&](const std::string& what) {
    std::error_code ignored;
    std::filesystem::remove(tmp, ignored);
    throw OutputError(std::string(who) + ": " + what);
  };
  {
    std::ofstream f(tmp, std::ios::binary | std::ios::trunc);
    if (!f) fail("cannot open '" + tmp + "' for writing");
    f.write(text.data(), std::streamsize(text.size()));
    f.close();
    if (!f) fail("error while writing '" + tmp + "' (disk full?)");
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) fail("cannot rename '" + tmp + "' to '" + path + "': " + ec.message());
}

inline void check_field(const LineMesh::Field& f, std::size_t count, const char* where, const std::string& path) {
  const auto bad = [&](const std::string& msg) {
    return InputError("write_vtu '" + path + "': " + where + " field '" + f.name + "': " + msg);
  };
  if (f.components != 1 && f.components != 3) throw bad("components must be 1 or 3, got " + std::to_string(f.components));
  if (f.values.size() != count * std::size_t(f.components))
    throw bad("has " + std::to_string(f.values.size()) + " values, expected " +
              std::to_string(count * std::size_t(f.components)));
  // VTK's ASCII reader cannot parse "nan"/"inf"; a non-finite value is a failed run, not output.
  for (std::size_t i = 0; i < f.values.size(); ++i)
    if (!std::isfinite(f.values[i]))
      throw bad("value " + std::to_string(i / std::size_t(f.components)) + " is not finite");
}

inline void put_fields(std::string& out, const std::vector<LineMesh::Field>& fields, const char* tag) {
  out += "      <";
  out += tag;
  // The first scalar/vector field becomes ParaView's active one.
  for (int comp : {1, 3})
    for (const auto& f : fields)
      if (f.components == comp) {
        out += comp == 1 ? " Scalars=\"" : " Vectors=\"";
        out += xml_escape(f.name) + "\"";
        break;
      }
  out += ">\n";
  for (const auto& f : fields) {
    out += "        <DataArray type=\"Float64\" Name=\"" + xml_escape(f.name) + "\" NumberOfComponents=\"" +
           std::to_string(f.components) + "\" format=\"ascii\">\n";
    for (std::size_t i = 0; i < f.values.size(); ++i) {
      out += (i % std::size_t(f.components) == 0) ? "          " : " ";
      put_number(out, f.values[i]);
      if ((i + 1) % std::size_t(f.components) == 0) out += '\n';
    }
    out += "        </DataArray>\n";
  }
  out += "      </";
  out += tag;
  out += ">\n";
}

// One appended array: its XML attributes and its compressed bytes (header, then the blocks).
struct Appended {
  std::string xml;    // the <DataArray .../> element
  std::string bytes;  // the compressed data, as VTK's vtkZLibDataCompressor lays it out
};

inline constexpr std::size_t zlib_block = 1 << 16;  // uncompressed bytes per block

// The raw little-endian bytes of `n` values converted to T.
template <class T, class Src>
std::string raw_bytes(const Src* v, std::size_t n) {
  static_assert(std::endian::native == std::endian::little, "the VTU writer assumes a little-endian machine");
  std::string out(n * sizeof(T), '\0');
  for (std::size_t i = 0; i < n; ++i) {
    const T x = static_cast<T>(v[i]);
    std::memcpy(out.data() + i * sizeof(T), &x, sizeof(T));
  }
  return out;
}

// vtkZLibDataCompressor's layout with header_type UInt64: [blocks, block size, last block's size (0: a
// full block), compressed size of each block], then the compressed blocks.
inline std::string zlib_blocks(const std::string& raw, int level, const std::string& path) {
  const std::size_t nblocks = (raw.size() + zlib_block - 1) / zlib_block;
  std::vector<std::uint64_t> header{nblocks, zlib_block, raw.size() % zlib_block};
  std::string data;
  std::vector<unsigned char> buf(compressBound(static_cast<uLong>(zlib_block)));
  for (std::size_t b = 0; b < nblocks; ++b) {
    const std::size_t at = b * zlib_block, len = std::min(zlib_block, raw.size() - at);
    uLongf out_len = static_cast<uLongf>(buf.size());
    if (compress2(buf.data(), &out_len, reinterpret_cast<const Bytef*>(raw.data() + at), static_cast<uLong>(len),
                  level) != Z_OK)
      throw OutputError("write_vtu '" + path + "': zlib could not compress the data");
    header.push_back(out_len);
    data.append(reinterpret_cast<const char*>(buf.data()), out_len);
  }
  return raw_bytes<std::uint64_t>(header.data(), header.size()) + data;
}

inline Appended appended(const std::string& name, const char* type, int components, std::string raw, int level,
                         const std::string& path) {
  Appended a;
  a.xml = "<DataArray type=\"" + std::string(type) + "\" Name=\"" + xml_escape(name) + "\"";
  if (components > 1) a.xml += " NumberOfComponents=\"" + std::to_string(components) + "\"";
  a.xml += " format=\"appended\" offset=\"";  // the offset is filled in when the arrays are laid out
  a.bytes = zlib_blocks(raw, level, path);
  return a;
}

inline Appended appended_doubles(const std::string& name, int components, const std::vector<double>& v, bool f32,
                                 int level, const std::string& path) {
  return appended(name, f32 ? "Float32" : "Float64", components,
                  f32 ? raw_bytes<float>(v.data(), v.size()) : raw_bytes<double>(v.data(), v.size()), level, path);
}

// The binary file: the XML with every array's offset into the appended data, then the data.
inline std::string binary_vtu(const LineMesh& mesh, const VtuOptions& opt, const std::string& path) {
  const std::size_t np = mesh.points.size(), nc = mesh.lines.size();
  const int level = std::clamp(opt.compression_level, 1, 9);
  std::string out;
  std::string data;
  const auto place = [&](Appended a, const std::string& indent) {
    out += indent + a.xml + std::to_string(data.size()) + "\"/>\n";
    data += a.bytes;
  };
  const auto fields = [&](const std::vector<LineMesh::Field>& list, const char* tag) {
    out += "      <";
    out += tag;
    for (int comp : {1, 3})
      for (const auto& f : list)
        if (f.components == comp) {
          out += comp == 1 ? " Scalars=\"" : " Vectors=\"";
          out += xml_escape(f.name) + "\"";
          break;
        }
    out += ">\n";
    for (const auto& f : list)
      place(appended_doubles(f.name, f.components, f.values, opt.float32_fields, level, path), "        ");
    out += "      </";
    out += tag;
    out += ">\n";
  };
  out += "<?xml version=\"1.0\"?>\n";
  out += "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\" "
         "compressor=\"vtkZLibDataCompressor\">\n";
  out += "  <UnstructuredGrid>\n";
  out += "    <Piece NumberOfPoints=\"" + std::to_string(np) + "\" NumberOfCells=\"" + std::to_string(nc) + "\">\n";
  fields(mesh.point_data, "PointData");
  fields(mesh.cell_data, "CellData");
  std::vector<double> xyz;
  xyz.reserve(3 * np);
  for (const auto& p : mesh.points) xyz.insert(xyz.end(), {p.x(), p.y(), p.z()});
  out += "      <Points>\n";
  place(appended_doubles("Points", 3, xyz, opt.float32_points, level, path), "        ");
  out += "      </Points>\n      <Cells>\n";
  std::vector<std::int32_t> conn, offsets(nc);
  std::vector<std::uint8_t> types(nc, std::uint8_t(vtk_line));
  conn.reserve(2 * nc);
  for (std::size_t c = 0; c < nc; ++c) {
    conn.insert(conn.end(), {mesh.lines[c][0], mesh.lines[c][1]});
    offsets[c] = static_cast<std::int32_t>(2 * (c + 1));
  }
  place(appended("connectivity", "Int32", 1, raw_bytes<std::int32_t>(conn.data(), conn.size()), level, path), "        ");
  place(appended("offsets", "Int32", 1, raw_bytes<std::int32_t>(offsets.data(), offsets.size()), level, path), "        ");
  place(appended("types", "UInt8", 1, raw_bytes<std::uint8_t>(types.data(), types.size()), level, path), "        ");
  out += "      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n  <AppendedData encoding=\"raw\">\n   _";
  out += data;
  out += "\n  </AppendedData>\n</VTKFile>\n";
  return out;
}

}  // namespace detail::vtk

// Writes `mesh` as a .vtu file. Throws InputError for an inconsistent mesh (bad index,
// field of the wrong length, non-finite value) and OutputError if the file cannot be written.
inline void write_vtu(const std::string& path, const LineMesh& mesh, const VtuOptions& opt = {}) {
  const std::size_t np = mesh.points.size(), nc = mesh.lines.size();
  for (std::size_t i = 0; i < np; ++i)
    if (!mesh.points[i].allFinite())
      throw InputError("write_vtu '" + path + "': point " + std::to_string(i) + " is not finite");
  for (std::size_t c = 0; c < nc; ++c)
    for (int k : mesh.lines[c])
      if (k < 0 || std::size_t(k) >= np)
        throw InputError("write_vtu '" + path + "': line " + std::to_string(c) + " uses point " +
                                    std::to_string(k) + " of " + std::to_string(np));
  for (const auto& f : mesh.point_data) detail::vtk::check_field(f, np, "point", path);
  for (const auto& f : mesh.cell_data) detail::vtk::check_field(f, nc, "cell", path);
  if (np > std::size_t(INT32_MAX) || 2 * nc > std::size_t(INT32_MAX))
    throw InputError("write_vtu '" + path + "': more than 2^31 points or line ends");
  if (opt.binary) {
    detail::vtk::write_atomically(path, detail::vtk::binary_vtu(mesh, opt, path), "write_vtu");
    return;
  }

  std::string out;
  out.reserve(64 * (np + nc) + 1024);
  out += "<?xml version=\"1.0\"?>\n";
  out += "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n";
  out += "  <UnstructuredGrid>\n";
  out += "    <Piece NumberOfPoints=\"" + std::to_string(np) + "\" NumberOfCells=\"" + std::to_string(nc) + "\">\n";
  detail::vtk::put_fields(out, mesh.point_data, "PointData");
  detail::vtk::put_fields(out, mesh.cell_data, "CellData");
  out += "      <Points>\n        <DataArray type=\"Float64\" Name=\"Points\" NumberOfComponents=\"3\" format=\"ascii\">\n";
  for (const auto& p : mesh.points) {
    out += "          ";
    for (int k = 0; k < 3; ++k) {
      if (k) out += ' ';
      detail::vtk::put_number(out, p[k]);
    }
    out += '\n';
  }
  out += "        </DataArray>\n      </Points>\n      <Cells>\n";
  out += "        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
  for (const auto& l : mesh.lines) out += "          " + std::to_string(l[0]) + " " + std::to_string(l[1]) + "\n";
  out += "        </DataArray>\n        <DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
  for (std::size_t c = 0; c < nc; ++c) out += "          " + std::to_string(2 * (c + 1)) + "\n";
  out += "        </DataArray>\n        <DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
  for (std::size_t c = 0; c < nc; ++c) out += "          " + std::to_string(vtk_line) + "\n";
  out += "        </DataArray>\n      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n";
  detail::vtk::write_atomically(path, out, "write_vtu");
}

// A .pvd time series. Call write() after each add() to keep the collection on disk up to date while
// a long run is still going. Relative file names are written as given (ParaView resolves them
// against the .pvd's folder); absolute ones are made relative to that folder when possible.
class PvdWriter {
 public:
  explicit PvdWriter(std::string path) : path_(std::move(path)) {}

  // Times must increase strictly: a repeated or decreasing time is an output bug.
  PvdWriter& add(double time, const std::string& file) {
    if (!std::isfinite(time) || (!entries_.empty() && !(time > entries_.back().time)))
      throw InputError("PvdWriter '" + path_ + "': time " + std::to_string(time) + " for '" + file +
                                  "' does not follow " + (entries_.empty() ? "" : std::to_string(entries_.back().time)));
    std::filesystem::path f(file);
    if (f.is_absolute()) {
      const auto dir = std::filesystem::absolute(std::filesystem::path(path_)).parent_path();
      const auto rel = f.lexically_proximate(dir);
      if (!rel.empty()) f = rel;
    }
    entries_.push_back({time, f.generic_string()});
    return *this;
  }

  void write() const {
    std::string out = "<?xml version=\"1.0\"?>\n";
    out += "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n  <Collection>\n";
    for (const auto& e : entries_) {
      out += "    <DataSet timestep=\"";
      detail::vtk::put_number(out, e.time);
      out += "\" group=\"\" part=\"0\" file=\"" + detail::vtk::xml_escape(e.file) + "\"/>\n";
    }
    out += "  </Collection>\n</VTKFile>\n";
    detail::vtk::write_atomically(path_, out, "PvdWriter");
  }

  std::size_t size() const { return entries_.size(); }
  const std::string& path() const { return path_; }

  // The frames listed so far, for a checkpoint (core/checkpoint.hpp).
  template <class Self, class Archive>
    requires std::is_same_v<std::remove_const_t<Self>, PvdWriter>
  friend void transfer_state(Self& p, Archive& ar) {
    ar(p.entries_);
  }

 private:
  struct Entry {
    double time;
    std::string file;
    template <class Self, class Archive>
      requires std::is_same_v<std::remove_const_t<Self>, Entry>
    friend void transfer_state(Self& e, Archive& ar) {
      ar(e.time, e.file);
    }
  };
  std::string path_;
  std::vector<Entry> entries_;
};

}  // namespace furniture_fem
