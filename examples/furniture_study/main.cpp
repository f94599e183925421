// furniture_study: runs a study (docs/study/studies.md): the realisations of a base scene over
// intensity levels, ground motions and seeded perturbations, with variants compared on the same
// realisations; writes realisations.csv, the statistics and summary.json into a results folder.
//
//   furniture_study STUDY.json [--workers N] [--out DIR] [--resume] [--overwrite] [--quiet]
//   furniture_study STUDY.json --scene-of RUN [--out FILE]     the scene of one run, for furniture_quake
//   mpirun -n K furniture_study STUDY.json ...                  the same, spread over K ranks
//
// Exit codes: 0 every run completed, 1 bad input (a study, scene or record file), 2 usage, 3 some runs
// did not complete (diverged or failed: the statistics count the others), 4 no run completed, 130
// interrupted (the study stops cleanly: finished runs are kept, --resume continues it).
#include <furniture_fem/study/realisation.hpp>
#include <furniture_fem/study/runner.hpp>

#include <CLI/CLI.hpp>

#include <atomic>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <string>
#include <thread>

#include "../common/folder_option.hpp"
#include "../common/interrupt.hpp"
#ifdef FFEM_WITH_MPI
#include "mpi_handout.hpp"
#endif

namespace {
using namespace furniture_fem;

enum ExitCode : int {
  exit_done = 0,
  exit_bad_input = 1,
  exit_usage = 2,
  exit_not_all_completed = 3,  // as furniture_quake's 3 (diverged): the outputs are written
  exit_none_completed = 4,
  exit_interrupted = ffem_examples::exit_interrupted
};

std::atomic<bool>& g_stop = ffem_examples::interrupt_requested;  // Ctrl-C (../common/interrupt.hpp)
using ffem_examples::install_interrupt_handlers;

struct CommandLine {
  std::string study, out_dir;
  long scene_of = -1;
  StudyOptions opt;
};

void define_options(CLI::App& app, CommandLine& cl) {
  app.set_version_flag("--version", std::string("furniture_study (furniture_fem) ") + version_string);
  app.add_option("study", cl.study, "study file (JSON, docs/study/studies.md)")->required()->type_name("FILE");
  app.add_option("--workers", cl.opt.workers, "worker threads on this machine (default: one per hardware thread; "
                                              "under MPI: one per rank)")
      ->type_name("N")->check(CLI::Range(1, 4096));
  app.add_option("--out", cl.out_dir, "results folder (default: study_<name>); with --scene-of: the scene file to write")
      ->type_name("DIR")->check(ffem_examples::folder_name("leave --out out for the default"));
  app.add_flag("--resume", cl.opt.resume, "continue a stopped or killed study in the folder, skipping finished runs");
  app.add_flag("--overwrite", cl.opt.overwrite, "replace a previous study's results in the folder (other files are kept)");
  app.add_flag_callback("--quiet", [&cl] { cl.opt.progress = false; }, "no progress line");
  app.add_option("--scene-of", cl.scene_of, "write the scene of run RUN (realisations.csv's `run`) and stop")
      ->type_name("RUN")->check(CLI::NonNegativeNumber);
  app.footer("Exit codes: 0 every run completed, 1 bad input, 2 usage, 3 some runs did not complete (diverged or failed),\n"
             "4 no run completed, 130 interrupted (finished runs are kept; --resume continues).");
}

int write_scene_of(const StudySpec& study, const CommandLine& cl) {
  if (cl.scene_of >= study.num_runs())
    throw InputError("command line", 0, "--scene-of", "the study has runs 0 to " + std::to_string(study.num_runs() - 1) +
                                                          " (got " + std::to_string(cl.scene_of) + ")");
  const long realisation = cl.scene_of / study.num_variants();
  const int variant = static_cast<int>(cl.scene_of % study.num_variants());
  nlohmann::json scene = realisation_scene_json(study, realisation_parameters(study, realisation), variant);
  const std::string path = cl.out_dir.empty() ? "run_" + std::to_string(cl.scene_of) + "_scene.json" : cl.out_dir;
  std::ofstream(path) << scene.dump(2) << "\n";
  std::printf("run %ld (realisation %ld, variant %s): scene written to %s\n", cl.scene_of, realisation,
              study.variant_name(variant).c_str(), path.c_str());
  if (!detail::study_scene_dir(study).empty())
    std::printf("  relative paths in it are relative to %s\n", detail::study_scene_dir(study).c_str());
  return exit_done;
}

// The last word: the summary line, and when runs did not complete, why (the first one's reason and
// how many share it) and an exit code that says so.
int report(const std::string& status, const StudyFolder& folder, double wall) {
  std::printf("%s: %s, %ld of %ld runs done (%ld not completed), %.1f s; results in %s\n", folder.study().name.c_str(),
              status.c_str(), folder.done(), folder.study().num_runs(), folder.failed(), wall, folder.dir().c_str());
  if (status == "stopped") return exit_interrupted;
  const StudyFailures f = study_failures(folder.results());
  if (f.not_completed == 0) return exit_done;
  const std::string why = folder.not_completed_text(f);
  if (f.completed == 0) {
    std::fprintf(stderr, "error: study '%s': no run completed (%ld of %ld did not); %s\n", folder.study().name.c_str(),
                 f.not_completed, folder.study().num_runs(), why.c_str());
    return exit_none_completed;
  }
  std::fprintf(stderr, "furniture_study: %ld of %ld runs did not complete (the statistics count the %ld that did); %s\n",
               f.not_completed, folder.study().num_runs(), f.completed, why.c_str());
  return exit_not_all_completed;
}

int run_here(const StudySpec& study, CommandLine cl) {
  cl.opt.out_dir = cl.out_dir;
  const auto t0 = std::chrono::steady_clock::now();
  StudyFolder folder(study, cl.opt);
  StudyTiming timing;
  timing.workers = cl.opt.workers > 0 ? cl.opt.workers : std::max(1u, std::thread::hardware_concurrency());
  if (folder.resumed() > 0) std::fprintf(stderr, "resuming: %ld runs already done\n", folder.resumed());
  const bool all = run_local(folder, folder.pending(), timing.workers, &g_stop, cl.opt.progress);
  timing.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const std::string status = folder.status(all);
  folder.finish(status, timing);
  return report(status, folder, timing.wall_seconds);
}

#ifdef FFEM_WITH_MPI
// Rank 0 keeps the folder and hands out the runs; the other ranks run what they are given. Errors on
// rank 0 (a bad study, a folder refused) abort every rank with the message.
int run_mpi(const StudySpec& study, CommandLine cl, int rank, int ranks) {
  if (rank != 0) {
    mpi_study::work(study, g_stop);
    return exit_done;
  }
  cl.opt.out_dir = cl.out_dir;
  const auto t0 = std::chrono::steady_clock::now();
  StudyFolder folder(study, cl.opt);
  StudyTiming timing;
  timing.ranks = ranks;
  timing.workers = cl.opt.workers > 0 ? cl.opt.workers : 1;
  if (folder.resumed() > 0) std::fprintf(stderr, "resuming: %ld runs already done\n", folder.resumed());
  const bool all = mpi_study::serve(folder, folder.pending(), timing.workers, g_stop, cl.opt.progress, timing);
  timing.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const std::string status = folder.status(all);
  folder.finish(status, timing);
  return report(status, folder, timing.wall_seconds);
}
#endif

int run(const CommandLine& cl, int rank, int ranks) {
  const StudySpec study = parse_study(cl.study);
  if (cl.scene_of >= 0) return rank == 0 ? write_scene_of(study, cl) : exit_done;
  if (rank == 0) std::cerr << "furniture_fem " << version_string << ": study " << study.name << ", " << study.num_runs()
                           << " runs (" << study.num_realisations() << " realisations x " << study.num_variants()
                           << " variants)\n" << study_size_line(study) << "\n";
#ifdef FFEM_WITH_MPI
  if (ranks > 1) return run_mpi(study, cl, rank, ranks);
#endif
  return run_here(study, cl);
}
}  // namespace

int main(int argc, char** argv) {
  install_interrupt_handlers();
  int rank = 0, ranks = 1;
#ifdef FFEM_WITH_MPI
  int provided = 0;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  const auto finish = [](int code) {
    MPI_Finalize();
    return code;
  };
#else
  const auto finish = [](int code) { return code; };
#endif
  CLI::App app("Runs a study: many realisations of a furniture scene, and their statistics.", "furniture_study");
  CommandLine cl;
  define_options(app, cl);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = rank == 0 ? app.exit(e) : (e.get_exit_code() == 0 ? 0 : 1);
    return finish(code == 0 ? exit_done : exit_usage);
  }
  try {
    return finish(run(cl, rank, ranks));
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
#ifdef FFEM_WITH_MPI
    if (ranks > 1) MPI_Abort(MPI_COMM_WORLD, exit_bad_input);
#endif
    return finish(exit_bad_input);
  }
}
