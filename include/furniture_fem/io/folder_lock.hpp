#pragma once
// furniture_fem/io/folder_lock.hpp: one writer per results folder (docs/io/output.md, "One run per
// folder").
//
//   FolderLock lock(dir)        creates the folder if it is missing and takes its lock file,
//                               <dir>/.furniture_fem.lock, for the object's life; refused with an
//                               InputError naming the folder and the holder's process id
//   folder_lock_holder(dir)     the process holding the folder's lock (0: none); creates nothing
//   refuse_if_locked(dir)       the same InputError as FolderLock when another holds it; creates nothing
//   detail::empty_but_lock(dir) the folder holds nothing but its lock file
//
// The lock is flock(2)'s: the kernel drops it when its holder ends, however it ends (SIGKILL included),
// so a killed run never leaves a stale lock. It belongs to the open file, not to the process: a second
// FolderLock on the same folder in the same process is refused too (fcntl's locks would let it pass).
// The holder writes its process id into the file, and empties it when it lets go. The file itself
// stays: removing it would race with a process that has just opened it (and would then lock a file
// no one else sees).
#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <system_error>
#include <utility>

#include "../core/errors.hpp"

namespace furniture_fem {

inline constexpr const char* folder_lock_file = ".furniture_fem.lock";

namespace detail {

inline std::string folder_lock_path(const std::string& dir) { return (std::filesystem::path(dir) / folder_lock_file).string(); }

// The process id written in a lock file (0: none written yet, or not a number).
inline long read_lock_pid(int fd) {
  char buf[32] = {};
  const ssize_t n = pread(fd, buf, sizeof buf - 1, 0);
  if (n <= 0) return 0;
  const long pid = std::strtol(buf, nullptr, 10);
  return pid > 0 ? pid : 0;
}

// Empty, or holding nothing but the lock file (a folder whose run ended before writing anything).
inline bool empty_but_lock(const std::filesystem::path& dir) {
  std::error_code ec;
  for (auto it = std::filesystem::directory_iterator(dir, ec); !ec && it != std::filesystem::directory_iterator();
       it.increment(ec))
    if (it->path().filename() != folder_lock_file) return false;
  return !ec;
}

[[noreturn]] inline void throw_folder_in_use(const std::string& dir, long pid) {
  const std::string who = pid > 0 ? "process " + std::to_string(pid) : std::string("another process");
  throw InputError("results folder '" + dir + "' is in use by " + who +
                   " (another furniture_quake or furniture_study run, or a program using furniture_fem, writes "
                   "there); wait for it to end or use another folder (--out DIR)");
}

// flock without blocking, retried when a signal interrupts it; false when another holds the lock.
inline bool try_flock(int fd, int how, const std::string& dir) {
  int rc;
  while ((rc = flock(fd, how | LOCK_NB)) != 0 && errno == EINTR) {
  }
  if (rc == 0) return true;
  if (errno == EWOULDBLOCK) return false;
  throw OutputError("results folder '" + dir + "': cannot lock '" + folder_lock_path(dir) + "': " + std::strerror(errno));
}

}  // namespace detail

// The process holding the folder's lock, 0 if none does (or the folder has no lock file). A holder that
// has not yet written its id reads as -1.
inline long folder_lock_holder(const std::string& dir) {
  const int fd = open(detail::folder_lock_path(dir).c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return 0;
  // A shared lock conflicts with a holder's exclusive one and with nothing else.
  bool held = false;
  try {
    held = !detail::try_flock(fd, LOCK_SH, dir);
  } catch (...) {
    close(fd);
    throw;
  }
  const long pid = held ? detail::read_lock_pid(fd) : 0;
  close(fd);  // drops the shared lock
  return held && pid == 0 ? -1 : pid;
}

// Refuses, naming the folder and the holder, a folder another run or study is writing into.
inline void refuse_if_locked(const std::string& dir) {
  if (const long pid = folder_lock_holder(dir); pid != 0) detail::throw_folder_in_use(dir, pid);
}

class FolderLock {
 public:
  explicit FolderLock(std::string dir) : dir_(std::move(dir)) {
    std::error_code ec;
    std::filesystem::create_directories(dir_, ec);
    if (ec) throw OutputError("results folder '" + dir_ + "': cannot create it: " + ec.message());
    const std::string path = detail::folder_lock_path(dir_);
    // O_CLOEXEC: a program this one starts must not inherit the lock and hold it after this one ends.
    fd_ = open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd_ < 0) throw OutputError("results folder '" + dir_ + "': cannot open '" + path + "': " + std::strerror(errno));
    try {
      if (!detail::try_flock(fd_, LOCK_EX, dir_)) detail::throw_folder_in_use(dir_, detail::read_lock_pid(fd_));
    } catch (...) {
      close(fd_);
      throw;
    }
    // Only for the message of a refused process: a failed write does not stop the run.
    const std::string pid = std::to_string(static_cast<long>(getpid())) + "\n";
    [[maybe_unused]] const bool written = ftruncate(fd_, 0) == 0 && pwrite(fd_, pid.data(), pid.size(), 0) > 0;
  }
  FolderLock(FolderLock&& o) noexcept : dir_(std::move(o.dir_)), fd_(std::exchange(o.fd_, -1)) {}
  FolderLock& operator=(FolderLock&&) = delete;
  FolderLock(const FolderLock&) = delete;
  FolderLock& operator=(const FolderLock&) = delete;
  ~FolderLock() {
    if (fd_ < 0) return;
    // Emptied first: the id of a process that no longer holds the lock would mislead.
    [[maybe_unused]] const bool emptied = ftruncate(fd_, 0) == 0;
    close(fd_);  // releases the lock
  }
  const std::string& dir() const { return dir_; }

 private:
  std::string dir_;
  int fd_ = -1;
};

}  // namespace furniture_fem
