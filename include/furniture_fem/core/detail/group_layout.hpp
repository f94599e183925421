#pragma once
// furniture_fem/core/detail/group_layout.hpp: the nodes of a flexible group's joint system and its kept
// factorisation (Simulation::solve_flexible_group; docs/contact/implicit_contact.md, "Flexible groups").
//
//   GroupLayout      the group's members and its pair nodes, member by member (slots of the system)
//   GroupFactor      the layout the group's system I + D G was last factorised on, the matrix and its LU
//                    (kept for the next steps' GMRES while the layout is the same; in checkpoints)
#ifndef FURNITURE_FEM_CORE_INTERNAL
#error "furniture_fem/core/detail/group_layout.hpp is internal: include <furniture_fem/core/simulation.hpp>"
#endif
#include <Eigen/Dense>
#include <algorithm>
#include <type_traits>
#include <vector>

#include "lu_kernels.hpp"

namespace furniture_fem::detail {

struct GroupLayout {
  std::vector<int> members;              // body ids, ascending
  std::vector<int> nodes;                // global node ids; a member's are consecutive
  std::vector<int> first;                // member i's slots are [first[i], first[i + 1])
  std::vector<std::vector<int>> locals;  // member i's nodes, as its local indices, in slot order
};

struct GroupFactor {
  GroupLayout layout;
  Eigen::MatrixXd matrix;  // I + D G as factorised: a checkpoint restores the LU from it, to the bit
  DenseLu lu;
  bool empty() const { return layout.nodes.empty(); }
  // In checkpoints the layout and the matrix; the loading simulation factorises it again (the same LU).
  template <class Self, class Archive>
    requires std::is_same_v<std::remove_const_t<Self>, GroupFactor>
  friend void transfer_state(Self& f, Archive& ar) {
    ar(f.layout.members, f.layout.nodes, f.layout.first, f.layout.locals, f.matrix);
    if constexpr (!Archive::saving)
      if (f.matrix.size() > 0) factorize_lu(f.lu, f.matrix);
  }
};

}  // namespace furniture_fem::detail
