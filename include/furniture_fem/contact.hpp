#pragma once
// furniture_fem/contact.hpp: the contact module (docs/contact.md).
//
//   geometry     closest points: segment-segment, node-plane, node-rectangle, segment-triangle
//                (contact/contact_geometry.hpp; light)
//   laws         ContactLaw<Normal, Damping, Friction>, the presets PaperLaw, PaperAnisotropicFloorLaw,
//                SpringDashpotLaw, HuntCrossleyLaw, StickSlipLaw, ContactParams, ContactState, and
//                the pair-level helpers evaluate_segment_pair / evaluate_node_plane /
//                evaluate_node_rectangle (contact/contact_laws.hpp; light)
//   CGAL         BroadPhase over ElementBox, MeshObstacle with an AABB tree, read_triangle_mesh for
//                OFF/OBJ/STL (contact/cgal_adapter.hpp; heavy: include contact/contact_laws.hpp alone in
//                translation units that need only the laws)
//
//   kernel       ContactLawKernel, make_contact_law_kernel: a law behind one run-time interface
//                (contact/contact_law_kernel.hpp; light)
//   room         RoomContact: every body against floor, walls, obstacles and each other, for a Simulation,
//                one type for every law (contact/room_contact.hpp)
#include "contact/contact_geometry.hpp"
#include "contact/contact_laws.hpp"
#include "contact/contact_law_kernel.hpp"
#include "contact/cgal_adapter.hpp"
#include "contact/room_contact.hpp"
