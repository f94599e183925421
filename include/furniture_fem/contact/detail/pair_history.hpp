#pragma once
// Internal: the contact state (history) of each element pair in contact, by the pair's key, for the
// laws with a tangential spring. Users include furniture_fem/contact/room_contact.hpp, not this file.
#ifndef FURNITURE_FEM_CONTACT_INTERNAL
#error "furniture_fem/contact/detail/pair_history.hpp is internal: include <furniture_fem/contact/room_contact.hpp>"
#endif
#include <algorithm>
#include <type_traits>
#include <utility>
#include <vector>

#include "../contact_laws.hpp"

namespace furniture_fem::detail {

// A vector kept sorted by key. The broad phase hands out its pairs in ascending key order, so a step's
// entries arrive sorted and each insertion is an append, and the lookups of a pass come in ascending
// order too: each search starts where the last one ended and walks forward (a key below the last one
// searched falls back to a binary search). An unordered_map allocated a node per pair and step and
// hashed every lookup (the stacked cabinets of a rigid room have a few hundred pairs; issue 10).
// A checkpoint stores the count and the entries in ascending key order, as it stored the map.
class PairHistory {
 public:
  using Entry = std::pair<long long, ContactState>;

  const ContactState* find(long long key) const {
    const auto it = lower(key);
    return it != entries_.end() && it->first == key ? &it->second : nullptr;
  }
  void set(long long key, const ContactState& state) {
    if (entries_.empty() || entries_.back().first < key) return entries_.emplace_back(key, state), void();
    const auto it = lower(key);
    if (it != entries_.end() && it->first == key) it->second = state;
    else entries_.emplace(it, key, state);
  }
  void erase(long long key) {
    const auto it = lower(key);
    if (it != entries_.end() && it->first == key) entries_.erase(it);
  }
  void clear() { entries_.clear(), cursor_ = 0; }
  void swap(PairHistory& other) { entries_.swap(other.entries_), std::swap(cursor_, other.cursor_); }
  std::size_t size() const { return entries_.size(); }
  const std::vector<Entry>& entries() const { return entries_; }

  template <class Self, class Archive>
    requires std::is_same_v<std::remove_const_t<Self>, PairHistory>
  friend void transfer_state(Self& h, Archive& ar) {
    ar(h.entries_);
  }

 private:
  // The first entry whose key is not below `key`, searched from the last search's result.
  std::size_t lower_index(long long key) const {
    const std::size_t n = entries_.size();
    std::size_t i = cursor_ <= n && (cursor_ == 0 || entries_[cursor_ - 1].first < key) ? cursor_ : 0;
    if (i == 0 && n > 0 && entries_.front().first < key)
      i = std::size_t(std::lower_bound(entries_.begin(), entries_.end(), key,
                                       [](const Entry& e, long long k) { return e.first < k; }) -
                      entries_.begin());
    while (i < n && entries_[i].first < key) ++i;
    return cursor_ = i;
  }
  std::vector<Entry>::const_iterator lower(long long key) const { return entries_.begin() + lower_index(key); }
  std::vector<Entry>::iterator lower(long long key) { return entries_.begin() + lower_index(key); }
  std::vector<Entry> entries_;
  mutable std::size_t cursor_ = 0;  // where the last search ended (searches are from one thread)
};

}  // namespace furniture_fem::detail
