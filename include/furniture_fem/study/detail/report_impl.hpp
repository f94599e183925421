#pragma once
// Internal: a study's statistics and their files (study/report.hpp's entry points), defined inline when
// the study is used header-only and once in the compiled study (src/study/study_results.cpp).
#ifndef FURNITURE_FEM_STUDY_INTERNAL
#error "furniture_fem/study/detail/report_impl.hpp is internal: include <furniture_fem/study/report.hpp>"
#endif
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "../report.hpp"

#define FURNITURE_FEM_STUDY_INTERNAL
#include "measure_names.hpp"
#include "study_files.hpp"
#undef FURNITURE_FEM_STUDY_INTERNAL

namespace furniture_fem {

namespace detail {
// A body's outcome in one completed run, with the run (its devices' outcomes).
struct BodyInRun {
  const RunResult* run;
  const BodyOutcome* body;
};
// The completed outcomes of one body in one variant at one level, by realisation.
inline std::map<long, BodyInRun> body_outcomes(const StudySpec& s, const std::vector<RunResult>& results, int variant, int level,
                                               const std::string& body, long* excluded = nullptr) {
  std::map<long, BodyInRun> out;
  const long per_level = long(s.num_motions()) * s.realisations;
  for (const auto& r : results) {
    if (r.variant != variant || r.realisation / per_level != level) continue;
    if (r.status != "completed") {
      if (excluded) ++*excluded;
      continue;
    }
    for (const auto& b : r.bodies)
      if (b.name == body) out[r.realisation] = {&r, &b};
  }
  return out;
}
inline bool in_state(const StudySpec& s, const BodyInRun& x, const char* state) {
  return in_damage_state(s.outcomes, *x.run, *x.body, state);
}
// The damage states reported for a body: device_broke only if some run of the study fastens it (a study
// without restraints keeps its four states).
inline std::vector<const char*> states_of(const std::vector<RunResult>& results, const std::string& body) {
  const bool fastened = std::any_of(results.begin(), results.end(), [&](const RunResult& r) {
    return std::any_of(r.restraints.begin(), r.restraints.end(), [&](const RestraintOutcome& o) { return o.item == body; });
  });
  std::vector<const char*> states(damage_states.begin(), damage_states.end());
  if (!fastened) states.pop_back();
  return states;
}
inline std::vector<std::string> bodies_of(const std::vector<RunResult>& results, int variant) {
  std::vector<std::string> names;
  for (const auto& r : results)
    if (r.variant == variant)
      for (const auto& b : r.bodies)
        if (std::find(names.begin(), names.end(), b.name) == names.end()) names.push_back(b.name);
  return names;
}
// The bootstrap's resamples: enough for a 95 % percentile interval to be stable to about 1 %.
inline constexpr int fragility_bootstrap_resamples = 1000;
}  // namespace detail

FFEM_STUDY_ENTRY StudyReport study_report(const StudySpec& s, const std::vector<RunResult>& results) {
  StudyReport rep;
  rep.measure = json_io::enum_name(detail::measure_names, s.intensity.measure);
  for (int v = 0; v < s.num_variants(); ++v) {
    const std::string vname = s.variant_name(v);
    for (const auto& body : detail::bodies_of(results, v)) {
      const auto states = detail::states_of(results, body);
      std::map<std::string, std::vector<FragilityLevel>> levels_by_state;
      for (int l = 0; l < s.num_levels(); ++l) {
        long excluded = 0;
        const auto outcomes = detail::body_outcomes(s, results, v, l, body, &excluded);
        const double level = s.intensity.levels[l];
        for (const char* state : states) {
          long k = 0;
          for (const auto& [real, b] : outcomes) k += detail::in_state(s, b, state);
          const long n = static_cast<long>(outcomes.size());
          if (n > 0) rep.probabilities.push_back({vname, body, state, l, level, wilson_interval(k, n), excluded});
          if (n > 0) levels_by_state[state].push_back({level, n, k});
        }
        for (const char* name : continuous_outcomes) {
          std::vector<double> values;
          for (const auto& [real, b] : outcomes) values.push_back(continuous_outcome(*b.body, name));
          if (!values.empty()) rep.distributions.push_back({vname, body, name, l, level, describe(values)});
        }
      }
      if (s.num_levels() >= 2)
        for (const char* state : states) {
          const auto& lv = levels_by_state[state];
          if (lv.size() < 2) continue;
          FragilityRow row{vname, body, state, fit_lognormal_fragility(lv), {}};
          if (row.fit.identifiable)
            row.interval = bootstrap_fragility(lv, detail::fragility_bootstrap_resamples, mix64(s.seed ^ 0xf7a9111eULL));
          rep.fragility.push_back(row);
        }
    }
  }
  // Every other variant against the first, on the realisations both completed.
  for (int v = 1; v < s.num_variants(); ++v)
    for (const auto& body : detail::bodies_of(results, 0))
      for (int l = 0; l < s.num_levels(); ++l) {
        const auto a = detail::body_outcomes(s, results, 0, l, body), b = detail::body_outcomes(s, results, v, l, body);
        for (const char* state : detail::states_of(results, body)) {
          long both = 0, only_a = 0, only_b = 0, neither = 0;
          for (const auto& [real, oa] : a) {
            const auto it = b.find(real);
            if (it == b.end()) continue;
            const bool da = detail::in_state(s, oa, state), db = detail::in_state(s, it->second, state);
            both += da && db;
            only_a += da && !db;
            only_b += !da && db;
            neither += !da && !db;
          }
          if (both + only_a + only_b + neither == 0) continue;
          rep.comparisons.push_back({s.variant_name(0), s.variant_name(v), body, state, l, s.intensity.levels[l],
                                     paired_difference(both, only_a, only_b, neither)});
        }
      }
  return rep;
}

namespace detail {
inline std::string report_number(double v) { return std::isfinite(v) ? exact_number(v) : std::string(); }
}  // namespace detail

FFEM_STUDY_ENTRY void write_report(const StudyReport& rep, const std::filesystem::path& dir) {
  using detail::csv_field;
  const auto num = detail::report_number;
  std::string p = "variant,level_index,level_" + rep.measure + ",body,state,count,runs,probability,wilson95_lo,wilson95_hi,excluded\n";
  for (const auto& r : rep.probabilities)
    p += csv_field(r.variant) + "," + std::to_string(r.level_index) + "," + num(r.level) + "," + csv_field(r.body) + "," +
         r.state + "," + std::to_string(r.estimate.successes) + "," + std::to_string(r.estimate.trials) + "," +
         num(r.estimate.p) + "," + num(r.estimate.lo) + "," + num(r.estimate.hi) + "," + std::to_string(r.excluded) + "\n";
  detail::write_text_atomically(dir / "probabilities.csv", p);

  std::string d = "variant,level_index,level_" + rep.measure + ",body,outcome,count,min,p16,median,p84,max,mean\n";
  for (const auto& r : rep.distributions) {
    const Distribution& x = r.distribution;
    d += csv_field(r.variant) + "," + std::to_string(r.level_index) + "," + num(r.level) + "," + csv_field(r.body) + "," +
         r.outcome + "," + std::to_string(x.count) + "," + num(x.min) + "," + num(x.p16) + "," + num(x.median) + "," +
         num(x.p84) + "," + num(x.max) + "," + num(x.mean) + "\n";
  }
  detail::write_text_atomically(dir / "distributions.csv", d);

  std::string f = "variant,body,state,identifiable,median_" + rep.measure +
                  ",median_lo,median_hi,beta,beta_lo,beta_hi,bootstrap_excluded,log_likelihood,message\n";
  for (const auto& r : rep.fragility)
    f += csv_field(r.variant) + "," + csv_field(r.body) + "," + r.state + "," + (r.fit.identifiable ? "true" : "false") +
         "," + num(r.fit.theta) + "," + num(r.interval.theta_lo) + "," + num(r.interval.theta_hi) + "," + num(r.fit.beta) +
         "," + num(r.interval.beta_lo) + "," + num(r.interval.beta_hi) + "," + std::to_string(r.interval.not_identifiable) + "," +
         num(r.fit.log_likelihood) + "," + csv_field(r.fit.message) + "\n";
  detail::write_text_atomically(dir / "fragility.csv", f);

  std::string c = "variant_a,variant_b,level_index,level_" + rep.measure +
                  ",body,state,pairs,p_a,p_b,difference,newcombe95_lo,newcombe95_hi,distinguishable\n";
  for (const auto& r : rep.comparisons) {
    const PairedDifference& x = r.difference;
    c += csv_field(r.variant_a) + "," + csv_field(r.variant_b) + "," + std::to_string(r.level_index) + "," + num(r.level) +
         "," + csv_field(r.body) + "," + r.state + "," + std::to_string(x.n) + "," + num(x.p_a) + "," + num(x.p_b) + "," +
         num(x.difference) + "," + num(x.lo) + "," + num(x.hi) + "," + (x.distinguishable ? "true" : "false") + "\n";
  }
  detail::write_text_atomically(dir / "comparisons.csv", c);

  nlohmann::json j = {{"measure", rep.measure}, {"fragility", nlohmann::json::array()}};
  for (const auto& r : rep.fragility)
    j["fragility"].push_back({{"variant", r.variant},
                              {"body", r.body},
                              {"state", r.state},
                              {"identifiable", r.fit.identifiable},
                              {"median", r.fit.identifiable ? nlohmann::json(r.fit.theta) : nlohmann::json()},
                              {"beta", r.fit.identifiable ? nlohmann::json(r.fit.beta) : nlohmann::json()},
                              {"message", r.fit.message}});
  detail::write_text_atomically(dir / "statistics.json", j.dump(2) + "\n");
}

}  // namespace furniture_fem
