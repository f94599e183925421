// One writer per results folder (io/folder_lock.hpp, scene/results_folder.hpp; issue 51): a second lock
// on a folder is refused, naming the holder's process, whether the holder is this process or another;
// the kernel lets go of a killed holder's lock (no stale lock); the lock file is none of a run's results.
#include <catch2/catch.hpp>

#include <furniture_fem/scene/results_folder.hpp>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

using namespace furniture_fem;

namespace folder_lock_tests {  // this file's own names (its group compiles files in batches)
namespace fs = std::filesystem;

namespace {

std::string fresh_dir(const std::string& name) {
  const fs::path p = fs::path(FFEM_TEST_TMP) / "folder_lock" / name;
  fs::remove_all(p);
  fs::create_directories(p.parent_path());
  return p.string();
}

// A child process that takes the folder's lock, says so through a pipe and waits to be killed.
class LockingChild {
 public:
  explicit LockingChild(const std::string& dir) {
    int fds[2];
    REQUIRE(pipe(fds) == 0);
    pid_ = fork();
    REQUIRE(pid_ >= 0);
    if (pid_ == 0) {
      close(fds[0]);
      char ok = 0;
      try {
        const FolderLock lock(dir);
        ok = 1;
        [[maybe_unused]] const ssize_t n = write(fds[1], &ok, 1);
        for (;;) pause();
      } catch (...) {
      }
      [[maybe_unused]] const ssize_t n = write(fds[1], &ok, 1);
      _exit(1);
    }
    close(fds[1]);
    char ok = 0;
    REQUIRE(read(fds[0], &ok, 1) == 1);
    close(fds[0]);
    REQUIRE(ok == 1);
  }
  ~LockingChild() { kill_now(); }
  long pid() const { return pid_; }
  // SIGKILL: the child runs no destructor, as a run killed with kill -9.
  void kill_now() {
    if (pid_ <= 0) return;
    kill(pid_, SIGKILL);
    int status = 0;
    waitpid(pid_, &status, 0);
    pid_ = -1;
  }

 private:
  pid_t pid_ = -1;
};

}  // namespace

TEST_CASE("a second lock on a results folder is refused, naming the folder and the holder",
          "[results_folder][lock]") {
  const std::string dir = fresh_dir("same_process");
  const FolderLock first(dir);
  CHECK(fs::is_directory(dir));
  const std::string pid = std::to_string(static_cast<long>(getpid()));
  // flock's lock belongs to the open file: a second open in this process does not share it.
  REQUIRE_THROWS_AS(FolderLock(dir), InputError);
  REQUIRE_THROWS_WITH(FolderLock(dir), Catch::Contains("results folder '" + dir + "'") &&
                                           Catch::Contains("in use by process " + pid) && Catch::Contains("--out"));
  CHECK(folder_lock_holder(dir) == getpid());
  REQUIRE_THROWS_WITH(refuse_if_locked(dir), Catch::Contains("in use by process " + pid));
}

TEST_CASE("a lock let go is taken again, and its file no longer names a process", "[results_folder][lock]") {
  const std::string dir = fresh_dir("again");
  { const FolderLock first(dir); }
  CHECK(folder_lock_holder(dir) == 0);
  CHECK(fs::file_size(fs::path(dir) / folder_lock_file) == 0);
  CHECK_NOTHROW(refuse_if_locked(dir));
  const FolderLock second(dir);
  CHECK(folder_lock_holder(dir) == getpid());
}

TEST_CASE("another process's lock is refused with its process id, and a killed holder leaves no lock",
          "[results_folder][lock]") {
  const std::string dir = fresh_dir("two_processes");
  LockingChild child(dir);
  CHECK(folder_lock_holder(dir) == child.pid());
  REQUIRE_THROWS_WITH(FolderLock(dir), Catch::Contains("results folder '" + dir + "'") &&
                                           Catch::Contains("in use by process " + std::to_string(child.pid())));
  REQUIRE_THROWS_AS(refuse_if_locked(dir), InputError);
  child.kill_now();
  CHECK(folder_lock_holder(dir) == 0);
  const FolderLock mine(dir);
  CHECK(folder_lock_holder(dir) == getpid());
}

TEST_CASE("the lock file is none of a run's results", "[results_folder][lock]") {
  CHECK_FALSE(results_file(folder_lock_file));
  SECTION("a folder holding only the lock file is empty to a run") {
    const std::string dir = fresh_dir("only_lock");
    { const FolderLock lock(dir); }
    CHECK_NOTHROW(check_results_folder(dir, false));
    CHECK(detail::empty_but_lock(dir));
  }
  SECTION("--overwrite removes a run's results, never the lock held while it does") {
    const std::string dir = fresh_dir("overwrite");
    const FolderLock lock(dir);
    std::ofstream(dir + "/run.json") << R"({"program": "furniture_fem", "status": "done"})";
    std::ofstream(dir + "/energy.csv") << "t\n0\n";
    const auto removed = prepare_results_folder(dir, true);
    CHECK(removed == std::vector<std::string>{"energy.csv", "run.json"});
    CHECK(fs::exists(fs::path(dir) / folder_lock_file));
    CHECK(folder_lock_holder(dir) == getpid());
  }
  SECTION("a folder with the user's files and a lock file is still the user's") {
    const std::string dir = fresh_dir("foreign");
    fs::create_directories(dir);
    std::ofstream(dir + "/notes.txt") << "mine\n";
    { const FolderLock lock(dir); }
    REQUIRE_THROWS_WITH(check_results_folder(dir, false), Catch::Contains("not empty"));
  }
}

}  // namespace folder_lock_tests
