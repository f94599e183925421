#pragma once
// Files the tests write and read back: every test file goes to the build's scratch folder
// (FFEM_TEST_TMP, set per test group in tests/CMakeLists.txt), never next to the sources.
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
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

// The text of docs/PAGE in the repository ("" when it cannot be read).
inline std::string docs_page(const std::string& page) {
  // __FILE__ may be relative to the build folder of the tests, which is where the executable sits.
  std::filesystem::path here(__FILE__);
  if (here.is_relative()) here = std::filesystem::read_symlink("/proc/self/exe").parent_path() / here;
  return slurp((here.parent_path() / "../../docs" / page).string());
}

// The text between "<!-- begin: NAME -->\n" and "<!-- end: NAME -->" in docs/PAGE, a block a test
// compares with the code that generates it; nothing when the page or a marker is missing.
inline std::optional<std::string> docs_block(const std::string& page, const std::string& name) {
  const std::string text = docs_page(page);
  const std::string begin = "<!-- begin: " + name + " -->\n", end = "<!-- end: " + name + " -->";
  const auto a = text.find(begin), b = text.find(end);
  if (a == std::string::npos || b == std::string::npos || b < a) return std::nullopt;
  return text.substr(a + begin.size(), b - a - begin.size());
}

}  // namespace ffem_test
