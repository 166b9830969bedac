// SPDX-License-Identifier: MIT
// Polygon moment evaluation rate (issue 2): evaluations per second of all monomial
// integrals up to a degree over 6- and 20-vertex concave polygons, and of the polyhedron
// integrals. The baseline in the same process is the degree-0 (area) evaluation, so the
// printed ratios do not depend on the machine's speed.
#include "manifold/regular_shapes.hpp"
#include "manifold/simplex_integration.hpp"

#include <benchmark/benchmark.h>

#include <cmath>
#include <numbers>

namespace {

// A concave star polygon with `n` vertices, 10 m across, placed away from the origin as an
// element of a real model would be.
nmm::Loop star(int n) {
  nmm::Loop loop;
  for (int k = 0; k < n; ++k) {
    const double angle = 2.0 * std::numbers::pi * k / n;
    const double r = (k % 2 == 0) ? 5.0 : 3.0;
    loop.emplace_back(120.0 + r * std::cos(angle), 80.0 + r * std::sin(angle));
  }
  return loop;
}

void polygon_moments(benchmark::State& state) {
  const nmm::Loop loop = star(static_cast<int>(state.range(0)));
  const int degree = static_cast<int>(state.range(1));
  const nmm::Point2 origin(120.0, 80.0);
  for (auto _ : state) {
    benchmark::DoNotOptimize(nmm::polygon_moments(loop, degree, origin));
  }
  state.counters["evaluations/s"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(polygon_moments)->ArgsProduct({{6, 20}, {0, 1, 2, 3, 4, 8}});

void polyhedron_moments(benchmark::State& state) {
  const nmm::Polyhedron solid = nmm::regular_solid(nmm::RegularSolid::dodecahedron);
  const int degree = static_cast<int>(state.range(0));
  for (auto _ : state) {
    benchmark::DoNotOptimize(nmm::polyhedron_moments(solid, degree, nmm::Point3::Zero()));
  }
  state.counters["evaluations/s"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(polyhedron_moments)->DenseRange(0, 4);

} // namespace

BENCHMARK_MAIN();
