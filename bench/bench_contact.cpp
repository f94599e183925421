// Per-step cost of contact detection and evaluation on a furnished room: 6 cabinet-like bodies of
// 0.9 x 0.4 x 1.8 m, each a surface grid of 50 mm elements (984 per body, 5904 in all, about the
// paper's configuration 3 with 6041), in two rows back to back with their walls 40 mm apart
// (closer than the 50 mm member width, so neighbouring walls are in contact).
//   BM_BroadPhase        boxes from nodal positions + CGAL box intersection, per step
//   BM_NarrowPhase       closest points of every candidate pair, per step
//   BM_NarrowPhaseBoxesFirst  the same with the boxes' test in front (segments_apart_beyond)
//   BM_Law<...>          one law evaluation per contact (kinematics prepared)
//   BM_SegmentPair<...>  closest points + kinematics + law + nodal shares, per contact pair
// Run: ./build-contact/bench/bench_contact --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <furniture_fem/contact/cgal_adapter.hpp>
#include <furniture_fem/contact/contact_laws.hpp>

#include <random>

namespace {
using namespace furniture_fem;

constexpr double element_length = 0.05, member_width = 0.05, margin = 0.05;  // margin: 5 m/s over 10 steps of 1 ms

struct Scene {
  std::vector<Vec3> x, v;                    // nodal positions and velocities
  std::vector<std::array<int, 3>> elements;  // node 1, node 2, body
};

// Lines along each axis through the grid points on the box surface, split into 50 mm elements.
void add_cabinet(Scene& s, int body, const Vec3& origin) {
  const Vec3 size(0.9, 0.4, 1.8);
  const std::array<int, 3> div = {4, 2, 8};  // grid divisions along x, y, z
  for (int axis = 0; axis < 3; ++axis) {
    const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
    for (int i = 0; i <= div[a1]; ++i)
      for (int j = 0; j <= div[a2]; ++j) {
        if (i != 0 && i != div[a1] && j != 0 && j != div[a2]) continue;  // surface lines only
        Vec3 p = origin;
        p[a1] += size[a1] * i / div[a1];
        p[a2] += size[a2] * j / div[a2];
        const int n = static_cast<int>(std::lround(size[axis] / element_length));
        int prev = static_cast<int>(s.x.size());
        s.x.push_back(p);
        for (int k = 1; k <= n; ++k) {
          Vec3 q = p;
          q[axis] += size[axis] * k / n;
          s.x.push_back(q);
          s.elements.push_back({prev, prev + 1, body});
          ++prev;
        }
      }
  }
}

const Scene& room() {
  static const Scene scene = [] {
    Scene s;
    const double gap = 0.04;
    for (int row = 0; row < 2; ++row)
      for (int k = 0; k < 3; ++k) add_cabinet(s, 3 * row + k, Vec3(k * (0.9 + gap), row * (0.4 + gap), 0));
    std::mt19937_64 rng(1);
    std::normal_distribution<double> vel(0.0, 0.05);
    s.v.resize(s.x.size());
    for (auto& v : s.v) v = Vec3(vel(rng), vel(rng), vel(rng));
    return s;
  }();
  return scene;
}

std::vector<ElementBox> boxes_of(const Scene& s) {
  std::vector<ElementBox> boxes;
  boxes.reserve(s.elements.size());
  for (std::size_t e = 0; e < s.elements.size(); ++e) {
    const auto& el = s.elements[e];
    boxes.push_back(ElementBox::around(s.x[el[0]], s.x[el[1]], 0.5 * member_width + margin, static_cast<int>(e), el[2]));
  }
  return boxes;
}

const std::vector<std::pair<int, int>>& candidate_pairs() {
  static const auto pairs = [] {
    BroadPhase bp;
    return bp.pairs(boxes_of(room()));
  }();
  return pairs;
}

SegmentPair segment_pair(const Scene& s, int ea, int eb) {
  const auto &A = s.elements[ea], &B = s.elements[eb];
  SegmentPair sp;
  sp.a0 = s.x[A[0]];
  sp.a1 = s.x[A[1]];
  sp.b0 = s.x[B[0]];
  sp.b1 = s.x[B[1]];
  sp.va0 = s.v[A[0]];
  sp.va1 = s.v[A[1]];
  sp.vb0 = s.v[B[0]];
  sp.vb1 = s.v[B[1]];
  sp.L = member_width;
  sp.dt = 1e-3;
  return sp;
}

// The candidate pairs that are in contact (l <= L).
const std::vector<std::pair<int, int>>& contact_pairs() {
  static const auto pairs = [] {
    std::vector<std::pair<int, int>> out;
    for (const auto& [a, b] : candidate_pairs()) {
      const auto sp = segment_pair(room(), a, b);
      if (closest_points_segment_segment(sp.a0, sp.a1, sp.b0, sp.b1).distance <= sp.L) out.emplace_back(a, b);
    }
    return out;
  }();
  return pairs;
}

const std::vector<ContactKinematics>& contact_kinematics() {
  static const auto ks = [] {
    std::vector<ContactKinematics> out;
    for (const auto& [a, b] : contact_pairs()) {
      ContactState st;
      const auto r = evaluate_segment_pair(ContactLaw<PowerPenalty, NoDamping, PaperSignFriction>{}, segment_pair(room(), a, b),
                                           ContactParams::paper(30, 0.169), st);
      ContactKinematics k = r.kinematics;
      k.long_axis = Vec3::UnitX();
      out.push_back(k);
    }
    return out;
  }();
  return ks;
}

ContactParams bench_params() {
  ContactParams p = ContactParams::paper_floor(43.6, 0.278, 0.208);
  p.k_t = 1e5;
  p.k_lin = p.alpha / member_width;
  p.c_lin = 200;
  p.k_hc = 1e7;
  p.hc_damping = 0.3;
  return p;
}

void BM_BroadPhase(benchmark::State& state) {
  const Scene& s = room();
  BroadPhase bp;
  std::vector<ElementBox> boxes;
  std::vector<std::pair<int, int>> pairs;
  boxes.reserve(s.elements.size());
  for (auto _ : state) {
    boxes.clear();
    for (std::size_t e = 0; e < s.elements.size(); ++e) {
      const auto& el = s.elements[e];
      boxes.push_back(ElementBox::around(s.x[el[0]], s.x[el[1]], 0.5 * member_width + margin, static_cast<int>(e), el[2]));
    }
    bp.pairs(boxes, pairs);
    benchmark::DoNotOptimize(pairs.data());
  }
  state.counters["elements"] = static_cast<double>(s.elements.size());
  state.counters["pairs"] = static_cast<double>(pairs.size());
  state.counters["body_pairs"] = bp.body_pairs_tested();
  state.SetItemsProcessed(state.iterations() * static_cast<long>(s.elements.size()));
}
BENCHMARK(BM_BroadPhase)->Unit(benchmark::kMillisecond);

void BM_NarrowPhase(benchmark::State& state) {
  const Scene& s = room();
  const auto& pairs = candidate_pairs();
  int contacts = 0;
  for (auto _ : state) {
    contacts = 0;
    for (const auto& [a, b] : pairs) {
      const auto &A = s.elements[a], &B = s.elements[b];
      const auto c = closest_points_segment_segment(s.x[A[0]], s.x[A[1]], s.x[B[0]], s.x[B[1]]);
      contacts += c.distance <= member_width;
    }
    benchmark::DoNotOptimize(contacts);
  }
  state.counters["candidates"] = static_cast<double>(pairs.size());
  state.counters["contacts"] = contacts;
  state.SetItemsProcessed(state.iterations() * static_cast<long>(pairs.size()));
}
BENCHMARK(BM_NarrowPhase)->Unit(benchmark::kMicrosecond);

// The same candidates with segments_apart_beyond in front, as RoomContact's narrow phase has it: pairs
// whose boxes are apart by more than L skip the closest points (the same contacts are found).
void BM_NarrowPhaseBoxesFirst(benchmark::State& state) {
  const Scene& s = room();
  const auto& pairs = candidate_pairs();
  int contacts = 0, passed_over = 0;
  for (auto _ : state) {
    contacts = passed_over = 0;
    for (const auto& [a, b] : pairs) {
      const auto &A = s.elements[a], &B = s.elements[b];
      if (segments_apart_beyond(s.x[A[0]], s.x[A[1]], s.x[B[0]], s.x[B[1]], member_width)) {
        ++passed_over;
        continue;
      }
      const auto c = closest_points_segment_segment(s.x[A[0]], s.x[A[1]], s.x[B[0]], s.x[B[1]]);
      contacts += c.distance <= member_width;
    }
    benchmark::DoNotOptimize(contacts);
  }
  state.counters["candidates"] = static_cast<double>(pairs.size());
  state.counters["passed_over"] = passed_over;
  state.counters["contacts"] = contacts;
  state.SetItemsProcessed(state.iterations() * static_cast<long>(pairs.size()));
}
BENCHMARK(BM_NarrowPhaseBoxesFirst)->Unit(benchmark::kMicrosecond);

template <class Law>
void BM_Law(benchmark::State& state) {
  const auto& ks = contact_kinematics();
  const ContactParams p = bench_params();
  const Law law;
  std::vector<ContactState> states(ks.size());
  Vec3 sum = Vec3::Zero();
  for (auto _ : state) {
    for (std::size_t i = 0; i < ks.size(); ++i) sum += law.force(ks[i], p, states[i]).on_a;
    benchmark::DoNotOptimize(sum.data());
  }
  state.counters["contacts"] = static_cast<double>(ks.size());
  state.SetItemsProcessed(state.iterations() * static_cast<long>(ks.size()));
}
BENCHMARK_TEMPLATE(BM_Law, PaperLaw)->Unit(benchmark::kMicrosecond);
BENCHMARK_TEMPLATE(BM_Law, PaperAnisotropicFloorLaw)->Unit(benchmark::kMicrosecond);
BENCHMARK_TEMPLATE(BM_Law, SpringDashpotLaw)->Unit(benchmark::kMicrosecond);
BENCHMARK_TEMPLATE(BM_Law, HuntCrossleyLaw)->Unit(benchmark::kMicrosecond);
BENCHMARK_TEMPLATE(BM_Law, StickSlipLaw)->Unit(benchmark::kMicrosecond);

template <class Law>
void BM_SegmentPair(benchmark::State& state) {
  const Scene& s = room();
  const auto& pairs = contact_pairs();
  const ContactParams p = bench_params();
  const Law law;
  std::vector<ContactState> states(pairs.size());
  Vec3 sum = Vec3::Zero();
  for (auto _ : state) {
    for (std::size_t i = 0; i < pairs.size(); ++i) {
      const auto r = evaluate_segment_pair(law, segment_pair(s, pairs[i].first, pairs[i].second), p, states[i]);
      sum += r.on_a0 + r.on_b1;
    }
    benchmark::DoNotOptimize(sum.data());
  }
  state.counters["contacts"] = static_cast<double>(pairs.size());
  state.SetItemsProcessed(state.iterations() * static_cast<long>(pairs.size()));
}
BENCHMARK_TEMPLATE(BM_SegmentPair, PaperLaw)->Unit(benchmark::kMicrosecond);
BENCHMARK_TEMPLATE(BM_SegmentPair, StickSlipLaw)->Unit(benchmark::kMicrosecond);

}  // namespace
