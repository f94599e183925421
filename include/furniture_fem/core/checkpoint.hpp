#pragma once
// furniture_fem/core/checkpoint.hpp: a simulation's state as bytes, to stop a run and go on with it later
// (docs/core/checkpoint.md).
//
//   StateWriter w;  sim.save_state(w);          w.bytes(): everything the next steps read
//   StateReader r(bytes, "run/checkpoint.bin");  sim.load_state(r);   r.finish();
//
// One function per class lists its state, `transfer_state(Self& self, Archive& ar)`, called with a
// const object and a StateWriter to save and with a mutable one and a StateReader to load, so saving
// and loading cannot list different members. Numbers are stored as their bytes: a loaded state is the
// saved one to the bit, and a run resumed from it gives the results of the run that was never stopped.
// A reader checks every size against what is left of the bytes and names the file when they do not fit
// (a truncated or foreign file), before it allocates.
#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <map>
#include <string>
#include <string_view>
#include <type_traits>
#include <unordered_map>
#include <utility>
#include <vector>

#include "errors.hpp"

namespace furniture_fem {

// Types stored as their bytes: arithmetic types, enums, fixed-size Eigen matrices, and the plain structs
// of those that say so with a member `static constexpr bool checkpoint_as_bytes = true;` (every member
// a number, a bool or a fixed-size Eigen matrix; no pointer, no container; no padding: its bytes are
// written as they are, and a padding byte is uninitialised memory). A struct with padding (a bool or an
// int before a double) lists its members in a transfer_state instead; g++ -Wpadded finds them.
template <class T>
inline constexpr bool stored_as_bytes =
    std::is_arithmetic_v<T> || std::is_enum_v<T> || requires { requires T::checkpoint_as_bytes; };
template <class S, int R, int C, int O, int MR, int MC>
  requires(R != Eigen::Dynamic && C != Eigen::Dynamic)
inline constexpr bool stored_as_bytes<Eigen::Matrix<S, R, C, O, MR, MC>> = true;

class StateWriter {
 public:
  static constexpr bool saving = true;
  template <class... T>
  void operator()(const T&... values) {
    (put(values), ...);
  }
  const std::string& bytes() const { return bytes_; }

 private:
  std::string bytes_;
  void raw(const void* p, std::size_t n) {
    if (n > 0) bytes_.append(static_cast<const char*>(p), n);  // p may be null when n is 0
  }
  void size(std::size_t n) {
    const std::uint64_t v = n;
    raw(&v, sizeof v);
  }
  template <class T>
    requires stored_as_bytes<T>
  void put(const T& v) {
    static_assert(std::is_standard_layout_v<T>);
    raw(&v, sizeof(T));
  }
  template <class S, int R, int C, int O, int MR, int MC>
    requires(R == Eigen::Dynamic || C == Eigen::Dynamic)
  void put(const Eigen::Matrix<S, R, C, O, MR, MC>& m) {
    size(static_cast<std::size_t>(m.rows()));
    size(static_cast<std::size_t>(m.cols()));
    raw(m.data(), sizeof(S) * static_cast<std::size_t>(m.size()));
  }
  void put(const std::string& s) {
    size(s.size());
    raw(s.data(), s.size());
  }
  template <class T, class A>
  void put(const std::vector<T, A>& v) {
    static_assert(!std::is_same_v<T, bool>, "store flags as std::vector<char>");
    size(v.size());
    if constexpr (stored_as_bytes<T>) raw(v.data(), sizeof(T) * v.size());
    else
      for (const auto& x : v) put(x);
  }
  template <class T, std::size_t N>
  void put(const std::array<T, N>& a) {
    for (const auto& x : a) put(x);
  }
  template <class A, class B>
  void put(const std::pair<A, B>& p) {
    put(p.first);
    put(p.second);
  }
  template <class K, class V, class C, class A>
  void put(const std::map<K, V, C, A>& m) {
    size(m.size());
    for (const auto& [k, v] : m) put(k), put(v);
  }
  // In ascending key order: the same map gives the same bytes whatever its buckets.
  template <class K, class V, class H, class E, class A>
  void put(const std::unordered_map<K, V, H, E, A>& m) {
    std::vector<const typename std::unordered_map<K, V, H, E, A>::value_type*> items;
    items.reserve(m.size());
    for (const auto& kv : m) items.push_back(&kv);
    std::sort(items.begin(), items.end(), [](const auto* a, const auto* b) { return a->first < b->first; });
    size(items.size());
    for (const auto* kv : items) put(kv->first), put(kv->second);
  }
  template <class T>
    requires requires(const T& t, StateWriter& w) { transfer_state(t, w); }
  void put(const T& v) {
    transfer_state(v, *this);
  }
};

class StateReader {
 public:
  static constexpr bool saving = false;
  // `source` names the bytes in errors (the checkpoint file).
  StateReader(std::string_view bytes, std::string source) : bytes_(bytes), source_(std::move(source)) {}
  // The reader does not own its bytes: a temporary string would be gone before the first read (a test
  // passed `w.bytes() + "extra"`; AddressSanitizer: heap-use-after-free). Keep the string alive.
  StateReader(std::string&&, std::string) = delete;
  template <class... T>
  void operator()(T&... values) {
    (get(values), ...);
  }
  // A size the state's owner already knows (its number of nodes, say) must match the stored one.
  void expect(std::size_t stored, std::size_t known, const char* what) const {
    if (stored != known)
      throw InputError(source_, 0, what,
                       "the checkpoint holds " + std::to_string(stored) + " but this run has " + std::to_string(known) +
                           ": it was written by another scene or another version");
  }
  // Every byte read: a longer file is not this state.
  void finish() const {
    if (pos_ != bytes_.size())
      throw InputError(source_, 0, "checkpoint", std::to_string(bytes_.size() - pos_) + " bytes left over after the state: "
                                                 "not a checkpoint of this run");
  }
  const std::string& source() const { return source_; }

 private:
  std::string_view bytes_;
  std::string source_;
  std::size_t pos_ = 0;

  void raw(void* p, std::size_t n) {
    if (n > bytes_.size() - pos_)
      throw InputError(source_, 0, "checkpoint",
                       "ends after " + std::to_string(bytes_.size()) + " bytes, in the middle of the state: truncated");
    if (n == 0) return;  // p may be an empty vector's null data(): memcpy's arguments must not be null
    std::memcpy(p, bytes_.data() + pos_, n);
    pos_ += n;
  }
  // A count of items of at least `item_bytes` each, checked against what is left before anything is
  // allocated for them.
  std::size_t size(std::size_t item_bytes) {
    std::uint64_t v = 0;
    raw(&v, sizeof v);
    if (item_bytes > 0 && v > (bytes_.size() - pos_) / item_bytes)
      throw InputError(source_, 0, "checkpoint",
                       "claims " + std::to_string(v) + " items where " + std::to_string(bytes_.size() - pos_) +
                           " bytes are left: truncated, or not a checkpoint");
    return static_cast<std::size_t>(v);
  }
  template <class T>
    requires stored_as_bytes<T>
  void get(T& v) {
    raw(&v, sizeof(T));
  }
  template <class S, int R, int C, int O, int MR, int MC>
    requires(R == Eigen::Dynamic || C == Eigen::Dynamic)
  void get(Eigen::Matrix<S, R, C, O, MR, MC>& m) {
    const std::size_t rows = size(0), cols = size(0);
    if (cols != 0 && rows > (bytes_.size() - pos_) / sizeof(S) / cols)
      throw InputError(source_, 0, "checkpoint", "claims a " + std::to_string(rows) + " x " + std::to_string(cols) +
                                                     " matrix where fewer numbers are left: truncated, or not a checkpoint");
    m.resize(static_cast<Eigen::Index>(rows), static_cast<Eigen::Index>(cols));
    raw(m.data(), sizeof(S) * rows * cols);
  }
  void get(std::string& s) {
    s.resize(size(1));
    raw(s.data(), s.size());
  }
  template <class T, class A>
  void get(std::vector<T, A>& v) {
    if constexpr (stored_as_bytes<T>) {
      v.resize(size(sizeof(T)));
      raw(v.data(), sizeof(T) * v.size());
    } else {
      v.resize(size(1));
      for (auto& x : v) {
        T item{};
        get(item);
        x = std::move(item);
      }
    }
  }
  template <class T, std::size_t N>
  void get(std::array<T, N>& a) {
    for (auto& x : a) get(x);
  }
  template <class A, class B>
  void get(std::pair<A, B>& p) {
    get(p.first);
    get(p.second);
  }
  template <class K, class V, class C, class A>
  void get(std::map<K, V, C, A>& m) {
    get_entries(m);
  }
  template <class K, class V, class H, class E, class A>
  void get(std::unordered_map<K, V, H, E, A>& m) {
    get_entries(m);
  }
  // A map's entries (key, value), after their count.
  template <class Map>
  void get_entries(Map& m) {
    m.clear();
    for (std::size_t i = 0, n = size(1); i < n; ++i) {
      typename Map::key_type k{};
      typename Map::mapped_type v{};
      get(k), get(v);
      m.emplace(std::move(k), std::move(v));
    }
  }
  template <class T>
    requires requires(T& t, StateReader& r) { transfer_state(t, r); }
  void get(T& v) {
    transfer_state(v, *this);
  }
};

}  // namespace furniture_fem
