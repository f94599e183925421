// libFuzzer harness for one ground-motion record reader (excitation/excitation.hpp), chosen at build time
// by FFEM_FUZZ_FORMAT (1 PEER AT2, 2 K-NET, 3 JMA CSV, 4 columns): the input is the file; the format's
// reader and read_record's detection must give a plausible Record (finite samples, dt in range) or an
// InputError, and a Record read must come back unchanged through write_columns / read_columns.
#include <cmath>
#include <cstdint>
#include <string>

#include <furniture_fem/excitation/excitation.hpp>

#include "fuzz_common.hpp"

#ifndef FFEM_FUZZ_FORMAT
#error "define FFEM_FUZZ_FORMAT (1 AT2, 2 K-NET, 3 JMA CSV, 4 columns)"
#endif

namespace {

using namespace furniture_fem;

// What every reader promises of a Record it returns.
void check_record(const Record& r, const std::string& how) {
  ffem_fuzz::check(r.dt >= 1e-5 && r.dt <= 1.0, how + ": dt out of [1e-5, 1] s: " + std::to_string(r.dt));
  ffem_fuzz::check(r.acc.size() >= 2, how + ": fewer than 2 samples");
  ffem_fuzz::check(std::isfinite(r.t0), how + ": t0 not finite");
  for (std::size_t i = 0; i < r.acc.size(); ++i)
    ffem_fuzz::check(std::isfinite(r.acc[i]), how + ": sample " + std::to_string(i + 1) + " not finite");
}

// write_columns promises that read_columns gives the record back: the samples and t0 exactly, dt
// to rounding (it is the mean step of the written times).
void round_trip(const Record& r, const std::string& how) {
  const std::string path = ffem_fuzz::scratch_dir() + "/round_trip.txt";
  Record back;
  try {
    write_columns(path, r);
    back = read_columns(path);
  } catch (const InputError& e) {
    ffem_fuzz::finding(how + ": the written record cannot be read back: " + e.what());
  }
  ffem_fuzz::check(back.acc == r.acc, how + ": round trip changed the samples");
  ffem_fuzz::check(back.t0 == r.t0, how + ": round trip changed t0");
  ffem_fuzz::check(std::abs(back.dt - r.dt) <= 1e-9 * r.dt, how + ": round trip changed dt");
}

void accept(const Record& r, const std::string& how) {
  check_record(r, how);
  round_trip(r, how);
}

template <class F>
void attempt(F&& f) {
  try {
    f();
  } catch (const InputError&) {  // the documented answer to bad input; anything else is a finding
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > (1u << 20)) return 0;
#if FFEM_FUZZ_FORMAT == 1
  const std::string path = ffem_fuzz::write_input("record.AT2", data, size);
  attempt([&] { accept(read_peer_at2(path), "read_peer_at2"); });
#elif FFEM_FUZZ_FORMAT == 2
  const std::string path = ffem_fuzz::write_input("record.NS", data, size);
  attempt([&] { accept(read_knet(path, true), "read_knet"); });
  attempt([&] { accept(read_knet(path, false), "read_knet (mean kept)"); });
#elif FFEM_FUZZ_FORMAT == 3
  const std::string path = ffem_fuzz::write_input("record.csv", data, size);
  attempt([&] {
    const auto c = read_jma_csv(path);
    for (int k = 0; k < 3; ++k) accept(c[static_cast<std::size_t>(k)], "read_jma_csv component " + std::to_string(k));
  });
#elif FFEM_FUZZ_FORMAT == 4
  const std::string path = ffem_fuzz::write_input("record.txt", data, size);
  attempt([&] { accept(read_columns(path), "read_columns (time, value)"); });
  ReadOptions values;
  values.dt = 0.01;
  values.unit = Unit::g;
  attempt([&] { accept(read_columns(path, values), "read_columns (values, dt 0.01, g)"); });
  ReadOptions skip;
  skip.skip_lines = 1;
  skip.unit = Unit::gal;
  attempt([&] { accept(read_columns(path, skip), "read_columns (skip 1 line, gal)"); });
#endif
  // The format detection of read_record on the same bytes.
  attempt([&] { accept(read_record(path), "read_record (automatic)"); });
  return 0;
}
