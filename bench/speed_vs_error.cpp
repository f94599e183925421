// Speed against error: what each modelling and numerical choice costs and what it buys, on a small
// but representative scene (the tall cabinet 0.2 m behind the desk, 3 s of the built-in synthetic
// 3-D motion), measured against a converged reference (dt = 0.25 ms, panel grids halved and 25 mm
// elements, paper Newmark carry-over, direct solver refreshed every step).
//
// Families (each point changes one thing from the default: ASI-Gauss elements, paper Newmark
// carry-over, dt = 1 ms, 50 mm elements on the tuned grids, direct LDL^T refreshed every 0.1 s,
// full fidelity):
//   element     conventional one-point Timoshenko (s = 0), cubic Euler-Bernoulli (elastic reference)
//   mesh        element_length 0.025 / 0.1 / 0.2 m, grid_scale 0.5 / 2
//   dt          0.25 / 0.5 / 2 / 5 ms
//   integrator  average acceleration, generalized-alpha (rho_inf 0.5); each also iterated to
//               equilibrium (paper Newmark too)
//   solver      CG (incomplete Cholesky) refreshed every 0.1 s; direct refreshed every 1 / 20 steps
//   fidelity    coarse, rigid, auto (the desk, whose sectional force is asked for, full; the cabinet
//               rigid)
// Errors against the reference: marker displacement histories (the cabinet's top front centre and
// the desk's top back centre, table frame, sampled every 10 ms): RMS over the run and peak, in mm,
// the larger of the two markers; final state: slide (mm) and tilt (deg), the larger over the two
// items; peak shear force |Q| of the desk's top-board element next to its back centre (%, when the
// desk is a finite-element body). Wall time: building the scene and stepping it, one thread.
//
// Writes <docs>/speed_vs_error.csv, <docs>/speed_vs_error.md (the table) and
// <docs>/images/speed_vs_error.png (wall time against marker RMS error, log-log, Pareto front).
//   cd /work/main && nice -n 10 ./build/bench/speed_vs_error            # the reference alone ~52 min on one core; the CG variant > 40 min
//   ./build/bench/speed_vs_error --only default,dt_5ms --duration 1     # a subset, for a quick look
// Options: --docs DIR (default docs), --duration S (3), --pga M_S2 (4.0), --only a,b,c, --list,
// --no-reference (the variants' own final states only), --table-from LOG (write the files from a
// previous run's printed lines, running nothing; variants the log lacks are left out),
// --reference-refresh N (1; the reference's
// factorisation is 86 % of its time: N = 5 makes it about 3 times cheaper, with the body rotation
// taken out of the reused factorisation at dt = 0.25 ms).
#include <furniture_fem/figures/plot.hpp>
#include <furniture_fem/scene/scene_runner.hpp>

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace {
using namespace furniture_fem;

enum class ElementChoice { asi_gauss, conventional, cubic_euler_bernoulli };

struct Variant {
  std::string name, family, label;
  double dt = 1e-3;
  double element_length = 0.05, grid_scale = 1.0;
  IntegratorKind scheme = IntegratorKind::paper_newmark;
  bool iterate = false;
  bool cg = false;
  int refresh = 0;  // steps between factorisations; 0: the scene default, every 0.1 s (100 steps at 1 ms)
  Fidelity fidelity = Fidelity::full;
  ElementChoice element = ElementChoice::asi_gauss;
};

struct Sample {
  std::vector<Vec3> markers;
};

struct Result {
  std::string status = "completed", diagnosis;
  double wall = 0;
  long steps = 0;
  int elements = 0;
  std::vector<Sample> samples;  // every 10 ms from t = 0
  std::vector<double> slide, tilt;  // per item
  std::optional<double> peak_shear;  // N, the desk's element (none when the desk is rigid)
  double energy_imbalance = 0;
};

constexpr double sample_interval = 0.01;

SceneSpec base_scene(double duration, double pga) {
  SceneSpec s;
  s.name = "speed vs error: tall cabinet and desk";
  s.source = s.name;
  s.walls = {};
  s.contact.law = law_kind<PaperAnisotropicSceneLaw>;
  s.duration = duration;
  // The tall cabinet (front towards -X) 0.2 m behind the desk's back edge, as in configuration 3's
  // centre group but closer.
  const double cabinet_x = 0.5, front = cabinet_x - 0.5 * paper_item(PaperItem::tall_cabinet).D;
  const double desk_x = front - 0.2 - 0.5 * paper_item(PaperItem::desk).D;
  s.items.push_back({"tall_cabinet", ItemKind::tall_cabinet, cabinet_x, 0.0, -90.0, Fidelity::full, {}});
  s.items.push_back({"desk", ItemKind::desk, desk_x, 0.0, -90.0, Fidelity::full, {}});
  s.ground_motion.source = MotionSource::synthetic;
  s.ground_motion.pga = pga;
  s.ground_motion.dimensions = MotionDimensions::three_d;
  s.ground_motion.seed = 1;
  s.outputs = OutputSpec{};
  s.outputs.figures = false;
  // The desk's sectional force is asked for: "auto" keeps the desk a finite-element body.
  Model scratch;
  const auto items = build_scene(s, scratch);
  const auto [member, element] = element_near(scratch, items[1], items[1].marker("top_back_centre")->local_point);
  s.outputs.sectional_forces.push_back({"desk", member, element});
  return s;
}

SceneSpec scene_for(const Variant& v, double duration, double pga) {
  SceneSpec s = base_scene(duration, pga);
  s.dt = v.dt;
  s.integrator.scheme = v.scheme;
  s.integrator.rho_inf = 0.5;
  s.integrator.iterate_to_equilibrium = v.iterate;
  s.solver = v.cg ? SolverKind::cg : SolverKind::direct;
  for (auto& it : s.items) {
    it.fidelity = v.fidelity;
    if (v.element_length != 0.05) it.params.element_length = v.element_length;
    if (v.grid_scale != 1.0) it.params.grid_scale = v.grid_scale;
  }
  return s;
}

template <class Solver, class Element>
Result run(const Variant& v, double duration, double pga) {
  const SceneSpec spec = scene_for(v, duration, pga);
  Result r;
  const auto t0 = std::chrono::steady_clock::now();
  SceneSimulation<Solver, Element> scene(spec, v.refresh, 1);
  auto& sim = *scene.sim;
  const Model& model = *scene.model;
  r.elements = model.num_elements();
  const ItemInfo& cabinet = scene.items[0];
  const ItemInfo& desk = scene.items[1];
  const std::vector<int> marker_nodes{cabinet.marker("top_front_centre")->node, desk.marker("top_back_centre")->node};
  // The desk's element nearest to its top back centre, in this variant's mesh.
  const auto [member, index] = element_near(model, desk, desk.marker("top_back_centre")->local_point);
  const int section = model.member(find_member(model, desk.body, member)).first_element + index;
  const bool desk_rigid = sim.is_rigid(desk.body);
  const long every = std::lround(sample_interval / v.dt);
  auto sample = [&] {
    Sample s;
    for (int n : marker_nodes) s.markers.push_back(sim.displacement(n));
    r.samples.push_back(s);
  };
  double peak = 0;
  sample();
  try {
    while (sim.time() < duration - 0.5 * v.dt) {
      sim.step();
      if (!desk_rigid) {
        const auto f = sim.section_forces(section);
        peak = std::max(peak, std::hypot(f.Qy, f.Qz));
      }
      if (sim.steps() % every == 0) sample();
    }
  } catch (const SimulationError& e) {
    r.status = "diverged";
    r.diagnosis = e.what();
  }
  r.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.steps = sim.steps();
  if (!desk_rigid) r.peak_shear = peak;
  for (const auto& it : scene.items) {
    Vec3 shift;
    r.tilt.push_back(detail::tilt_of(detail::body_rotation_of(sim, model, it.body, &shift)));
    r.slide.push_back(std::hypot(shift.x(), shift.y()));
  }
  const auto E = sim.energy();
  r.energy_imbalance = std::abs(E.imbalance()) / E.scale();
  return r;
}

Result run_variant(const Variant& v, double duration, double pga) {
  if (v.cg) return run<ConjugateGradientSolver, AsiGaussTimoshenko>(v, duration, pga);
  switch (v.element) {
    case ElementChoice::conventional: return run<DirectLdltSolver, ConventionalTimoshenko>(v, duration, pga);
    case ElementChoice::cubic_euler_bernoulli: return run<DirectLdltSolver, CubicEulerBernoulli>(v, duration, pga);
    default: return run<DirectLdltSolver, AsiGaussTimoshenko>(v, duration, pga);
  }
}

struct Errors {
  double rms_mm = NAN, peak_mm = NAN, slide_mm = NAN, tilt_deg = NAN, shear_pct = NAN;
};

Errors compare(const Result& r, const Result& ref) {
  Errors e;
  const size_t n = std::min(r.samples.size(), ref.samples.size());
  if (n == 0 || r.status != "completed") return e;
  e.rms_mm = 0;
  e.peak_mm = 0;
  for (size_t m = 0; m < ref.samples[0].markers.size(); ++m) {
    double sum2 = 0, peak = 0;
    for (size_t i = 0; i < n; ++i) {
      const double d = (r.samples[i].markers[m] - ref.samples[i].markers[m]).norm();
      sum2 += d * d;
      peak = std::max(peak, d);
    }
    e.rms_mm = std::max(e.rms_mm, 1e3 * std::sqrt(sum2 / double(n)));
    e.peak_mm = std::max(e.peak_mm, 1e3 * peak);
  }
  e.slide_mm = 0;
  e.tilt_deg = 0;
  for (size_t i = 0; i < ref.slide.size(); ++i) {
    e.slide_mm = std::max(e.slide_mm, 1e3 * std::abs(r.slide[i] - ref.slide[i]));
    e.tilt_deg = std::max(e.tilt_deg, std::abs(r.tilt[i] - ref.tilt[i]));
  }
  if (r.peak_shear && ref.peak_shear && *ref.peak_shear > 0)
    e.shear_pct = 100.0 * std::abs(*r.peak_shear - *ref.peak_shear) / *ref.peak_shear;
  return e;
}

std::string fmt(double v, int precision = 3) {
  if (!std::isfinite(v)) return "-";
  std::ostringstream o;
  o.precision(precision);
  o << v;
  return o.str();
}

std::vector<Variant> variants() {
  std::vector<Variant> v;
  const Variant d{"default", "default", "default: paper Newmark carry-over, 1 ms, 50 mm, direct/0.1 s, full"};
  v.push_back(d);
  auto add = [&](std::string name, std::string family, std::string label, auto change) {
    Variant x = d;
    x.name = std::move(name);
    x.family = std::move(family);
    x.label = std::move(label);
    change(x);
    v.push_back(x);
  };
  add("element_conventional", "element", "conventional one-point Timoshenko (s = 0)",
      [](Variant& x) { x.element = ElementChoice::conventional; });
  add("element_cubic_eb", "element", "cubic Euler-Bernoulli (reference element, elastic)",
      [](Variant& x) { x.element = ElementChoice::cubic_euler_bernoulli; });
  add("element_25mm", "mesh", "element length 25 mm", [](Variant& x) { x.element_length = 0.025; });
  add("element_100mm", "mesh", "element length 100 mm", [](Variant& x) { x.element_length = 0.1; });
  add("element_200mm", "mesh", "element length 200 mm", [](Variant& x) { x.element_length = 0.2; });
  add("grid_0.5", "mesh", "grid scale 0.5", [](Variant& x) { x.grid_scale = 0.5; });
  add("grid_2", "mesh", "grid scale 2", [](Variant& x) { x.grid_scale = 2.0; });
  add("dt_0.25ms", "dt", "dt 0.25 ms", [](Variant& x) { x.dt = 2.5e-4; });
  add("dt_0.5ms", "dt", "dt 0.5 ms", [](Variant& x) { x.dt = 5e-4; });
  add("dt_2ms", "dt", "dt 2 ms", [](Variant& x) { x.dt = 2e-3; });
  add("dt_5ms", "dt", "dt 5 ms", [](Variant& x) { x.dt = 5e-3; });
  add("average_acceleration", "integrator", "average acceleration, carry-over",
      [](Variant& x) { x.scheme = IntegratorKind::average_acceleration; });
  add("generalized_alpha", "integrator", "generalized-alpha 0.5, carry-over",
      [](Variant& x) { x.scheme = IntegratorKind::generalized_alpha; });
  add("paper_iterate", "integrator", "paper Newmark, iterated", [](Variant& x) { x.iterate = true; });
  add("average_acceleration_iterate", "integrator", "average acceleration, iterated", [](Variant& x) {
    x.scheme = IntegratorKind::average_acceleration;
    x.iterate = true;
  });
  add("generalized_alpha_iterate", "integrator", "generalized-alpha 0.5, iterated", [](Variant& x) {
    x.scheme = IntegratorKind::generalized_alpha;
    x.iterate = true;
  });
  add("cg", "solver", "CG (IC), refresh 0.1 s", [](Variant& x) { x.cg = true; });
  add("direct_refresh_1", "solver", "direct, refresh 1", [](Variant& x) { x.refresh = 1; });
  add("direct_refresh_20", "solver", "direct, refresh 20", [](Variant& x) { x.refresh = 20; });
  add("coarse", "fidelity", "fidelity coarse", [](Variant& x) { x.fidelity = Fidelity::coarse; });
  add("rigid", "fidelity", "fidelity rigid", [](Variant& x) { x.fidelity = Fidelity::rigid; });
  add("auto", "fidelity", "fidelity auto (desk full, cabinet rigid)", [](Variant& x) { x.fidelity = Fidelity::automatic; });
  return v;
}

Variant reference_variant(int refresh) {
  Variant r{"reference", "reference",
            "reference: dt 0.25 ms, grid scale 0.5, 25 mm, direct/" + std::to_string(refresh)};
  r.dt = 2.5e-4;
  r.grid_scale = 0.5;
  r.element_length = 0.025;
  r.refresh = refresh;
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  namespace fs = std::filesystem;
  std::string docs = "docs", only;
  double duration = 3.0, pga = 4.0;
  bool list = false, no_reference = false;
  int reference_refresh = 1;
  std::string table_from;  // a previous run's printed log: write the files from it, run nothing
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "%s needs a value\n", a.c_str());
        std::exit(2);
      }
      return argv[++i];
    };
    if (a == "--docs") docs = next();
    else if (a == "--duration") duration = std::stod(next());
    else if (a == "--pga") pga = std::stod(next());
    else if (a == "--only") only = "," + next() + ",";
    else if (a == "--list") list = true;
    else if (a == "--no-reference") no_reference = true;
    else if (a == "--reference-refresh") reference_refresh = std::stoi(next());
    else if (a == "--table-from") table_from = next();
    else {
      std::fprintf(stderr, "usage: speed_vs_error [--docs DIR] [--duration S] [--pga M_S2] [--only a,b] [--list] [--no-reference] [--reference-refresh N]\n");
      return 2;
    }
  }
  const auto all = variants();
  if (list) {
    for (const auto& v : all) std::printf("%-30s %-10s %s\n", v.name.c_str(), v.family.c_str(), v.label.c_str());
    return 0;
  }
  const bool partial = !only.empty();
  if (no_reference) {  // the variants' own results, no errors (to choose the scene)
    for (const auto& v : all) {
      if (partial && only.find("," + v.name + ",") == std::string::npos) continue;
      const Result r = run_variant(v, duration, pga);
      std::printf("%-30s %-9s %5d el %7.1f s  slide %.1f / %.1f mm  tilt %.2f / %.2f deg  peak |Q| %s N  imbalance %.3g\n",
                  v.name.c_str(), r.status.c_str(), r.elements, r.wall, 1e3 * r.slide[0], 1e3 * r.slide[1], r.tilt[0],
                  r.tilt[1], r.peak_shear ? fmt(*r.peak_shear).c_str() : "-", r.energy_imbalance);
      std::fflush(stdout);
    }
    return 0;
  }
  std::printf("speed vs error: %g s of synthetic 3-D motion (pga %g m/s^2), tall cabinet + desk\n", duration, pga);
  Variant refv = reference_variant(reference_refresh);
  struct Row {
    Variant v;
    Result r;
    Errors e;
  };
  std::vector<Row> logged;  // --table-from: the rows a previous run printed
  Result ref;
  if (!table_from.empty()) {
    // The lines this program prints: "  completed, N elements, W s wall, energy imbalance I; ..." for the
    // reference, "name status N el W s rms R mm peak P mm slide S mm tilt T deg shear Q % imbalance I"
    // for each variant ("-" for a value that does not exist). Variants the log lacks are left out.
    std::ifstream in(table_from);
    if (!in) {
      std::fprintf(stderr, "%s: cannot be read\n", table_from.c_str());
      return 2;
    }
    const auto value = [](const std::string& t) { return t == "-" ? NAN : std::stod(t); };
    const std::string logged_reference = "reference (" + refv.label.substr(0, refv.label.rfind('/') + 1);
    std::string line;
    while (std::getline(in, line)) {
      std::istringstream ls(line);
      std::string name, status;
      // "reference (<label>)...": the logged run's reference (its refresh interval), whatever
      // --reference-refresh says now.
      if (line.rfind(logged_reference, 0) == 0) {
        int refresh = 0;
        const char* first = line.data() + logged_reference.size();
        if (const auto [end, ec] = std::from_chars(first, line.data() + line.size(), refresh); ec == std::errc() && refresh > 0)
          refv = reference_variant(refresh);
        else
          std::fprintf(stderr, "%s: no refresh interval in \"%s\"; the reference's label says %d\n", table_from.c_str(),
                       line.c_str(), refv.refresh);
        continue;
      }
      if (line.rfind("  completed, ", 0) == 0) {
        std::sscanf(line.c_str(), "  completed, %d elements, %lf s wall, energy imbalance %lf", &ref.elements, &ref.wall,
                    &ref.energy_imbalance);
        continue;
      }
      if (!(ls >> name >> status)) continue;
      const auto v = std::find_if(all.begin(), all.end(), [&](const Variant& x) { return x.name == name; });
      if (v == all.end()) continue;
      // Tokens after the status: N el W s rms R mm peak P mm slide S mm tilt T deg shear Q % imbalance I.
      std::vector<std::string> w;
      for (std::string t; ls >> t;) w.push_back(t);
      if (w.size() < 21) continue;  // an unfinished line
      Row row{*v, {}, {}};
      row.r.status = status;
      row.r.elements = std::stoi(w[0]);
      row.r.wall = std::stod(w[2]);
      row.e.rms_mm = value(w[5]);
      row.e.peak_mm = value(w[8]);
      row.e.slide_mm = value(w[11]);
      row.e.tilt_deg = value(w[14]);
      row.e.shear_pct = value(w[17]);
      row.r.energy_imbalance = value(w[20]);
      logged.push_back(row);
    }
    std::printf("%zu variants from %s\n", logged.size(), table_from.c_str());
  } else {
    std::printf("reference (%s)...\n", refv.label.c_str());
    std::fflush(stdout);
    ref = run_variant(refv, duration, pga);
  }
  if (table_from.empty())
    std::printf("  %s, %d elements, %.1f s wall, energy imbalance %.3g; slide %.1f / %.1f mm, tilt %.2f / %.2f deg, "
              "peak |Q| %s N\n",
              ref.status.c_str(), ref.elements, ref.wall, ref.energy_imbalance, 1e3 * ref.slide[0], 1e3 * ref.slide[1],
              ref.tilt[0], ref.tilt[1], ref.peak_shear ? fmt(*ref.peak_shear).c_str() : "-");
  if (ref.status != "completed") {
    std::fprintf(stderr, "the reference did not complete: %s\n", ref.diagnosis.c_str());
    return 1;
  }
  std::vector<Row> rows = logged;
  for (const auto& v : all) {
    if (!table_from.empty()) break;
    if (partial && only.find("," + v.name + ",") == std::string::npos) continue;
    std::printf("%-30s ", v.name.c_str());
    std::fflush(stdout);
    Row row{v, run_variant(v, duration, pga), {}};
    row.e = compare(row.r, ref);
    std::printf("%-9s %5d el  %7.1f s  rms %7s mm  peak %7s mm  slide %7s mm  tilt %6s deg  shear %6s %%  imbalance %.3g\n",
                row.r.status.c_str(), row.r.elements, row.r.wall, fmt(row.e.rms_mm).c_str(), fmt(row.e.peak_mm).c_str(),
                fmt(row.e.slide_mm).c_str(), fmt(row.e.tilt_deg).c_str(), fmt(row.e.shear_pct).c_str(),
                row.r.energy_imbalance);
    if (!row.r.diagnosis.empty()) std::printf("    %s\n", row.r.diagnosis.c_str());
    std::fflush(stdout);
    rows.push_back(std::move(row));
  }
  if (partial) return 0;  // a subset: no files

  fs::create_directories(fs::path(docs) / "images");
  {
    std::ofstream csv(fs::path(docs) / "speed_vs_error.csv");
    csv << "name,family,label,element,dt_s,element_length_m,grid_scale,integrator,iterate,solver,refresh,fidelity,status,"
           "elements,steps,wall_s,marker_rms_mm,marker_peak_mm,slide_err_mm,tilt_err_deg,peak_shear_err_pct,"
           "energy_imbalance\n";
    auto line = [&](const Variant& v, const Result& r, const Errors& e) {
      const char* scheme = v.scheme == IntegratorKind::paper_newmark          ? "paper_newmark"
                           : v.scheme == IntegratorKind::average_acceleration ? "average_acceleration"
                                                                              : "generalized_alpha";
      const char* element = v.element == ElementChoice::conventional            ? "conventional"
                            : v.element == ElementChoice::cubic_euler_bernoulli ? "cubic_euler_bernoulli"
                                                                                : "asi_gauss";
      csv << v.name << ',' << v.family << ",\"" << v.label << "\"," << element << ',' << v.dt << ',' << v.element_length << ','
          << v.grid_scale << ',' << scheme << ',' << (v.iterate ? 1 : 0) << ',' << (v.cg ? "cg" : "direct") << ','
          << (v.refresh > 0 ? std::to_string(v.refresh) : std::string("0.1s")) << ',' << to_string(v.fidelity) << ',' << r.status << ',' << r.elements << ',' << r.steps << ','
          << r.wall << ',' << fmt(e.rms_mm, 6) << ',' << fmt(e.peak_mm, 6) << ',' << fmt(e.slide_mm, 6) << ','
          << fmt(e.tilt_deg, 6) << ',' << fmt(e.shear_pct, 6) << ',' << r.energy_imbalance << '\n';
    };
    line(refv, ref, Errors{0, 0, 0, 0, 0});
    for (const auto& row : rows) line(row.v, row.r, row.e);
  }
  {
    std::ofstream md(fs::path(docs) / "speed_vs_error.md");
    md << "| variant | family | elements | wall (s) | x default | marker RMS (mm) | marker peak (mm) | slide (mm) | "
          "tilt (deg) | peak shear (%) | energy imbalance |\n|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    double wall_default = 0;
    for (const auto& row : rows)
      if (row.v.name == "default") wall_default = row.r.wall;
    md << "| " << refv.label << " | reference | " << ref.elements << " | " << fmt(ref.wall) << " | "
       << (wall_default > 0 ? fmt(ref.wall / wall_default, 2) : "-") << " | 0 | 0 | 0 | 0 | 0 | "
       << fmt(ref.energy_imbalance, 2) << " |\n";
    for (const auto& row : rows)
      md << "| " << row.v.label << (row.r.status != "completed" ? " (" + row.r.status + ")" : "") << " | "
         << row.v.family << " | " << row.r.elements << " | " << fmt(row.r.wall) << " | "
         << (wall_default > 0 ? fmt(row.r.wall / wall_default, 2) : "-") << " | " << fmt(row.e.rms_mm) << " | "
         << fmt(row.e.peak_mm) << " | " << fmt(row.e.slide_mm) << " | " << fmt(row.e.tilt_deg, 2) << " | "
         << fmt(row.e.shear_pct) << " | " << fmt(row.r.energy_imbalance, 2) << " |\n";
  }
  {
    ScatterPlot p;
    p.title("Speed vs error: cabinet + desk, " + fmt(duration) + " s 3-D, pga " + fmt(pga))
        .xlabel("wall time (s, one thread)")
        .ylabel("marker displacement RMS error (mm)")
        .log_x()
        .log_y()
        .show_pareto_front();
    p.style().legend = LegendPos::bottom_right;  // the slow, inaccurate corner (top right) holds the iterated runs
    std::vector<std::string> names;
    for (const auto& row : rows)
      if (std::isfinite(row.e.rms_mm) && row.e.rms_mm > 0) {
        p.add(row.r.wall, row.e.rms_mm, row.v.name == "default" ? "default" : "", row.v.family);
        names.push_back(row.v.name);
      }
    p.save_png((fs::path(docs) / "images" / "speed_vs_error.png").string(), 900, 560);
    std::printf("Pareto front:");
    for (std::size_t i : p.front()) std::printf(" %s", names[i].c_str());
    std::printf("\n");
  }
  // How far the default is from the front: its wall time over the fastest variant that is at least as
  // accurate (marker RMS). Timing noise on this shared machine is a few per cent, so a ratio within
  // 1.05 means no variant is measurably better on both axes.
  for (const auto& d : rows) {
    if (d.v.name != "default" || !std::isfinite(d.e.rms_mm)) continue;
    const Row* best = nullptr;
    for (const auto& row : rows)
      if (row.v.name != "default" && std::isfinite(row.e.rms_mm) && row.e.rms_mm <= d.e.rms_mm &&
          (!best || row.r.wall < best->r.wall))
        best = &row;
    if (!best || best->r.wall >= d.r.wall)
      std::printf("the default is on the Pareto front\n");
    else
      std::printf("the default takes %.2f times the wall time of %s (RMS %.3g mm against %.3g mm)\n",
                  d.r.wall / best->r.wall, best->v.name.c_str(), best->e.rms_mm, d.e.rms_mm);
  }
  std::printf("wrote %s/speed_vs_error.csv, %s/speed_vs_error.md, %s/images/speed_vs_error.png\n", docs.c_str(),
              docs.c_str(), docs.c_str());
  return 0;
}
