#pragma once
// furniture_fem/study/random.hpp: reproducible random numbers for studies.
//
//   std::uint64_t mix64(std::uint64_t)                    SplitMix64's finaliser (a bijection of 64 bits)
//   RandomStream stream(seed, {key, ...})                  an independent stream per (seed, keys)
//   stream.bits(), stream.uniform(), stream.uniform(a, b), stream.normal(), stream.bernoulli(p)
//
// A realisation's parameters must follow from the study seed and its index alone, whatever the
// number of workers or ranks and whatever ran before it; and a realisation written out on one machine
// must be re-runnable on another. So every stream is counter-based (SplitMix64 over seed and keys:
// no state shared between realisations), and the conversions to doubles are written out here instead of
// std::uniform_real_distribution / std::normal_distribution, whose algorithms the standard leaves to
// each library (libstdc++ and libc++ give different numbers from the same engine).
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <numbers>

namespace furniture_fem {

// SplitMix64's output function (Steele, Lea and Flood 2014): a bijection with good avalanche.
constexpr std::uint64_t mix64(std::uint64_t z) {
  z += 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

class RandomStream {
 public:
  // The stream of `seed` and `keys` (a realisation's index, a factor's number, ...): streams with any
  // differing key are independent for practical purposes.
  RandomStream(std::uint64_t seed, std::initializer_list<std::uint64_t> keys) : state_(mix64(seed)) {
    for (std::uint64_t k : keys) state_ = mix64(state_ ^ mix64(k + 0x632be59bd9b4e019ULL));
  }
  // The next 64 random bits (SplitMix64's generator: a Weyl sequence through mix64).
  std::uint64_t bits() {
    state_ += 0x9e3779b97f4a7c15ULL;
    return mix64(state_);
  }
  // Uniform on [0, 1): the top 53 bits, exactly representable.
  double uniform() { return static_cast<double>(bits() >> 11) * 0x1.0p-53; }
  // Uniform on [a, b).
  double uniform(double a, double b) { return a + (b - a) * uniform(); }
  // Standard normal, by Box-Muller (one of the pair; 1 - u keeps the logarithm finite).
  double normal() {
    const double u1 = 1.0 - uniform(), u2 = uniform();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
  }
  bool bernoulli(double p) { return uniform() < p; }

 private:
  std::uint64_t state_;
};

}  // namespace furniture_fem
