#pragma once
// Files the tests write and read back: every test file goes to the build's scratch folder
// (FFEM_TEST_TMP, set per test group in tests/CMakeLists.txt), never next to the sources.
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace ffem_test {

// A path in the scratch folder, the folder created if needed.
inline std::string tmp(const std::string& name) {
  std::filesystem::create_directories(FFEM_TEST_TMP);
  return (std::filesystem::path(FFEM_TEST_TMP) / name).string();
}

// A whole file as bytes ("" when it cannot be read; the test's own checks then fail).
inline std::string slurp(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}

}  // namespace ffem_test
