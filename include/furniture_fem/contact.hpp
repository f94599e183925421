#pragma once
// furniture_fem/contact.hpp: the contact module (FORMULATION section 5).
//
//   geometry     closest points: segment-segment, node-plane, node-rectangle, segment-triangle
//                (detail/contact_geometry.hpp; light)
//   laws         ContactLaw<Normal, Damping, Friction>, the presets PaperLaw, PaperAnisotropicFloorLaw,
//                SpringDashpotLaw, HuntCrossleyLaw, StickSlipLaw, ContactParams, ContactState, and
//                the pair-level helpers evaluate_segment_pair / evaluate_node_plane /
//                evaluate_node_rectangle (contact_laws.hpp; light)
//   CGAL         BroadPhase over ElementBox, MeshObstacle with an AABB tree, read_triangle_mesh for
//                OFF/OBJ/STL (detail/cgal_adapter.hpp; heavy: include contact_laws.hpp alone in
//                translation units that need only the laws)
//
// Documentation: docs/contact.md.
#include "contact_laws.hpp"
#include "detail/cgal_adapter.hpp"
#include "detail/contact_geometry.hpp"
