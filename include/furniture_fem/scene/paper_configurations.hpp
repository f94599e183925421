#pragma once
// furniture_fem/scene/paper_configurations.hpp: configuration(k), the paper's three arrangements as scenes.
#include <optional>
#include <string>

#include "../core/errors.hpp"
#include "../excitation/known_records.hpp"
#include "../furniture/furniture.hpp"
#include "laws/law_list.hpp"
#include "spec.hpp"

namespace furniture_fem {

// ---------------------------------------------------------------------------------------------------
// The paper's configurations (section 3; Figure 7's drawings are not available: docs/furniture/furniture.md
// gives the coordinates chosen and why)
// ---------------------------------------------------------------------------------------------------

// Configuration k = 1, 2 or 3 on the 4 m x 4 m table with walls at x = -2 and x = +2, excited by the
// JMA-Kobe record (PEER RSN1106: NS along X) at 100 %, 1-D, low-passed at 10 Hz, over record time
// 4-16 s. `records_dir` is where the AT2 files are (relative paths: relative to the working folder; by
// default $FFEM_RECORDS, else ../shared/ground_motions: excitation/known_records.hpp).
inline SceneSpec configuration(int k, const std::string& records_dir = default_records_dir()) {
  if (k < 1 || k > 3)
    throw InputError("configuration", 0, "k", "the paper has configurations 1, 2 and 3 (got " + std::to_string(k) + ")");
  SceneSpec s;
  s.name = "configuration " + std::to_string(k);
  s.source = s.name;
  // Cabinets: backs 30 mm from the wall at x = +2, fronts towards -X (yaw -90 deg puts the item's
  // front, -y, on -X and its width along -Y).
  const double wall_gap = 0.03, cabinet_x = 2.0 - wall_gap - 0.5 * paper_item(PaperItem::tall_cabinet).D;
  const ItemSpec tall{"tall_cabinet", ItemKind::tall_cabinet, cabinet_x, -0.5, -90.0, Fidelity::full, {}};
  const ItemSpec pair{"separated_cabinets", ItemKind::separated_cabinets, cabinet_x, 0.5, -90.0, Fidelity::full, {}};
  // Centre group: desk with its depth along X, front towards the chair on the -X side; side table
  // with its casters (longer edge) along X. Gaps exceed the heights of the items that could fall
  // into them (configuration 2's clearances).
  const ItemSpec desk{"desk", ItemKind::desk, 0.6, 0.0, -90.0, Fidelity::full, {}};
  const ItemSpec side{"side_table", ItemKind::side_table, 0.6, -1.45, 0.0, Fidelity::full, {}};
  const ItemSpec chair{"office_chair", ItemKind::office_chair, -0.82, 0.0, 90.0, Fidelity::full, {}};
  if (k == 1 || k == 3) s.items = {tall, pair};
  if (k == 2 || k == 3) s.items.insert(s.items.end(), {side, desk, chair});

  auto& g = s.ground_motion;
  g.source = MotionSource::file;
  g.format = RecordFormat::at2;
  const std::string dir = records_dir.empty() || records_dir.back() == '/' ? records_dir : records_dir + "/";
  g.file_x = dir + "jma_kobe_1995_NS_PEER_RSN1106_KJM000.AT2";
  g.file_y = dir + "jma_kobe_1995_EW_PEER_RSN1106_KJM090.AT2";
  g.file_z = dir + "jma_kobe_1995_UD_PEER_RSN1106_KJM-UP.AT2";
  g.level = 1.0;
  g.dimensions = MotionDimensions::one_d;
  g.lowpass_hz = 10.0;
  g.window_start = 4.0;
  g.window_end = 16.0;
  s.duration = 12.0;
  s.dt = 1e-3;
  s.contact.law = law_kind<PaperAnisotropicSceneLaw>;
  s.contact.plane_contact_at = PlaneContactAt::centre_lines;  // the paper's code: contact at the nodes
  // The paper's explicit contact for its FE items (the scene default, `all`, puts them inside the step):
  // the reproduction's documented switch (paper/README.md), and the paper's rigid pairs by members.
  s.contact.implicit = ImplicitContact::rigid;
  s.contact.rigid_pairs = RigidPairContact::members;
  s.integrator = {IntegratorKind::paper_newmark, 0.5, false, 1};  // no impact sub-steps: the paper's code
  s.integrator.frame_drift_refresh = 0;  // no refresh on a member's frame drift: the paper's code
  s.solver = SolverKind::direct;
  s.outputs.folder = "out/configuration_" + std::to_string(k);
  s.outputs.vtu_every = 100;
  const auto marker = [](const std::string& item, const std::string& name) {
    return MarkerRequest{item + "." + name, item, name, std::nullopt};
  };
  // The paper's evaluation points (Figures 16-18): the upper separated cabinet, the desk, the chair.
  if (k == 1 || k == 3) s.outputs.markers.push_back(marker("separated_cabinets/upper", "top_front_centre"));
  if (k == 1) s.outputs.markers.push_back(marker("tall_cabinet", "top_front_centre"));
  if (k == 2 || k == 3) {
    s.outputs.markers.push_back(marker("desk", "top_back_centre"));
    s.outputs.markers.push_back(marker("office_chair", "seat_centre"));
    // Figure 19: shear in the top board element next to the desk's evaluation point, on the edge
    // the falling tall cabinet strikes (the desk's back, facing the cabinets).
    Model scratch;
    const ItemInfo built = build_desk(scratch);
    const auto [member, element] = element_near(scratch, built, built.marker("top_back_centre")->local_point);
    s.outputs.sectional_forces.push_back({"desk", member, element});
  }
  return s;
}


}  // namespace furniture_fem
