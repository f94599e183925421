// libFuzzer harness for the triangle-mesh readers (contact/cgal_adapter.hpp): the first byte picks OFF,
// OBJ or STL (ASCII or binary: read_stl decides), the rest is the file. A mesh read must have valid
// indices and finite vertices and build a MeshObstacle (CGAL AABB tree) or give an InputError.
#include <cmath>
#include <cstdint>
#include <string>

#include <furniture_fem/contact/cgal_adapter.hpp>

#include "fuzz_common.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace furniture_fem;
  if (size < 1 || size > (1u << 20)) return 0;
  static const char* const ext[3] = {"off", "obj", "stl"};
  const int format = data[0] % 3;
  const std::string bytes(reinterpret_cast<const char*>(data) + 1, size - 1);
  const std::string path = ffem_fuzz::write_input(std::string("mesh.") + ext[format], data + 1, size - 1);
  try {
    // The path entry (read_triangle_mesh) reads the file and dispatches on its extension.
    const TriangleMesh m = read_triangle_mesh(path);
    const TriangleMesh direct = format == 0   ? detail::read_off(path, bytes)
                                : format == 1 ? detail::read_obj(path, bytes)
                                              : detail::read_stl(path, bytes);
    ffem_fuzz::check(direct.vertices == m.vertices && direct.triangles == m.triangles,
                     "read_triangle_mesh and the format's reader differ");
    ffem_fuzz::check(!m.triangles.empty(), "a mesh without triangles was accepted");
    for (const auto& v : m.vertices) ffem_fuzz::check(v.allFinite(), "a vertex is not finite");
    for (const auto& t : m.triangles)
      for (int i : t)
        ffem_fuzz::check(i >= 0 && i < static_cast<int>(m.vertices.size()), "a triangle index is out of range");
    if (m.triangles.size() <= 20000) {  // the tree of a huge mesh is slow, not wrong
      const MeshObstacle obstacle(m, path);
      const MeshClosestPoint c = obstacle.closest(Vec3(0.1, 0.2, 0.3));
      ffem_fuzz::check(c.triangle >= 0 && c.triangle < static_cast<int>(m.triangles.size()),
                       "closest() named a triangle that does not exist");
    }
  } catch (const InputError&) {  // includes ModelError (no triangle of non-zero area)
  }
  return 0;
}
