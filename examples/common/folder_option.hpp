#pragma once
// The check of a folder given on the example programs' command lines (furniture_quake's --out, --resume
// and --records, furniture_study's --out): an empty name would fall back silently to the default folder,
// and a control character makes a name no one can type (the scene's outputs.folder refuses both too).
#include <CLI/CLI.hpp>

#include <algorithm>
#include <string>

namespace ffem_examples {

// `if_empty`: what to do instead, said when the name is empty.
inline CLI::Validator folder_name(std::string if_empty) {
  return CLI::Validator(
      [if_empty](std::string& w) -> std::string {
        if (w.empty()) return "must not be empty (" + if_empty + ")";
        if (std::any_of(w.begin(), w.end(), [](unsigned char c) { return c < 0x20 || c == 0x7f; }))
          return "must not hold control characters (a newline, a tab...)";
        return {};
      },
      "", "folder");
}

}  // namespace ffem_examples
