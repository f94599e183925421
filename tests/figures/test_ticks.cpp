// Tick generation, tick labels, axis mapping and the palette (no drawing).
#include <catch2/catch.hpp>

#include <cmath>
#include <random>
#include <vector>

#include "furniture_fem/figures/plot.hpp"

using namespace furniture_fem;

namespace ticks_tests {  // this file's own names (its group compiles files in batches)

TEST_CASE("nice ticks follow the 1-2-5 rule", "[ticks]") {
  CHECK(nice_ticks(0, 9.3) == std::vector<double>{0, 2, 4, 6, 8});
  CHECK(nice_step(9.3) == 2);
  CHECK(nice_step(1.0) == Approx(0.2));
  CHECK(nice_step(100, 4) == 20);
  const auto t = nice_ticks(-0.3, 0.3);
  REQUIRE(t.size() == 7);
  CHECK(t[3] == 0.0);  // exact zero, not 1e-17
  CHECK(nice_ticks(1, 1).empty());

  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1, 1), e(-8, 8);
  for (int trial = 0; trial < 2000; ++trial) {
    const double scale = std::pow(10.0, e(rng));
    const double lo = u(rng) * scale, hi = lo + (0.01 + std::abs(u(rng))) * scale;
    for (int target : {3, 5, 8}) {
      const auto ticks = nice_ticks(lo, hi, target);
      REQUIRE(ticks.size() >= 2);
      const double step = ticks[1] - ticks[0];
      const double mant = step / std::pow(10.0, std::floor(std::log10(step) + 1e-12));
      INFO("lo " << lo << " hi " << hi << " target " << target << " step " << step);
      CHECK((std::abs(mant - 1) < 1e-6 || std::abs(mant - 2) < 1e-6 || std::abs(mant - 5) < 1e-6));
      CHECK(step <= nice_step(hi - lo, target) * (1 + 1e-9));  // the nominal step, or smaller if needed
      CHECK(int(ticks.size()) <= 2 * target + 1);
      CHECK(ticks.front() >= lo - 1e-9 * step);
      CHECK(ticks.back() <= hi + 1e-9 * step);
      CHECK(ticks.front() - lo < step * (1 + 1e-9));  // no multiple of step missed at either end
      CHECK(hi - ticks.back() < step * (1 + 1e-9));
      for (std::size_t k = 0; k < ticks.size(); ++k) {
        CHECK(std::abs(ticks[k] / step - std::round(ticks[k] / step)) < 1e-6);  // multiples of the step
        if (k) CHECK(ticks[k] - ticks[k - 1] == Approx(step).epsilon(1e-6));
      }
    }
  }
}

TEST_CASE("tick labels and log ticks", "[ticks]") {
  CHECK(format_tick(0.30000000000000004, 0.1) == "0.3");
  CHECK(format_tick(4, 2) == "4");
  CHECK(format_tick(-1e-17, 0.5) == "0.0");
  CHECK(format_tick(0.025, 0.005) == "0.025");
  CHECK(format_tick(2e-6, 1e-6) == "2e-06");
  CHECK(format_tick(1.5e6, 5e5) == "1.5e+06");

  CHECK(log_ticks(1e-3, 1e2) == std::vector<double>{1e-3, 1e-2, 1e-1, 1, 10, 100});
  const auto few = log_ticks(2, 30);  // less than three decades: 1-2-5 multiples
  REQUIRE(few.size() == 4);
  CHECK(few[0] == Approx(2));
  CHECK(few[1] == Approx(5));
  CHECK(few[2] == Approx(10));
  CHECK(few[3] == Approx(20));
  const auto many = log_ticks(1e-12, 1e12, 6);  // 25 decades thinned
  CHECK(many.size() <= 7);
  CHECK(many.front() == Approx(1e-12));
  CHECK(format_log_tick(0.01) == "0.01");
  CHECK(format_log_tick(1e-5) == "1e-05");
}

TEST_CASE("axis mapping", "[ticks]") {
  const Axis x{0, 10, 100, 200};
  CHECK(x.to_pixel(0) == 100);
  CHECK(x.to_pixel(5) == 150);
  CHECK(x.to_pixel(10) == 200);
  const Axis y{-1, 1, 300, 100};  // y grows upwards on screen
  CHECK(y.to_pixel(1) == 100);
  CHECK(y.to_pixel(0) == 200);
  const Axis l{1, 100, 0, 200, true};
  CHECK(l.to_pixel(10) == Approx(100));
  CHECK(std::isnan(l.to_pixel(-1)));
}

TEST_CASE("palette colours are distinct", "[ticks]") {
  for (std::size_t i = 0; i < palette.size(); ++i)
    for (std::size_t j = i + 1; j < palette.size(); ++j) {
      const int d = std::abs(palette[i].r - palette[j].r) + std::abs(palette[i].g - palette[j].g) +
                    std::abs(palette[i].b - palette[j].b);
      CHECK(d > 60);
    }
  CHECK(palette_color(10) == palette_color(0));
}

}  // namespace ticks_tests
