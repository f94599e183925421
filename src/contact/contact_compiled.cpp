// furniture_fem::contact_compiled: the contact module's calls into CGAL (the broad phase's box
// intersection, the mesh obstacles' AABB tree, the convex hull of a rigid body's support points;
// contact/detail/cgal_adapter_impl.hpp) compiled once. A program that links this library gets
// FURNITURE_FEM_COMPILED_CONTACT from it and parses no CGAL header (docs/performance.md section 6).
#define FURNITURE_FEM_BUILDING_CONTACT_LIBRARY
#include <furniture_fem/contact/cgal_adapter.hpp>
