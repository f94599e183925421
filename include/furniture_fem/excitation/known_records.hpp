#pragma once
// furniture_fem/excitation/known_records.hpp: the real records the paper's configurations and the
// examples name, and where a user gets them (docs/excitation/ground_motions.md, "Getting the records").
//
//   default_records_dir()        $FFEM_RECORDS when set and not empty, else "../shared/ground_motions"
//   where_to_get_record(path)    for a known file name: the line that says where to download it; else ""
//   record_not_found(path)       'record file not found: "<path>"', and where to get it when known
//
// The repository holds no record (their terms of use are the databases'); a missing one is named with
// where it comes from instead of a bare "not found".
#include <array>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <string_view>

namespace furniture_fem {

inline constexpr const char* records_dir_variable = "FFEM_RECORDS";

// Where the paper's configurations (configuration(k)) and furniture_quake --config look for records.
inline std::string default_records_dir() {
  const char* dir = std::getenv(records_dir_variable);
  return dir && *dir ? std::string(dir) : std::string("../shared/ground_motions");
}

namespace detail {

struct KnownRecord {
  std::string_view file;  // the name the examples expect
  std::string_view from;  // where to download it (after "get it from ")
};

inline constexpr std::array<KnownRecord, 6> known_records{{
    {"jma_kobe_1995_NS_PEER_RSN1106_KJM000.AT2",
     "the PEER NGA-West2 database (https://ngawest2.berkeley.edu, free account): record RSN1106 (Kobe, Japan, "
     "1995, station KJMA), file RSN1106_KOBE_KJM000.AT2"},
    {"jma_kobe_1995_EW_PEER_RSN1106_KJM090.AT2",
     "the PEER NGA-West2 database (https://ngawest2.berkeley.edu, free account): record RSN1106 (Kobe, Japan, "
     "1995, station KJMA), file RSN1106_KOBE_KJM090.AT2"},
    {"jma_kobe_1995_UD_PEER_RSN1106_KJM-UP.AT2",
     "the PEER NGA-West2 database (https://ngawest2.berkeley.edu, free account): record RSN1106 (Kobe, Japan, "
     "1995, station KJMA), file RSN1106_KOBE_KJM-UP.AT2"},
    {"jma_kobe_1995_NS_unprocessed_gal_dt0.02.txt",
     "JMA's strong-motion records of the 1995 Hyogo-ken Nanbu earthquake (station Kobe, NS, unprocessed), "
     "two columns (time in s, acceleration in gal) at dt 0.02 s"},
    {"elcentro_1940_NS_gal_dt0.02.txt",
     "the standard waves of Japanese building design (El Centro 1940 NS, 341.7 gal), two columns (time in s, "
     "acceleration in gal) at dt 0.02 s"},
    {"hachinohe_1968_NS_gal_dt0.01.txt",
     "the standard waves of Japanese building design (Hachinohe 1968 NS, 225 gal), two columns (time in s, "
     "acceleration in gal) at dt 0.01 s"},
}};

}  // namespace detail

// For a file name the examples use: "get it from <where>, save it as <name> in one folder ...", else "".
inline std::string where_to_get_record(const std::string& path) {
  const std::string name = std::filesystem::path(path).filename().string();
  for (const auto& r : detail::known_records)
    if (r.file == name)
      return "get it from " + std::string(r.from) + ", save it as " + name +
             " in one folder with the other records, and give that folder (--records DIR, or " +
             records_dir_variable + "=DIR); docs/excitation/ground_motions.md, \"Getting the records\"";
  return "";
}

inline std::string record_not_found(const std::string& path) {
  const std::string where = where_to_get_record(path);
  return "record file not found: \"" + path + "\"" + (where.empty() ? "" : "; " + where);
}

}  // namespace furniture_fem
