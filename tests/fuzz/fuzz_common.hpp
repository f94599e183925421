#pragma once
// Shared by the libFuzzer harnesses (tests/fuzz, docs/fuzzing.md): the input as a file (the readers
// take paths), and a check whose failure is a finding (printed, then abort: libFuzzer keeps the input).
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

namespace ffem_fuzz {

// A folder of this process's own (under /dev/shm when it exists: no disk writes per input).
inline const std::string& scratch_dir() {
  static const std::string dir = [] {
    std::string tmpl = (access("/dev/shm", W_OK) == 0 ? "/dev/shm" : "/tmp") + std::string("/ffem_fuzz_XXXXXX");
    if (!mkdtemp(tmpl.data())) {
      std::perror("ffem_fuzz: mkdtemp");
      std::abort();
    }
    return tmpl;
  }();
  return dir;
}

// Writes the bytes to <scratch>/<name> (the name's extension picks a format where the reader asks it).
inline std::string write_input(const std::string& name, const std::uint8_t* data, std::size_t size) {
  const std::string path = scratch_dir() + "/" + name;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  out.close();
  if (!out) {
    std::fprintf(stderr, "ffem_fuzz: cannot write %s\n", path.c_str());
    std::abort();
  }
  return path;
}

// A broken promise of the code under test (not bad input): a finding.
[[noreturn]] inline void finding(const std::string& what) {
  std::fprintf(stderr, "\nFFEM FUZZ FINDING: %s\n", what.c_str());
  std::fflush(stderr);
  std::abort();
}
inline void check(bool ok, const std::string& what) {
  if (!ok) finding(what);
}

}  // namespace ffem_fuzz
