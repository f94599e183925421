#pragma once
// furniture_fem/scene/run_summary.hpp: what a run is asked to do and what it reports.
//
//   RunOptions       how to run a scene (folder, duration, history interval, stop flag, trust limits)
//   RunSummary       how it went: status, times, counts, energy ledger, final states, section peaks
//
// Plain data, apart from the simulation and the contact (observer.hpp has the observers' interface):
// a program that only runs scenes (scene/run_scene.hpp) compiles these and not the solver.
#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <atomic>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "../core/model.hpp"
#include "../harm/strike.hpp"
#include "../io/vtk.hpp"

namespace furniture_fem {

inline constexpr const char* version_string = "0.1.0";

struct RunOptions {
  std::string out_dir;                        // empty: the scene's outputs.folder
  // A non-empty results folder that no run of this program wrote, or whose run.json says a run is still
  // running, is refused (InputError); true: remove the old results in it (only the files a run writes,
  // results_folder.hpp) and write. A folder a run wrote is always cleared of its old results first.
  bool overwrite = false;
  std::string git_hash;                       // written to run.json; empty: unknown (null)
  bool write_files = true;                    // false: no folder, no files, no figures; the summary only
  bool progress = true;                       // progress bar on stderr
  // The run's steps before the first and its projected wall time after a second of stepping, on
  // stderr; without the progress bar only for a run projected past a minute (detail::RunForecast).
  bool forecast = true;
  // Threads over the bodies of this run; 0: every hardware thread. A study running one realisation
  // per worker sets 1 (results are the same to the bit with any number).
  int threads = 0;
  std::optional<double> duration;             // overrides the scene's duration (s)
  // How errors about `duration` name it (file and key of InputError): a program sets its option's name.
  std::string duration_source = "RunOptions", duration_key = "duration (run option)";
  // History rows (CSV, figures, energy checks) every output_interval s of simulated time, rounded to
  // whole steps as SceneSpec::refresh_interval_steps() rounds refresh_every (0.01 s: every 10 steps
  // at dt = 1 ms). See RunView::row_interval_steps.
  double output_interval = 0.01;
  const std::atomic<bool>* stop = nullptr;    // set by a signal handler to stop cleanly
  std::optional<bool> figures;                // overrides outputs.figures
  // Checkpoints (docs/io/output.md, "Checkpoints"): every this many seconds of wall time the run writes
  // its whole state to checkpoint.bin in the results folder (atomically); 0: only when stopped (a stop
  // request writes one before the run ends). A run that completes or diverges removes it.
  double checkpoint_every = 0;
  // Go on with the run whose checkpoint is in the results folder (stopped or killed): the same scene and
  // options (checked), its files cut back to the checkpoint and continued; the results are those of the
  // run that was never stopped, to the bit.
  bool resume = false;
  // A run that creates energy cannot be trusted: it ends as "diverged", with a diagnosis, as soon as
  // the contact forces' net work or the ledger's imbalance exceeds this fraction of the ledger's scale
  // (the contact laws only store and dissipate energy, the integrators only dissipate; checked at
  // every output row). 0: never. See energy_creation_diagnosis().
  double energy_creation_limit = 0.25;
  // A run that completes having lost more than this fraction of the ledger's scale (impacts with the
  // carried-over penalty contact, or a time step too long for the penalty) is kept, but its summary's
  // diagnosis warns that the energy ledger does not close. See energy_loss_warning().
  double energy_loss_warning = 0.15;
  // The energy ledger's verdict (RunSummary::energy): it closes when |imbalance| <= this fraction of its
  // scale at the end of the run.
  double energy_tolerance = 0.05;
  VtuOptions vtu;                             // how the VTU frames are written (binary, compressed)
};

// Whether the energy ledger closes at the end of the run (summary.json "energy_verdict"), and if not,
// when the imbalance grew most and which term moved most meanwhile.
struct EnergyVerdict {
  bool closes = true;
  double tolerance = 0;       // RunOptions::energy_tolerance
  double imbalance = 0;       // J, at the end (the ledger's: lost < 0 < created)
  double relative = 0;        // imbalance / scale
  double scale = 0;           // J
  // The history-row interval in which the imbalance changed most, by how much, and the ledger term
  // that changed most in it (kinetic, strain, gravity_potential, external_work, contact_work,
  // damping_work, plastic_work) and by how much (J).
  double t_from = 0, t_to = 0, imbalance_step = 0;
  std::string term;
  double term_step = 0;
  std::string text;           // one sentence: "closes: ..." or "does not close: ..."
};

// The thresholds of an item's final state (ItemFinalState, scene/observers.hpp) and of a study's damage
// state "fallen" (study/report.hpp): one definition for both.
inline constexpr double overturned_tilt_deg = 60;  // lying: its vertical axis tilted past this
inline constexpr double fell_drop_m = 0.05;         // came down: its lowest node this far below its start
// Off its feet at some time in the run: tipped past overturned_tilt_deg, or came down more than
// fell_drop_m (off the item it stood on), whatever it rests on at the end.
inline bool has_fallen(double max_tilt_deg, double lift) {
  return max_tilt_deg > overturned_tilt_deg || lift < -fell_drop_m;
}

struct ItemFinalState {
  std::string name;
  std::string state;          // standing, slid, tilted, fell, overturned, resting_on_item, diverged
                              // (fell: upright again at the end, but it tipped past 60 degrees or came
                              // down more than 5 cm on the way, e.g. off the item it stood on; diverged:
                              // the run diverged, the numbers are those of its last finite step)
  double slide = 0;           // horizontal displacement of the centre of gravity since t = 0 (m)
  double tilt_deg = 0;        // angle of the item's vertical axis from the vertical
  double max_tilt_deg = 0;    // during the run
  double lift = 0;            // height of the lowest node above the floor contact onset (m)
  std::string resting_on;     // the item it leans or rests on, if any
  Vec3 cog_displacement = Vec3::Zero();  // of its centre of gravity (every mass it carries) since t = 0 (m)
  double max_node_speed = 0;  // the largest speed of any of its nodes at the end, relative to the table (m/s)
};

// The extremes of one requested sectional force over every step of the run (N, N m; times in s).
// Components in the order N, Qy, Qz, Mx, My, Mz.
struct SectionForcePeak {
  std::string section;  // item:member#element
  std::array<double, 6> min, max, t_min, t_max;
};

// A settled start (contact.start "settled"): the simulated time the items took to settle before t = 0,
// and the largest nodal speed they were left with.
struct SettledStart {
  double settling_time = 0;  // s
  double max_node_speed = 0;  // m/s, at the end of the settling
  // Whether every node was quiet for the quiet time before the cap (scene/runner.hpp, settle_at_rest); if
  // not, the item whose node was fastest at the end (a room whose light members ring, a rocking item).
  bool settled = true;
  std::string fastest_item;
  // A stop request (Ctrl-C) ended the settling: the run does not start (it stops at t = 0 with no
  // checkpoint: a resume would start from a state that had not settled).
  bool interrupted = false;
};

// What a restraint did over the run (scene/restraint_observers.hpp; docs/restraints/restraints.md).
struct RestraintOutcome {
  std::string name, kind, item;
  double peak_force = 0;   // N: the largest force it carried (its kind's measure: restraints.csv's _force)
  double strength = 0;     // N: the strength its failure is judged by (bracket pull-out, strap tension,
                           // mat peel, pole: the lower of its lock's and the board's)
  double peak_ratio = 0;   // peak_force / strength
  bool broke = false;
  double broke_at = -1;    // s
  std::string failure;     // none, pull_out, shear, tension, peel, uplift, punch_through
  double dissipated = 0;   // J: yielding, slipping, breaking
  double stored = 0;       // J: elastic energy it holds at the end
};

// What the items did to an occupant (scene/occupant_observers.hpp; docs/harm/occupants.md).
struct OccupantOutcome {
  std::string name;
  std::vector<Strike> strikes;         // by onset time
  std::vector<std::string> in_contact_at_end;  // the items in one of its zones at the end (leaning on, lying on)
  bool seriously_struck() const {
    return std::any_of(strikes.begin(), strikes.end(), [](const Strike& s) { return s.serious(); });
  }
};

// An exit's narrowest cross-section at one time (scene/exit_observers.hpp; docs/harm/harm.md, "Exits").
struct ExitSection {
  double t = 0;            // s
  double clear_width = 0;  // m: the widest free interval of the section
  double s = 0;            // m: the station's arc length along the path
  double x = 0, y = 0;     // m: the station
  std::vector<std::string> by;  // the items that narrow it (none: walls, the table's edge, the reach)
  template <class Self, class Archive>
    requires std::is_same_v<std::remove_const_t<Self>, ExitSection>
  friend void transfer_state(Self& e, Archive& ar) {
    ar(e.t, e.clear_width, e.s, e.x, e.y, e.by);
  }
};

// What an exit's clear width did over the run, measured at the history rows and at the end.
struct ExitOutcome {
  std::string name;
  double required_width = 0;                 // m
  bool blocked = false;                      // at the end: its clear width below required_width
  std::optional<ExitSection> first_blocked;  // the first row it was below required_width
  ExitSection narrowest;                     // the narrowest over the run (the first of equals)
  ExitSection at_end;
};

struct RunSummary {
  std::string status = "completed";  // completed, stopped, diverged
  std::string diagnosis;             // why it stopped; for a completed run, empty or an energy-loss warning
  // t_end: the time reached (s); of a diverged run, its last finite step, the one final states are of.
  double t_end = 0, duration = 0;
  std::optional<double> t_diverged;  // a diverged run: the end of the step that diverged (s)
  long steps = 0;
  double wall_seconds = 0;
  double energy_imbalance = 0;        // |imbalance| / scale of the ledger at the end
  double max_energy_imbalance = 0;    // the largest during the run (at the history rows)
  long factorizations = 0;
  // The largest change of a contact term, relative to the term, that a reused factorisation left out of
  // a solve (Simulation::factor_reuse_error; at most 0.3, a change of contact regime never): 0 when
  // every flexible body was refactorised at every step or had no contact.
  double factor_reuse_error = 0;
  // Refactorisations because a member's frame drifted from its body's rotation, and the largest drift
  // (rad) a reused factorisation solved with (integrator.frame_drift_refresh; both 0 when it is 0).
  long drift_refreshes = 0;
  double max_frame_drift = 0;
  // Steps divided into sub-steps for an impact, and how many sub-steps they took in all
  // (integrator.impact_substeps).
  long impact_steps = 0, impact_substeps = 0;
  int elements = 0, nodes = 0, bodies = 0;
  std::vector<ItemFinalState> items;
  std::vector<SectionForcePeak> section_peaks;  // one per outputs.sectional_forces request
  std::vector<RestraintOutcome> restraints;     // one per restraint, in the scene's order
  std::vector<OccupantOutcome> occupants;       // one per occupant, in the scene's order
  std::vector<ExitOutcome> exits;               // one per exit, in the scene's order
  // With exits: the area of the union of the plan outlines of the items that fell or overturned (m^2).
  std::optional<double> floor_covered_by_fallen_items;
  EnergyVerdict energy;                         // the energy ledger's verdict
  std::string out_dir;  // empty when the run wrote no files (write_files false, or stopped before it was built)
  // The factor ground_motion.scale_to applied to the record (1 without a target); `level` multiplies after.
  double ground_motion_scale = 1.0;
  std::optional<SettledStart> settled_start;  // contact.start "settled": how the items settled
};

}  // namespace furniture_fem
