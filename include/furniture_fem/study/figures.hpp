#pragma once
// furniture_fem/study/figures.hpp: a study's figures, drawn from its report and results with the
// figures module (docs/study/studies.md, "Outputs").
//
//   write_study_figures(study, report, results, folder)
//     fragility.png               per body: the fitted lognormal P(state | im) of each damage state and
//                                 variant (lines: a colour per state, the first variant solid, the others
//                                 dashed), the observed fraction per level (dots) with its Wilson 95 %
//                                 interval (bars); states without a fit show their dots only; one legend
//     max_tilt_vs_intensity.png   every completed run's largest tilt against its level, per body and
//                                 variant, with the tilt threshold
//     outcome_histograms.png      per body: the final slide of the completed runs (all levels pooled),
//                                 one step line per variant; the first bin ends at the slide threshold
//
// A figure with nothing to show (no completed run) is not written. Throws OutputError when a file
// cannot be written. The detail:: builders return the LinePlot so tests can locate the data in it.
#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "../figures/plot.hpp"
#include "outcomes.hpp"
#include "report.hpp"
#include "spec.hpp"

#define FURNITURE_FEM_STUDY_INTERNAL
#include "detail/measure_names.hpp"
#include "detail/study_files.hpp"
#undef FURNITURE_FEM_STUDY_INTERNAL

namespace furniture_fem {
namespace detail {

// Width fixed; each panel gets ~340 px so a six-entry legend fits beside the data, and at least
// 500 px overall keeps the text at scale 2 (PlotStyle::scale_for).
inline constexpr int study_figure_width = 1000;
inline int study_figure_height(int panels) { return std::max(500, 140 + 340 * panels); }

inline std::string intensity_axis_label(const StudySpec& s) {
  const IntensityMeasure m = s.intensity.measure;
  const char* unit = m == IntensityMeasure::pga ? "m/s^2" : m == IntensityMeasure::pgv ? "m/s" : "-";
  return "intensity (" + json_io::enum_name(measure_names, m) + ", " + unit + ")";
}

// The x range of the intensity figures: from 0, so the fitted curves show their foot, to 1.2 times
// the highest level, so they show their shoulder.
inline double intensity_axis_end(const StudySpec& s) {
  double hi = 0;
  for (double l : s.intensity.levels) hi = std::max(hi, l);
  return 1.2 * (hi > 0 ? hi : 1.0);
}

// Half the smallest gap between levels: the points of one level are spread within it (so series and
// coincident runs stay apart) and never reach the next level's.
inline double level_spread(const StudySpec& s) {
  std::vector<double> l = s.intensity.levels;
  std::sort(l.begin(), l.end());
  double gap = intensity_axis_end(s) / 6;
  for (std::size_t i = 1; i < l.size(); ++i)
    if (l[i] > l[i - 1]) gap = std::min(gap, l[i] - l[i - 1]);
  return 0.5 * gap;
}
// Offset of series k of n: its own slot of width spread / n, centred on the level.
inline double dodge(std::size_t k, std::size_t n, double spread) {
  return n < 2 ? 0.0 : spread * ((double(k) + 0.5) / double(n) - 0.5);
}

inline void add_unique(std::vector<std::string>& names, const std::string& name) {
  if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
}
inline std::string with_variant(const StudySpec& s, std::string label, const std::string& variant) {
  return s.num_variants() > 1 ? label + ", " + variant : label;
}

// Dots without lines: LinePlot marks every finite point, and the NaN after each breaks the polyline.
inline Series dots(const std::vector<double>& x, const std::vector<double>& y, RGB colour, std::string label) {
  Series d;
  d.color = colour, d.label = std::move(label), d.marker = 4.5, d.width = 1;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (std::size_t i = 0; i < x.size(); ++i) d.x.insert(d.x.end(), {x[i], nan}), d.y.insert(d.y.end(), {y[i], nan});
  return d;
}
// Error bars as one broken polyline (the plot API has no bars): a vertical stroke lo..hi at each x.
inline Series bars(const std::vector<double>& x, const std::vector<double>& lo, const std::vector<double>& hi, RGB colour) {
  Series b;
  b.color = colour, b.width = 1.5;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (std::size_t i = 0; i < x.size(); ++i)
    b.x.insert(b.x.end(), {x[i], x[i], nan}), b.y.insert(b.y.end(), {lo[i], hi[i], nan});
  return b;
}

// The fitted P(state | im) at 121 points over the intensity axis.
inline Series fragility_curve(const LognormalFragility& fit, double x_end, RGB colour, std::string label) {
  Series c;
  c.color = colour, c.label = std::move(label);
  for (int i = 0; i <= 120; ++i) {
    const double im = x_end * i / 120.0;
    c.x.push_back(im), c.y.push_back(fragility_probability(fit, im));
  }
  return c;
}

// One (variant, state) cell of a body's panel: its curve if identifiable, its observed fractions
// always (a state never or always reached has no fit, and the researcher still wants to see that).
// A state has one colour in every panel and variant; the first variant's fits are solid, the others'
// dashed (with 8 series of 8 colours each panel needed its own legend, and it covered the data).
inline void add_fragility_cell(LinePlot& plot, int panel, const StudySpec& s, const StudyReport& rep, const std::string& body,
                               int variant, int state, double offset) {
  const std::string vname = s.variant_name(variant), sname = damage_states[std::size_t(state)];
  std::vector<double> x, p, lo, hi;
  for (const ProbabilityRow& r : rep.probabilities)
    if (r.variant == vname && r.body == body && r.state == sname)
      x.push_back(r.level + offset), p.push_back(r.estimate.p), lo.push_back(r.estimate.lo), hi.push_back(r.estimate.hi);
  if (x.empty()) return;
  const RGB colour = palette_color(std::size_t(state));
  const auto fit = std::find_if(rep.fragility.begin(), rep.fragility.end(), [&](const FragilityRow& f) {
    return f.variant == vname && f.body == body && f.state == sname && f.fit.identifiable;
  });
  if (fit != rep.fragility.end()) {
    Series curve = fragility_curve(fit->fit, intensity_axis_end(s), colour, "");
    curve.dashed = variant > 0;
    plot.add(std::move(curve), panel);
  }
  plot.add(bars(x, lo, hi, colour), panel);
  plot.add(dots(x, p, colour, ""), panel);
}

// The damage states the report has rows of, by their index in damage_states (which fixes each one's
// colour): device_broke only in a study that fastens something.
inline std::vector<int> reported_states(const StudyReport& rep) {
  std::vector<int> states;
  for (int st = 0; st < int(damage_states.size()); ++st)
    if (std::any_of(rep.probabilities.begin(), rep.probabilities.end(),
                    [&](const ProbabilityRow& r) { return r.state == damage_states[std::size_t(st)]; }))
      states.push_back(st);
  return states;
}

// The fragility figure's one legend, in the first panel: a line and dot per damage state in its
// colour, and (several variants) each variant's line style and where its dots sit at a level.
inline void add_fragility_legend(LinePlot& plot, const StudySpec& s, const std::vector<int>& states) {
  for (int st : states) {
    Series key;
    key.color = palette_color(std::size_t(st)), key.label = damage_states[std::size_t(st)], key.marker = 4.5;
    plot.add(std::move(key), 0);
  }
  if (s.num_variants() < 2) return;
  for (int v = 0; v < s.num_variants(); ++v) {
    Series key;
    const int n = s.num_variants();
    const std::string dots = v == 0 ? "left" : v == n - 1 ? "right" : "place " + std::to_string(v + 1) + " from left";
    key.color = colors::black, key.label = s.variant_name(v) + ": fit, dots " + dots, key.dashed = v > 0;
    plot.add(std::move(key), 0);
  }
}

// fragility.png: one panel per body; the legend top left of the first, where rising curves leave room.
// A state with dots and no line has no fit (never or always reached, or not identifiable).
inline LinePlot fragility_plot(const StudySpec& s, const StudyReport& rep) {
  std::vector<std::string> bodies;
  for (const ProbabilityRow& r : rep.probabilities) add_unique(bodies, r.body);
  const std::vector<int> states = reported_states(rep);
  LinePlot plot("Fragility: lognormal fits (lines), observed fractions (dots, 95 %)");
  plot.panels(std::max<int>(1, int(bodies.size()))).xlabel(intensity_axis_label(s)).xlim(0, intensity_axis_end(s));
  plot.style().legend = LegendPos::top_left;
  add_fragility_legend(plot, s, states);
  const std::size_t cells = std::size_t(s.num_variants()) * states.size();
  for (int b = 0; b < int(bodies.size()); ++b) {
    plot.ylabel(bodies[std::size_t(b)] + ": probability", b).ylim(-0.03, 1.03, b);
    for (int v = 0; v < s.num_variants(); ++v)
      for (std::size_t i = 0; i < states.size(); ++i) {
        const std::size_t k = std::size_t(v) * states.size() + i;
        add_fragility_cell(plot, b, s, rep, bodies[std::size_t(b)], v, states[i], dodge(k, cells, level_spread(s)));
      }
  }
  return plot;
}

// The intensity level a run was scaled to.
inline double run_level(const StudySpec& s, const RunResult& r) {
  const long per_level = long(s.num_motions()) * s.realisations;
  return s.intensity.levels.at(std::size_t(r.realisation / per_level));
}

// max_tilt_vs_intensity.png: one cloud per (body, variant), spread around each level; the
// threshold that defines "tilted" as a dashed line, so the fragility's "tilted" can be read off.
inline LinePlot max_tilt_plot(const StudySpec& s, const std::vector<RunResult>& results) {
  std::vector<std::string> labels;
  std::vector<std::vector<std::array<double, 3>>> clouds;  // level, max tilt, realisation
  double top = s.outcomes.tilt_threshold_deg;
  for (const RunResult& r : results) {
    if (r.status != "completed") continue;
    for (const BodyOutcome& b : r.bodies) {
      const std::string label = with_variant(s, b.name, s.variant_name(r.variant));
      add_unique(labels, label);
      clouds.resize(labels.size());
      const auto k = std::size_t(std::find(labels.begin(), labels.end(), label) - labels.begin());
      clouds[k].push_back({run_level(s, r), b.max_tilt_deg, double(r.realisation)});
      top = std::max(top, b.max_tilt_deg);
    }
  }
  const double x_end = intensity_axis_end(s), spread = level_spread(s), slot = spread / std::max<double>(1, double(labels.size()));
  LinePlot plot("Largest tilt of each completed run");
  plot.xlabel(intensity_axis_label(s)).ylabel("max tilt (deg)").xlim(0, x_end).ylim(0, 1.08 * top);
  plot.style().legend = LegendPos::top_left;
  for (std::size_t k = 0; k < labels.size(); ++k) {
    std::vector<double> x, y;
    for (const auto& [level, tilt, real] : clouds[k]) {  // runs of one level fan out within the series' slot
      x.push_back(level + dodge(k, labels.size(), spread) + 0.7 * slot * (std::fmod(real, 5.0) / 4.0 - 0.5));
      y.push_back(tilt);
    }
    plot.add(dots(x, y, palette_color(k), labels[k]));
  }
  Series t;
  t.x = {0, x_end}, t.y = {s.outcomes.tilt_threshold_deg, s.outcomes.tilt_threshold_deg};
  t.dashed = true, t.color = colors::dark_grey, t.label = "tilt threshold (" + exact_number(s.outcomes.tilt_threshold_deg) + " deg)";
  return plot.add(std::move(t));
}

// A histogram as a step line over ascending `edges` (the plot API has no bars): up, across each
// bin, down. A value on an edge counts in the bin above it, the last edge in the last bin.
inline Series histogram_steps(const std::vector<double>& values, const std::vector<double>& edges) {
  const std::size_t nb = edges.size() - 1;
  std::vector<double> count(nb, 0.0);
  for (double v : values)
    if (std::isfinite(v)) {
      const auto above = std::size_t(std::upper_bound(edges.begin(), edges.end(), v) - edges.begin());
      ++count[std::clamp<std::size_t>(above, 1, nb) - 1];
    }
  Series s;
  s.x = {edges[0]}, s.y = {0};
  for (std::size_t i = 0; i < nb; ++i) s.x.insert(s.x.end(), {edges[i], edges[i + 1]}), s.y.insert(s.y.end(), {count[i], count[i]});
  s.x.push_back(edges[nb]), s.y.push_back(0);
  return s;
}

// Bins: [0, threshold] first, so its bar is exactly the runs that did not slide, then equal bins up to
// the largest slide (about the square root of the runs, 8 to 30 in all).
inline std::vector<double> slide_bin_edges(double threshold, double hi, std::size_t runs) {
  const int nb = std::clamp(int(std::ceil(std::sqrt(double(runs)))), 8, 30);
  std::vector<double> edges{0.0};
  for (int i = 0; i < nb; ++i) edges.push_back(threshold + (hi - threshold) * i / (nb - 1));
  return edges;
}

// outcome_histograms.png: one panel per body, one step line per variant on bins shared by all, so
// panels and variants compare bin for bin. The first variant is drawn widest so an identical
// histogram on top of it leaves it visible.
inline LinePlot slide_histogram_plot(const StudySpec& s, const std::vector<RunResult>& results) {
  std::vector<std::string> bodies;
  std::vector<std::vector<std::vector<double>>> slides;  // body, variant, runs
  double hi = 1.5 * s.outcomes.slide_threshold;           // the threshold stays in view
  std::size_t most = 1;
  for (const RunResult& r : results) {
    if (r.status != "completed") continue;
    for (const BodyOutcome& b : r.bodies) {
      add_unique(bodies, b.name);
      slides.resize(bodies.size(), std::vector<std::vector<double>>(std::size_t(s.num_variants())));
      auto& v = slides[std::size_t(std::find(bodies.begin(), bodies.end(), b.name) - bodies.begin())][std::size_t(r.variant)];
      v.push_back(b.slide);
      most = std::max(most, v.size());
      if (std::isfinite(b.slide)) hi = std::max(hi, b.slide);
    }
  }
  const std::vector<double> edges = slide_bin_edges(s.outcomes.slide_threshold, hi, most);
  LinePlot plot("Final slide of completed runs (all levels)");
  // A little room right of the last bin, so its drop to zero is not hidden by the frame.
  plot.panels(std::max<int>(1, int(bodies.size()))).xlabel("final slide (m)").xlim(0, 1.03 * hi);
  plot.style().legend = LegendPos::top_right;
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    double peak = 1;
    for (int v = 0; v < s.num_variants(); ++v) {
      Series h = histogram_steps(slides[b][std::size_t(v)], edges);
      for (double c : h.y) peak = std::max(peak, c);
      h.color = palette_color(std::size_t(v)), h.width = v == 0 ? 3.5 : 2.0, h.label = s.variant_name(v);
      plot.add(std::move(h), int(b));
    }
    Series t;
    t.x = {s.outcomes.slide_threshold, s.outcomes.slide_threshold}, t.y = {0, 1.1 * peak};
    t.dashed = true, t.color = colors::dark_grey, t.label = "slide threshold (" + exact_number(s.outcomes.slide_threshold) + " m)";
    plot.add(std::move(t), int(b)).ylabel(bodies[b] + ": runs", int(b)).ylim(0, 1.1 * peak, int(b));
  }
  return plot;
}

inline void save_study_figure(const LinePlot& plot, const std::filesystem::path& file) {
  plot.save_png(file.string(), study_figure_width, study_figure_height(plot.num_panels()));
}

}  // namespace detail

inline void write_study_figures(const StudySpec& s, const StudyReport& rep, const std::vector<RunResult>& results,
                                const std::filesystem::path& dir) {
  if (!rep.probabilities.empty()) detail::save_study_figure(detail::fragility_plot(s, rep), dir / "fragility.png");
  const bool any = std::any_of(results.begin(), results.end(), [](const RunResult& r) { return r.status == "completed"; });
  if (!any) return;
  detail::save_study_figure(detail::max_tilt_plot(s, results), dir / "max_tilt_vs_intensity.png");
  detail::save_study_figure(detail::slide_histogram_plot(s, results), dir / "outcome_histograms.png");
}

}  // namespace furniture_fem
