// paper_figures: the comparison figures and event times of the paper study, from the results
// folders the runs wrote (markers.csv, sectional_forces.csv, summary.json, final_state.json).
//
//   paper_figures --results DIR
//
// For every folder DIR/<case>/ holding a summary.json it writes DIR/<case>/events.json (the times and
// values RESULTS.md compares with the paper) and prints one markdown table row per case; for
// configuration 3 (and 1) it draws, into DIR/:
//   fig16_upper_cabinet_x.png  X displacement of the upper separated cabinet, one panel per case
//   fig17_desk_x.png           X displacement of the desk's evaluation point, one panel per case
//   fig17_desk_z.png           vertical displacement of the desk's front edge (it lifts when the desk rocks)
//   fig18_chair_x.png          X displacement of the chair's seat
//   fig19_desk_shear.png       shear in the desk top element next to the evaluation point, case (iii):
//                              vertical (local z of a top-board line, Qz) and depth (local y, Qy)
//   fig16_config1_upper_cabinet_x.png  the same as fig16 for configuration 1
// Displacements are relative to the table, as the paper's motion capture measured them.
#include <furniture_fem/io/csv.hpp>
#include <furniture_fem/figures/plot.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using namespace furniture_fem;
using nlohmann::json;

namespace {

struct CaseInfo {
  std::string tag;    // e.g. kobe100_3d
  std::string label;  // the paper's numbering
};
const std::vector<CaseInfo> kCases = {{"kobe50_1d", "(i) 50% Kobe 1-D"},
                                      {"kobe100_1d", "(ii) 100% Kobe 1-D"},
                                      {"kobe100_3d", "(iii) 100% Kobe 3-D"},
                                      {"haga100_3d", "(iv) 100% Haga 3-D"}};

json read_json(const fs::path& p) {
  std::ifstream f(p);
  return json::parse(f);
}

std::optional<CsvTable> try_csv(const fs::path& p) {
  if (!fs::is_regular_file(p)) return std::nullopt;
  try {
    return read_csv(p.string());
  } catch (const std::exception& e) {
    std::cerr << "warning: " << p << ": " << e.what() << "\n";
    return std::nullopt;
  }
}

// First time a column falls below `threshold` (NaN when never).
double first_below(const CsvTable& t, const std::string& col, double threshold) {
  if (!t.has(col)) return NAN;
  const auto& time = t.column("t");
  const auto& v = t.column(col);
  for (std::size_t i = 0; i < v.size(); ++i)
    if (v[i] < threshold) return time[i];
  return NAN;
}

// Extreme value of a column and its time: the most negative (sign < 0), the largest (sign > 0) or the
// largest magnitude (sign == 0).
std::pair<double, double> extreme(const CsvTable& t, const std::string& col, int sign) {
  if (!t.has(col)) return {NAN, NAN};
  const auto& time = t.column("t");
  const auto& v = t.column(col);
  double best = NAN, at = NAN;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const double key = sign < 0 ? -v[i] : sign > 0 ? v[i] : std::abs(v[i]);
    const double cur = sign < 0 ? -best : sign > 0 ? best : std::abs(best);
    if (std::isnan(best) || key > cur) best = v[i], at = time[i];
  }
  return {best, at};
}

json num(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

std::string fmt(double v, const char* f = "%.2f") {
  if (!std::isfinite(v)) return "-";
  char b[64];
  std::snprintf(b, sizeof b, f, v);
  return b;
}

// The sectional-force column of the desk element (one is requested by configuration(2) and (3)).
std::string desk_section_prefix(const CsvTable& s) {
  for (const auto& c : s.columns())
    if (c.rfind("desk:", 0) == 0 && c.size() > 3 && c.substr(c.size() - 3) == "_Qz") return c.substr(0, c.size() - 3);
  return {};
}

// One figure with a panel per available case of configuration k: column `col` of markers.csv.
void case_panels(const fs::path& results, int k, const std::string& col, const std::string& ylabel,
                 const std::string& title, const fs::path& png, double scale = 1.0) {
  LinePlot p;
  p.title(title).xlabel("time (s) from the start of the window");
  int n = 0;
  for (const auto& c : kCases) {
    const auto m = try_csv(results / ("config" + std::to_string(k) + "_" + c.tag) / "markers.csv");
    if (!m || !m->has(col)) continue;
    std::vector<double> y = m->column(col);
    for (double& v : y) v *= scale;
    p.panels(n + 1);
    p.panel_title(c.label, n).ylabel(ylabel, n);
    p.add(m->column("t"), y, "", n);
    ++n;
  }
  if (n == 0) return;
  p.save_png(png.string(), 1000, 250 + 220 * n);
  std::fprintf(stderr, "wrote %s\n", png.string().c_str());
}

}  // namespace

int main(int argc, char** argv) {
  fs::path results;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--results" && i + 1 < argc) results = argv[++i];
    else {
      std::cerr << "usage: paper_figures --results DIR\n";
      return 2;
    }
  }
  if (results.empty() || !fs::is_directory(results)) {
    std::cerr << "paper_figures: no results folder given or found\n";
    return 2;
  }
  try {
    std::vector<fs::path> dirs;
    for (const auto& e : fs::directory_iterator(results))
      if (e.is_directory() && fs::is_regular_file(e.path() / "summary.json")) dirs.push_back(e.path());
    std::sort(dirs.begin(), dirs.end());

    std::printf("| case | status | t_end (s) | steps | wall (s) | CPU (s) | wall ms/step | energy imbalance | final states |\n");
    std::printf("|---|---|---|---|---|---|---|---|---|\n");
    for (const auto& d : dirs) {
      const json sum = read_json(d / "summary.json");
      json ev;
      ev["case"] = d.filename().string();
      ev["status"] = sum.at("status");
      ev["t_end_s"] = sum.at("t_end_s");
      ev["wall_seconds"] = sum.at("wall_seconds");
      const long steps = sum.at("steps").get<long>();
      ev["ms_per_step"] = steps > 0 ? 1000.0 * sum.at("wall_seconds").get<double>() / double(steps) : 0.0;
      // CPU time from run_paper.sh's time.log ("time: wall W s, user U s, sys S s"), when present.
      double cpu = NAN;
      if (std::ifstream tl(d / "time.log"); tl) {
        std::string line;
        while (std::getline(tl, line)) {
          double w, u, sy;
          if (std::sscanf(line.c_str(), "time: wall %lf s, user %lf s, sys %lf s", &w, &u, &sy) == 3) cpu = u + sy;
        }
      }
      ev["cpu_seconds"] = num(cpu);
      std::string states;
      for (const auto& it : sum.at("final_state")) {
        std::string s = it.at("item").get<std::string>() + ": " + it.at("state").get<std::string>();
        s += " (slide " + fmt(it.at("slide_m").get<double>()) + " m, tilt " + fmt(it.at("tilt_deg").get<double>(), "%.0f") +
             " deg";
        // The largest tilt on the way shows a fall that ended upright (runs before "fell" existed).
        if (it.contains("max_tilt_deg") && it.at("max_tilt_deg").get<double>() > 60 &&
            it.at("tilt_deg").get<double>() <= 60)
          s += ", max tilt " + fmt(it.at("max_tilt_deg").get<double>(), "%.0f") + " deg";
        if (!it.at("resting_on").get<std::string>().empty()) s += ", on " + it.at("resting_on").get<std::string>();
        s += ")";
        states += (states.empty() ? "" : "; ") + s;
      }
      if (const auto m = try_csv(d / "markers.csv")) {
        // A top marker 0.3 m below where it started: the item has fallen (or is falling).
        ev["upper_cabinet_falls_s"] = num(first_below(*m, "separated_cabinets/upper.top_front_centre_z", -0.3));
        ev["tall_cabinet_falls_s"] = num(first_below(*m, "tall_cabinet.top_front_centre_z", -0.3));
        const auto [ux, uxt] = extreme(*m, "separated_cabinets/upper.top_front_centre_x", 0);
        ev["upper_cabinet_max_abs_x_m"] = num(ux);
        ev["upper_cabinet_max_abs_x_at_s"] = num(uxt);
        const auto [dz, dzt] = extreme(*m, "desk.top_back_centre_z", 1);
        ev["desk_max_rise_m"] = num(dz);
        ev["desk_max_rise_at_s"] = num(dzt);
        const auto [fz, fzt] = extreme(*m, "desk.top_front_centre_z", 1);
        ev["desk_front_max_rise_m"] = num(fz);
        ev["desk_front_max_rise_at_s"] = num(fzt);
        const auto [dx, dxt] = extreme(*m, "desk.top_back_centre_x", 0);
        ev["desk_max_abs_x_m"] = num(dx);
        ev["desk_max_abs_x_at_s"] = num(dxt);
        if (m->has("desk.top_back_centre_x")) ev["desk_final_x_m"] = m->column("desk.top_back_centre_x").back();
        const auto [cx, cxt] = extreme(*m, "office_chair.seat_centre_x", 0);
        ev["chair_max_abs_x_m"] = num(cx);
        ev["chair_max_abs_x_at_s"] = num(cxt);
        if (m->has("office_chair.seat_centre_x")) ev["chair_final_x_m"] = m->column("office_chair.seat_centre_x").back();
      }
      if (const auto s = try_csv(d / "sectional_forces.csv")) {
        const std::string pre = desk_section_prefix(*s);
        if (!pre.empty()) {
          ev["desk_section"] = pre;
          // Peaks of both signs: the paper's sign convention for "vertically downward" is not ours.
          for (const auto& [key, comp] : {std::pair{"vertical", "_Qz"}, std::pair{"depth", "_Qy"}}) {
            const auto [lo, lot] = extreme(*s, pre + comp, -1);
            const auto [hi, hit] = extreme(*s, pre + comp, 1);
            ev[std::string("desk_shear_") + key + "_min_N"] = num(lo);
            ev[std::string("desk_shear_") + key + "_min_at_s"] = num(lot);
            ev[std::string("desk_shear_") + key + "_max_N"] = num(hi);
            ev[std::string("desk_shear_") + key + "_max_at_s"] = num(hit);
          }
          // The static value before the shaking builds up (0.5 s), for reference.
          const auto& t = s->column("t");
          for (std::size_t i = 0; i < t.size(); ++i)
            if (t[i] >= 0.5) {
              ev["desk_shear_vertical_at_0.5s_N"] = s->column(pre + "_Qz")[i];
              break;
            }
        }
      }
      std::ofstream(d / "events.json") << ev.dump(2) << "\n";
      std::printf("| %s | %s | %.2f | %ld | %.0f | %s | %.1f | %.2g | %s |\n", d.filename().string().c_str(),
                  sum.at("status").get<std::string>().c_str(), sum.at("t_end_s").get<double>(), steps,
                  sum.at("wall_seconds").get<double>(), fmt(cpu, "%.0f").c_str(), ev["ms_per_step"].get<double>(),
                  sum.at("energy_imbalance_relative").get<double>(), states.c_str());
    }

    case_panels(results, 3, "separated_cabinets/upper.top_front_centre_x", "X (m)",
                "Fig. 16: upper cabinet, X (config 3)", results / "fig16_upper_cabinet_x.png");
    case_panels(results, 1, "separated_cabinets/upper.top_front_centre_x", "X (m)",
                "Upper cabinet, X (config 1)", results / "fig16_config1_upper_cabinet_x.png");
    case_panels(results, 3, "desk.top_back_centre_x", "X (m)", "Fig. 17: desk, X (config 3)",
                results / "fig17_desk_x.png");
    case_panels(results, 3, "desk.top_front_centre_z", "Z (m)", "Desk front edge, Z (config 3)",
                results / "fig17_desk_z.png");
    case_panels(results, 3, "office_chair.seat_centre_x", "X (m)", "Fig. 18: office chair, X (config 3)",
                results / "fig18_chair_x.png");
    case_panels(results, 3, "tall_cabinet.top_front_centre_z", "Z (m)",
                "Tall cabinet top, Z (config 3)", results / "fall_tall_cabinet_z.png");

    if (const auto s = try_csv(results / "config3_kobe100_3d" / "sectional_forces.csv")) {
      const std::string pre = desk_section_prefix(*s);
      if (!pre.empty()) {
        LinePlot p;
        p.title("Fig. 19: desk top shear, (iii) Kobe 3-D")
            .xlabel("time (s) from the start of the window")
            .panels(2);
        p.panel_title("(A) vertical, Qz of " + pre, 0).ylabel("Qz (N)", 0);
        p.panel_title("(B) depth direction, Qy", 1).ylabel("Qy (N)", 1);
        p.add(s->column("t"), s->column(pre + "_Qz"), "", 0);
        p.add(s->column("t"), s->column(pre + "_Qy"), "", 1);
        p.save_png((results / "fig19_desk_shear.png").string(), 1000, 650);
        std::fprintf(stderr, "wrote %s\n", (results / "fig19_desk_shear.png").string().c_str());
      }
    }
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "paper_figures: " << e.what() << "\n";
    return 1;
  }
}
