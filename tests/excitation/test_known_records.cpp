// Where the real records come from: a missing record the examples name says where to get it, an
// unknown name gets the bare message, and FFEM_RECORDS moves the default folder.
#include <catch2/catch.hpp>

#include <cstdlib>
#include <string>

#include <furniture_fem/excitation/known_records.hpp>

using namespace furniture_fem;

namespace known_records_tests {  // this file's own names (its group compiles files in batches)

TEST_CASE("a missing record the examples name says where to get it", "[records]") {
  const std::string ns = "/nowhere/jma_kobe_1995_NS_PEER_RSN1106_KJM000.AT2";
  const std::string msg = record_not_found(ns);
  CHECK(msg.rfind("record file not found: \"" + ns + "\"; get it from the PEER NGA-West2 database", 0) == 0);
  CHECK(msg.find("RSN1106_KOBE_KJM000.AT2") != std::string::npos);  // the name PEER gives it
  CHECK(msg.find("save it as jma_kobe_1995_NS_PEER_RSN1106_KJM000.AT2") != std::string::npos);
  CHECK(msg.find("FFEM_RECORDS=DIR") != std::string::npos);
  // Each component names its own PEER file.
  CHECK(where_to_get_record("jma_kobe_1995_UD_PEER_RSN1106_KJM-UP.AT2").find("RSN1106_KOBE_KJM-UP.AT2") != std::string::npos);
  CHECK(where_to_get_record("a/b/elcentro_1940_NS_gal_dt0.02.txt").find("341.7 gal") != std::string::npos);
  CHECK(where_to_get_record("hachinohe_1968_NS_gal_dt0.01.txt").find("dt 0.01 s") != std::string::npos);
}

TEST_CASE("a record of the user's own gets the bare message", "[records]") {
  CHECK(where_to_get_record("/data/my_record.AT2").empty());
  // The name must match whole: a known name inside a longer one is the user's own file.
  CHECK(where_to_get_record("old_jma_kobe_1995_NS_PEER_RSN1106_KJM000.AT2").empty());
  CHECK(record_not_found("my.AT2") == "record file not found: \"my.AT2\"");
}

TEST_CASE("FFEM_RECORDS sets the default records folder", "[records]") {
  const char* before = std::getenv(records_dir_variable);
  const std::string saved = before ? before : "";
  ::setenv(records_dir_variable, "/srv/records", 1);
  CHECK(default_records_dir() == "/srv/records");
  ::setenv(records_dir_variable, "", 1);  // empty: as if not set
  CHECK(default_records_dir() == "../shared/ground_motions");
  ::unsetenv(records_dir_variable);
  CHECK(default_records_dir() == "../shared/ground_motions");
  if (before) ::setenv(records_dir_variable, saved.c_str(), 1);
}

}  // namespace known_records_tests
