#pragma once
// furniture_fem/scene/forecast.hpp: what a run will cost, said before it costs (issue 51).
//
//   detail::RunForecast       a run's steps before the first, its projected wall time after a second
//   detail::wall_time_text    "2.5 h"
//
// The run loop (runner.hpp) and a study's progress line (study/runner.hpp) use them; both write to
// stderr only, so the programs' stdout and files are the same as without them.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>

#include "run_summary.hpp"

namespace furniture_fem::detail {

// A wall time in s, m, h or d: "2.5 h".
inline std::string wall_time_text(double s) {
  char b[32];
  if (s < 10) std::snprintf(b, sizeof b, "%.1f s", s);
  else if (s < 120) std::snprintf(b, sizeof b, "%.0f s", s);
  else if (s < 7200) std::snprintf(b, sizeof b, "%.1f min", s / 60);
  else if (s < 172800) std::snprintf(b, sizeof b, "%.1f h", s / 3600);
  else std::snprintf(b, sizeof b, "%.1f days", s / 86400);
  return b;
}

// What a run will cost, said on stderr before it costs (issue 51): its steps before the first, and
// after forecast_after_seconds of stepping its projected wall time. Without the progress bar
// (--quiet) both only for a run projected to take longer than quiet_forecast_seconds.
inline constexpr double forecast_after_seconds = 1.0, quiet_forecast_seconds = 60.0;
class RunForecast {
 public:
  RunForecast(const RunOptions& opt, long done, long total, std::string steps_line)
      : on_(opt.forecast), bar_(opt.progress), done0_(done), total_(total), line_(std::move(steps_line)) {
    if (on_ && bar_) say(line_);
  }
  void after_step(long done) {
    if (!on_ || said_) return;
    const double el = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    if (el < forecast_after_seconds) return;
    said_ = true;
    const double projected = el / double(done - done0_) * double(total_ - done0_);
    if (!bar_ && !(projected > quiet_forecast_seconds)) return;
    const std::string left = done0_ > 0 ? " left" : "";
    std::string text = "run: " + std::to_string(done - done0_) + " steps in the first " + fmt(std::round(el * 10) / 10) +
                       " s of wall time: about " + wall_time_text(projected) + " for the " +
                       std::to_string(total_ - done0_) + " steps" + left;
    if (!bar_) text = line_ + "\n" + text;
    say(text);
  }

 private:
  // On its own line over the progress bar's (which is drawn again after it).
  void say(const std::string& text) const {
    std::fprintf(stderr, bar_ ? "\r%-100s\n" : "%s\n", text.c_str());
    std::fflush(stderr);
  }
  bool on_, bar_, said_ = false;
  long done0_, total_;
  std::string line_;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

}  // namespace furniture_fem::detail
