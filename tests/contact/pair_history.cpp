// The element pairs' contact history (contact/detail/pair_history.hpp), a sorted vector searched from
// where the last search ended, against std::map over random sequences of sets, erases and lookups in
// any order; and its checkpoint, in the format of the unordered_map it replaced (a checkpoint written
// before the change is read after it, and the other way).
#include <catch2/catch.hpp>

#include <furniture_fem/contact/room_contact.hpp>

#include <map>
#include <random>
#include <unordered_map>

using namespace furniture_fem;

namespace pair_history_tests {  // this file's own names (its group compiles files in batches)

namespace {
ContactState state_of(int i) {
  ContactState s;
  s.elongation = Vec3(i, -0.5 * i, 1e-3 * i);
  s.sticking = i % 2 == 0;
  s.normal = Vec3(0, 0, i % 3 == 0 ? 1.0 : -1.0);
  return s;
}
bool same(const ContactState& a, const ContactState& b) {
  return a.elongation == b.elongation && a.sticking == b.sticking && a.normal == b.normal;
}
}  // namespace

TEST_CASE("pair history: sets, erases and lookups agree with std::map, in ascending and any order", "[contact][history]") {
  for (const bool ascending : {true, false}) {
    for (unsigned seed : {1u, 2u, 3u}) {
      INFO("ascending " << ascending << ", seed " << seed);
      std::mt19937 rng(seed);
      std::uniform_int_distribution<int> element(0, 40), op(0, 9);
      detail::PairHistory h;
      std::map<long long, ContactState> ref;
      for (int pass = 0; pass < 30; ++pass) {
        // A pass: keys drawn, then visited ascending (as the broad phase hands them out) or as drawn.
        std::vector<long long> keys;
        for (int k = 0; k < 60; ++k) keys.push_back((static_cast<long long>(element(rng)) << 32) | unsigned(element(rng)));
        if (ascending) std::sort(keys.begin(), keys.end());
        for (long long key : keys) {
          const int o = op(rng);
          if (o < 4) {
            h.set(key, state_of(int(key % 97)));
            ref[key] = state_of(int(key % 97));
          } else if (o < 5) {
            h.erase(key);
            ref.erase(key);
          } else {
            const ContactState* found = h.find(key);
            const auto it = ref.find(key);
            REQUIRE((found != nullptr) == (it != ref.end()));
            if (found) CHECK(same(*found, it->second));
          }
        }
        REQUIRE(h.size() == ref.size());
        auto it = ref.begin();
        for (const auto& [key, st] : h.entries()) {
          CHECK(key == it->first);
          CHECK(same(st, it->second));
          ++it;
        }
        if (pass % 10 == 9) h.clear(), ref.clear();
      }
    }
  }
}

TEST_CASE("pair history: its checkpoint reads as the unordered_map's it replaced, and the other way", "[contact][history][checkpoint]") {
  detail::PairHistory h;
  std::unordered_map<long long, ContactState> map;
  for (int i : {5, 1, 9, 3, 7}) {
    const long long key = (static_cast<long long>(i) << 32) | unsigned(2 * i);
    h.set(key, state_of(i));
    map[key] = state_of(i);
  }
  // The same bytes: a ContactState is stored member by member, without its padding (checkpoint format 5).
  StateWriter from_history, from_map;
  from_history(h);
  from_map(map);
  CHECK(from_history.bytes() == from_map.bytes());
  detail::PairHistory back;
  StateReader r(from_map.bytes(), "test");
  r(back);
  r.finish();
  std::unordered_map<long long, ContactState> map_back;
  StateReader r2(from_history.bytes(), "test");
  r2(map_back);
  r2.finish();
  REQUIRE(back.size() == 5);
  REQUIRE(map_back.size() == 5);
  for (const auto& [key, st] : h.entries()) {
    const ContactState* b = back.find(key);
    REQUIRE(b != nullptr);
    CHECK(same(*b, st));
    REQUIRE(map_back.count(key) == 1);
    CHECK(same(map_back.at(key), st));
  }
}

}  // namespace pair_history_tests
