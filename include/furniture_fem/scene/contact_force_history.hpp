#pragma once
// furniture_fem/scene/contact_force_history.hpp: the run's observer of the contact forces between its
// bodies and the floor, the walls, the obstacles and each other (contact_forces.csv, and above 100
// bodies contact_pairs.csv: OutputSpec::contact_pairs). One of the built-in observers of observers.hpp.
#include <Eigen/Core>
#include <algorithm>
#include <cstddef>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "../io/csv.hpp"
#include "observer.hpp"

namespace furniture_fem {

// contact_forces.csv: t, then three columns per pair of contact partners, named by the item and the
// partner: "<item>|floor_fx", "<item>|walls_fx" (every wall together), "<item>|obstacles_fx" (every
// mesh obstacle together; only when the scene has obstacles), "<item>|ceiling_fx" (only when the scene
// has a ceiling), "<item>|<occupant>_head_fx" and "_body_fx" (a person standing as an obstacle) and
// "<item>|<other item>_fx" for every
// pair of items (the item first in the scene's order first), _fy, _fz likewise: the force on the first
// from the second (N), 0 when they do not touch. Each is its mean over the steps since the previous
// row: a penalty contact at rest chatters from one step to the next, and single steps sampled one
// phase of it (a cabinet at rest showed -75 N from the floor). The first row is the initial state's.
class ContactForceHistory : public RunObserver {
 public:
  // The column prefix of every pair the contact model can report in contact_forces.csv, in the order of
  // the columns; pairs of items only when the scene's outputs put them in columns (OutputSpec::pair_columns).
  static std::vector<std::pair<std::pair<int, int>, std::string>> pairs(const RunView& run) {
    std::vector<std::pair<std::pair<int, int>, std::string>> out;
    const int nb = run.model.num_bodies();
    const auto name = [&](int b) { return run.model.body(b).name; };
    for (int a = 0; a < nb; ++a) out.push_back({{a, PairForce::floor_id}, name(a) + "|floor"});
    for (int a = 0; a < nb; ++a) out.push_back({{a, PairForce::wall_id}, name(a) + "|walls"});
    if (!run.spec.obstacles.empty())
      for (int a = 0; a < nb; ++a) out.push_back({{a, PairForce::obstacle_id}, name(a) + "|obstacles"});
    if (run.spec.ceiling)
      for (int a = 0; a < nb; ++a) out.push_back({{a, PairForce::ceiling_id}, name(a) + "|ceiling"});
    for (std::size_t j = 0; j < run.spec.occupants.size(); ++j)
      if (run.spec.occupants[j].obstacle)
        for (OccupantZone z : {OccupantZone::head, OccupantZone::body})
          for (int a = 0; a < nb; ++a)
            out.push_back({{a, PairForce::capsule_id(occupant_capsule(static_cast<int>(j), z))},
                           name(a) + "|" + run.spec.occupants[j].name + "_" + std::string(to_string(z))});
    if (run.spec.outputs.pair_columns(nb))
      for (int a = 0; a < nb; ++a)
        for (int b = a + 1; b < nb; ++b) out.push_back({{a, b}, name(a) + "|" + name(b)});
    return out;
  }
  void begin(const RunView& run) override {
    pair_rows_ = item_pairs_as_rows(run);
    const std::vector<std::string> cols = columns(run);
    row_.assign(cols.size(), 0.0);
    csv_.emplace(path(run), cols);
    if (pair_rows_) pair_csv_.emplace(pair_path(run), pair_columns());
    for (const auto& pf : run.sim.pair_forces()) add(pf.body_a, pf.body_b, pf.force_on_a);
    steps_ = 1;
    write(run, run.sim.time());
  }
  void after_step(const RunView& run, const StepInfo&) override {
    ++steps_;
    for (const auto& pf : run.sim.pair_forces()) add(pf.body_a, pf.body_b, pf.force_on_a);
    if (run.row_due()) write(run, run.sim.time());
  }
  void end(const RunView&, RunSummary&) override {
    csv_->flush();
    if (pair_csv_) pair_csv_->flush();
  }
  void save(StateWriter& w) override {
    w(csv_->position(), row_, steps_);
    if (pair_csv_) w(pair_csv_->position(), pair_sums_);
  }
  void resume(const RunView& run, StateReader& r) override {
    pair_rows_ = item_pairs_as_rows(run);
    CsvWriter::Position at;
    r(at, row_, steps_);
    csv_.emplace(path(run), columns(run), at);
    if (pair_rows_) {
      r(at, pair_sums_);
      pair_csv_.emplace(pair_path(run), pair_columns(), at);
    }
  }

 private:
  static std::string path(const RunView& run) { return run.out_dir + "/contact_forces.csv"; }
  static std::string pair_path(const RunView& run) { return run.out_dir + "/contact_pairs.csv"; }
  static std::vector<std::string> pair_columns() { return {"t", "item_a", "item_b", "fx", "fy", "fz"}; }
  // The header, and each pair's first column in column_.
  std::vector<std::string> columns(const RunView& run) {
    std::vector<std::string> cols{"t"};
    column_.clear();
    for (const auto& [pair, prefix] : pairs(run)) {
      column_.emplace(pair, cols.size());
      for (const char* c : {"_fx", "_fy", "_fz"}) cols.push_back(prefix + c);
    }
    return cols;
  }
  static bool item_pairs_as_rows(const RunView& run) {
    return !run.spec.outputs.pair_columns(run.model.num_bodies());
  }
  std::optional<CsvWriter> csv_, pair_csv_;
  std::map<std::pair<int, int>, std::size_t> column_;  // the pair's _fx column
  std::vector<double> row_;                            // the force sums since the previous row
  bool pair_rows_ = false;                             // item pairs in contact_pairs.csv
  std::map<std::pair<int, int>, Vec3> pair_sums_;      // there: the touching pairs' sums since the previous row
  int steps_ = 0;

  void add(int a, int b, const Vec3& f_on_a) {
    Vec3 f = f_on_a;
    if (a >= 0 && b >= 0 && b < a) std::swap(a, b), f = -f;
    if (pair_rows_ && b >= 0) {
      pair_sums_.try_emplace({a, b}, Vec3::Zero()).first->second += f;
      return;
    }
    const auto it = column_.find({a, b});
    if (it == column_.end())
      throw std::logic_error("contact_forces.csv: a contact between bodies " + std::to_string(a) + " and " +
                             std::to_string(b) + " has no column");
    for (int c = 0; c < 3; ++c) row_[it->second + c] += f[c];
  }
  void write(const RunView& run, double t) {
    for (std::size_t i = 1; i < row_.size(); ++i) row_[i] /= steps_;
    row_[0] = t;
    csv_->row(row_);
    std::fill(row_.begin(), row_.end(), 0.0);
    for (const auto& [pair, sum] : pair_sums_) {
      if (sum.isZero(0.0)) continue;
      const Vec3 mean = sum / steps_;
      const std::string_view a = run.model.body(pair.first).name, b = run.model.body(pair.second).name;
      pair_csv_->cells_row({t, a, b, mean.x(), mean.y(), mean.z()});
    }
    pair_sums_.clear();
    steps_ = 0;
  }
};

}  // namespace furniture_fem
