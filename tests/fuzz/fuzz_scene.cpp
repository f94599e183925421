// libFuzzer harness for scene files (scene/reader.hpp, validation.hpp, writer.hpp): the input is the
// scene file. parse_scene gives a SceneSpec or an InputError; validate() gives nothing or an InputError;
// a scene read, written (write_scene) and read again must give the same JSON and the same verdict.
#include <cstdint>
#include <string>

#include <furniture_fem/scene/reader.hpp>
#include <furniture_fem/scene/validation.hpp>
#include <furniture_fem/scene/writer.hpp>

#include "fuzz_common.hpp"

namespace {
using namespace furniture_fem;

// The verdict of validate(): "" or the message's text after the file name (which differs).
std::string verdict(const SceneSpec& s) {
  try {
    validate(s);
    return "";
  } catch (const InputError& e) {
    return e.field() + ": " + std::to_string(e.line());
  }
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > (1u << 20)) return 0;
  const std::string path = ffem_fuzz::write_input("scene.json", data, size);
  SceneSpec s;
  try {
    s = parse_scene(path);
  } catch (const InputError&) {  // the documented answer to bad input; anything else is a finding
    return 0;
  }
  const std::string first_verdict = verdict(s);
  const nlohmann::json j1 = to_json(s);
  const std::string again = ffem_fuzz::scratch_dir() + "/round_trip.json";
  SceneSpec s2;
  try {
    write_scene(s, again);
    s2 = parse_scene(again);
  } catch (const InputError& e) {
    ffem_fuzz::finding(std::string("the written scene cannot be read back: ") + e.what());
  }
  const nlohmann::json j2 = to_json(s2);
  if (j1 != j2)
    ffem_fuzz::finding("round trip changed the scene:\n--- written\n" + j1.dump(1) + "\n--- read back and written\n" + j2.dump(1));
  ffem_fuzz::check(j1.dump() == j2.dump(), "round trip: the same JSON dumps differently");
  const std::string second_verdict = verdict(s2);
  ffem_fuzz::check(first_verdict == second_verdict,
                   "validate() changed its verdict after the round trip: '" + first_verdict + "' then '" + second_verdict + "'");
  return 0;
}
