#pragma once
// furniture_fem/scene/row_history.hpp: the base of the run's CSV histories (observers.hpp,
// restraint_observers.hpp): a file with a row at each history row, cut back and continued on resume.
#include <optional>
#include <string>
#include <vector>

#include "../io/csv.hpp"
#include "observer.hpp"

namespace furniture_fem {

// A CSV history written at the history rows: derived observers give the columns and each row.
class RowHistory : public RunObserver {
 public:
  void begin(const RunView& run) override {
    csv_.emplace(run.out_dir + "/" + file(), columns(run));
    write_row(run);
  }
  void after_step(const RunView& run, const StepInfo&) override {
    if (run.row_due()) write_row(run);
  }
  void end(const RunView&, RunSummary&) override { csv_->flush(); }
  void save(StateWriter& w) override {
    w(csv_->position());
    save_rows(w);
  }
  void resume(const RunView& run, StateReader& r) override {
    CsvWriter::Position at;
    r(at);
    csv_.emplace(run.out_dir + "/" + file(), columns(run), at);
    resume_rows(r);
  }

 protected:
  // What a history keeps from row to row, for a checkpoint.
  virtual void save_rows(StateWriter&) {}
  virtual void resume_rows(StateReader&) {}
  virtual std::string file() const = 0;
  virtual std::vector<std::string> columns(const RunView& run) const = 0;
  virtual void write_row(const RunView& run) = 0;
  CsvWriter& csv() { return *csv_; }

 private:
  std::optional<CsvWriter> csv_;
};

}  // namespace furniture_fem
