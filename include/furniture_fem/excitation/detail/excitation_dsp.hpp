#pragma once
// Internals of furniture_fem/excitation/excitation.hpp: the exact SDOF step, Butterworth sections, polynomial
// least squares and a portable normal random generator.
#ifndef FURNITURE_FEM_EXCITATION_INTERNAL
#error "furniture_fem/excitation/detail/excitation_dsp.hpp is internal: include <furniture_fem/excitation/excitation.hpp>"
#endif
#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "excitation_text.hpp"

namespace furniture_fem::detail::gm {

// One step h of u'' + 2 zeta w u' + w^2 u = -a(t) with a(t) linear over the step, as the exact
// recurrence of Nigam & Jennings (1969):
//   [u1 v1] = A [u0 v0] + B [a0 a1].
// The closed-form B loses digits to cancellation (terms ~1/(w^3 h) that cancel to ~h^2) when w h is
// small, so there the same A, B are taken from the exponential of the augmented system instead.
struct SdofStep {
  double a11 = 0, a12 = 0, a21 = 0, a22 = 0;
  double b11 = 0, b12 = 0, b21 = 0, b22 = 0;

  // Below this w h the closed form would lose more than ~1e-9 relative.
  static constexpr double closed_form_min_wh = 0.02;

  SdofStep(double w, double zeta, double h, bool force_closed_form = false) {
    if (w * h >= closed_form_min_wh || force_closed_form)
      closed_form(w, zeta, h);
    else
      augmented_exponential(w, zeta, h);
  }

  void advance(double& u, double& v, double a0, double a1) const {
    const double un = a11 * u + a12 * v + b11 * a0 + b12 * a1;
    const double vn = a21 * u + a22 * v + b21 * a0 + b22 * a1;
    u = un;
    v = vn;
  }

 private:
  void closed_form(double w, double z, double h) {
    const double w2 = w * w, w3 = w2 * w;
    const double sz = std::sqrt(1.0 - z * z);
    const double wd = w * sz;
    const double E = std::exp(-z * w * h), S = std::sin(wd * h), C = std::cos(wd * h);
    a11 = E * (z / sz * S + C);
    a12 = E * S / wd;
    a21 = -w / sz * E * S;
    a22 = E * (C - z / sz * S);
    const double t1 = (2.0 * z * z - 1.0) / (w2 * h), t2 = 2.0 * z / (w3 * h);
    const double Cz = C - z / sz * S, Dz = wd * S + z * w * C;
    b11 = E * ((t1 + z / w) * S / wd + (t2 + 1.0 / w2) * C) - t2;
    b12 = -E * (t1 * S / wd + t2 * C) - 1.0 / w2 + t2;
    b21 = E * ((t1 + z / w) * Cz - (t2 + 1.0 / w2) * Dz) + 1.0 / (w2 * h);
    b22 = -E * (t1 * Cz - t2 * Dz) - 1.0 / (w2 * h);
  }

  // State [u, v, a, s] with a' = s, s' = 0: exp(Z h) holds A and the exact input terms as plain
  // power series (no cancellation). Scaling and squaring keeps the Taylor series short.
  void augmented_exponential(double w, double z, double h) {
    Eigen::Matrix4d Z = Eigen::Matrix4d::Zero();
    Z(0, 1) = 1.0;
    Z(1, 0) = -w * w;
    Z(1, 1) = -2.0 * z * w;
    Z(1, 2) = -1.0;
    Z(2, 3) = 1.0;
    Z *= h;
    int squarings = 0;
    double norm = Z.cwiseAbs().colwise().sum().maxCoeff();
    while (norm > 0.25) {
      norm *= 0.5;
      ++squarings;
    }
    Z /= std::ldexp(1.0, squarings);
    Eigen::Matrix4d X = Eigen::Matrix4d::Identity(), term = Eigen::Matrix4d::Identity();
    for (int k = 1; k <= 18; ++k) {
      term = term * Z / double(k);
      X += term;
    }
    for (int k = 0; k < squarings; ++k) X = X * X;
    a11 = X(0, 0);
    a12 = X(0, 1);
    a21 = X(1, 0);
    a22 = X(1, 1);
    // a(t) = a0 + s t with s = (a1 - a0) / h.
    b11 = X(0, 2) - X(0, 3) / h;
    b12 = X(0, 3) / h;
    b21 = X(1, 2) - X(1, 3) / h;
    b22 = X(1, 3) / h;
  }
};

// Second-order section of a digital filter, direct form II transposed.
struct Biquad {
  double b0 = 1, b1 = 0, b2 = 0, a1 = 0, a2 = 0;
};

// Butterworth low-pass of the given order as second-order sections (bilinear transform, prewarped at
// fc). Each section has unit DC gain.
inline std::vector<Biquad> butterworth_lowpass(int order, double fc, double dt) {
  const double K = std::tan(kPi * fc * dt);
  std::vector<Biquad> sections;
  for (int k = 0; k < order / 2; ++k) {
    const double Q = 1.0 / (2.0 * std::sin(kPi * (2 * k + 1) / (2.0 * order)));
    const double n = 1.0 / (1.0 + K / Q + K * K);
    Biquad s;
    s.b0 = K * K * n;
    s.b1 = 2.0 * s.b0;
    s.b2 = s.b0;
    s.a1 = 2.0 * (K * K - 1.0) * n;
    s.a2 = (1.0 - K / Q + K * K) * n;
    sections.push_back(s);
  }
  if (order % 2 == 1) {
    Biquad s;
    s.b0 = K / (1.0 + K);
    s.b1 = s.b0;
    s.a1 = (K - 1.0) / (K + 1.0);
    sections.push_back(s);
  }
  return sections;
}

// Filters x in place, starting from the steady state of a constant input x[0] so a record that does
// not start at zero gives no start-up transient.
inline void run_section(const Biquad& q, std::vector<double>& x) {
  if (x.empty()) return;
  const double c = x[0];
  double s2 = (q.b2 - q.a2) * c;
  double s1 = (q.b1 - q.a1) * c + s2;
  for (double& xi : x) {
    const double in = xi;
    const double y = q.b0 * in + s1;
    s1 = q.b1 * in - q.a1 * y + s2;
    s2 = q.b2 * in - q.a2 * y;
    xi = y;
  }
}

// Removes from y its least-squares fit by a polynomial of the given order in the sample index.
// Gram-Schmidt on the monomials of tau in [-1, 1] (done twice) is well conditioned, unlike the
// normal equations of raw powers of t.
inline void remove_polynomial(std::vector<double>& y, int order) {
  const std::size_t n = y.size();
  if (n == 0) return;
  std::vector<std::vector<double>> basis;
  for (int j = 0; j <= order && static_cast<std::size_t>(j) < n; ++j) {
    std::vector<double> v(n);
    for (std::size_t i = 0; i < n; ++i) {
      const double tau = n > 1 ? 2.0 * double(i) / double(n - 1) - 1.0 : 0.0;
      v[i] = std::pow(tau, j);
    }
    for (int pass = 0; pass < 2; ++pass)
      for (const auto& q : basis) {
        double d = 0;
        for (std::size_t i = 0; i < n; ++i) d += q[i] * v[i];
        for (std::size_t i = 0; i < n; ++i) v[i] -= d * q[i];
      }
    double norm = 0;
    for (double x : v) norm += x * x;
    norm = std::sqrt(norm);
    if (!(norm > 1e-12 * std::sqrt(double(n)))) continue;
    for (double& x : v) x /= norm;
    basis.push_back(std::move(v));
  }
  for (const auto& q : basis) {
    double d = 0;
    for (std::size_t i = 0; i < n; ++i) d += q[i] * y[i];
    for (std::size_t i = 0; i < n; ++i) y[i] -= d * q[i];
  }
}

// Standard normal samples by Box-Muller on mt19937_64, whose output the C++ standard fixes;
// std::normal_distribution is implementation-defined, so seeds would not reproduce across libraries.
class NormalSource {
 public:
  explicit NormalSource(std::uint64_t seed) : rng_(seed) {}
  double operator()() {
    if (has_spare_) {
      has_spare_ = false;
      return spare_;
    }
    const double u1 = 1.0 - uniform();  // (0, 1]: log stays finite
    const double u2 = uniform();
    const double r = std::sqrt(-2.0 * std::log(u1));
    spare_ = r * std::sin(2.0 * kPi * u2);
    has_spare_ = true;
    return r * std::cos(2.0 * kPi * u2);
  }

 private:
  double uniform() { return double(rng_() >> 11) * 0x1.0p-53; }  // [0, 1), 53 random bits
  std::mt19937_64 rng_;
  bool has_spare_ = false;
  double spare_ = 0;
};

// Decorrelates derived seeds (one per component) from a user seed.
inline std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ULL;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ULL;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBULL;
  return x ^ (x >> 31);
}

}  // namespace furniture_fem::detail::gm
