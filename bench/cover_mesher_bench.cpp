// SPDX-License-Identifier: MIT
// bench/cover_mesher_bench.cpp — robustness and speed of the cover mesher (issue 3).
//
//   bench_cover_mesher robustness [N=1000]   N seeded random joint networks, 10-200 joints
//                                            each, with crossings, near-parallel pairs and
//                                            joints passing near or through math nodes;
//                                            every one must mesh with the invariants exact.
//   bench_cover_mesher speed [TRIANGLES=1e5] [JOINTS=2000]
//                                            a 200 m x 200 m rock mass; prints the time
//                                            split and the peak memory.
#include "mesh/cover_mesher.hpp"
#include "mesh/error.hpp"
#include "mesh/math_mesh.hpp"
#include "mesh/physical_mesh.hpp"

#include <sys/resource.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <random>
#include <set>
#include <string>
#include <vector>

namespace {

using nmm::Point2;

double peak_memory_mb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;
}

nmm::PhysicalMesh square_rock(double size) {
  nmm::PhysicalMesh physical;
  physical.source = "bench";
  physical.regions.push_back({"rock", {{{{0, 0}, {size, 0}, {size, size}, {0, size}}, {}}}});
  return physical;
}

/// A random joint network in [0, L]^2: joint sets of random mean orientation with scatter,
/// lengths from 2% to 60% of L, some joints starting exactly on a math node, some passing
/// 1e-12..1e-6 of L from a node, some near-parallel twins 1e-12..1e-4 of L apart.
void add_random_joints(nmm::PhysicalMesh& physical,
                       const nmm::MathMesh& math,
                       int joints,
                       double side,
                       std::mt19937_64& random) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const int sets = 1 + static_cast<int>(unit(random) * 3.0);
  std::vector<double> mean_angle;
  for (int s = 0; s < sets; ++s)
    mean_angle.push_back(unit(random) * 3.14159265358979);
  auto node = [&]() {
    return math.nodes[static_cast<std::size_t>(unit(random) * (math.n_nodes() - 1))];
  };
  for (int j = 0; j < joints; ++j) {
    const double angle =
        mean_angle[static_cast<std::size_t>(j % sets)] + 0.2 * (unit(random) - 0.5);
    const double length = side * (0.02 + 0.58 * unit(random));
    const Point2 direction(std::cos(angle), std::sin(angle));
    Point2 start(side * (1.2 * unit(random) - 0.1), side * (1.2 * unit(random) - 0.1));
    const double kind = unit(random);
    if (kind < 0.1) {
      start = node(); // starts exactly on a node
    } else if (kind < 0.2) {
      // passes near a node: the node offset across the joint by 1e-12..1e-6 of the side
      const Point2 n = node();
      const double offset = side * std::pow(10.0, -12.0 + 6.0 * unit(random));
      start = n + offset * Point2(-direction.y(), direction.x()) - 0.5 * length * direction;
    }
    std::vector<Point2> line{start, start + length * direction};
    physical.curves.push_back({"joint" + std::to_string(j), {line}});
    if (kind > 0.9) {
      // a near-parallel twin
      const double offset = side * std::pow(10.0, -12.0 + 8.0 * unit(random));
      const double tilt = 1e-9 * unit(random);
      const Point2 shifted = start + offset * Point2(-direction.y(), direction.x());
      const Point2 end = shifted + length * Point2(std::cos(angle + tilt), std::sin(angle + tilt));
      physical.curves.push_back({"twin" + std::to_string(j), {{shifted, end}}});
    }
  }
}

/// The invariants of issue 3: areas exact to 1e-12, three distinct covers per element of the
/// element's own nodes. Returns an empty string or the first violation.
std::string check(const nmm::CoverSystem& cs, const nmm::MathMesh& math, double material) {
  nmm::CompensatedSum sum;
  for (const nmm::Element& e : cs.elements) {
    sum += e.area;
    const std::set<int> distinct(e.covers.begin(), e.covers.end());
    if (distinct.size() != 3)
      return "element with repeated covers";
    for (std::size_t k = 0; k < 3; ++k) {
      if (cs.covers[static_cast<std::size_t>(e.covers[k])].node !=
          math.triangles[static_cast<std::size_t>(e.triangle)][k])
        return "cover of another node";
    }
  }
  const double total = sum.value();
  if (std::abs(total - material) > 1e-12 * material) {
    char text[160];
    std::snprintf(text, sizeof text, "area %.17g != %.17g (relative %.3g)", total, material,
                  std::abs(total - material) / material);
    return text;
  }
  return {};
}

int robustness(int networks) {
  const double side = 10.0;
  int failures = 0;
  double seconds = 0.0;
  long elements = 0;
  long tiny = 0;
  for (int n = 0; n < networks; ++n) {
    std::mt19937_64 random(static_cast<std::uint64_t>(n) * 7919U + 17U);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    nmm::PhysicalMesh physical = square_rock(side);
    const double size = side / (8.0 + 24.0 * unit(random));
    const nmm::MathMesh math =
        nmm::make_regular_math_mesh(nmm::material_bounding_box(physical), size);
    add_random_joints(physical, math, 10 + static_cast<int>(unit(random) * 191.0), side, random);
    std::vector<int> joints(physical.curves.size());
    for (std::size_t i = 0; i < joints.size(); ++i)
      joints[i] = static_cast<int>(i);
    try {
      nmm::validate_physical_mesh(physical);
      const auto start = std::chrono::steady_clock::now();
      const nmm::CoverSystem cs = nmm::build_cover_system(math, physical, joints);
      seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      const std::string problem = check(cs, math, side * side);
      elements += cs.n_elements();
      tiny += cs.stats.tiny_covers;
      if (!problem.empty()) {
        ++failures;
        std::printf("network %d: %s\n", n, problem.c_str());
      }
    } catch (const std::exception& e) {
      ++failures;
      std::printf("network %d: exception: %s\n", n, e.what());
    }
  }
  std::printf("robustness: %d networks, %d failures, %.2f s meshing (%.1f ms each), %ld "
              "elements, %ld tiny covers given extension elements\n",
              networks, failures, seconds, 1e3 * seconds / networks, elements, tiny);
  return failures == 0 ? 0 : 1;
}

int speed(double triangles, int joint_count) {
  const double side = 200.0;
  nmm::PhysicalMesh physical = square_rock(side);
  // Equilateral triangles of edge s: about side^2 / (sqrt(3)/4 s^2) of them.
  const double size = std::sqrt(side * side * 4.0 / (std::sqrt(3.0) * triangles));
  const auto start_math = std::chrono::steady_clock::now();
  const nmm::MathMesh math =
      nmm::make_regular_math_mesh(nmm::material_bounding_box(physical), size);
  const double math_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_math).count();
  std::mt19937_64 random(2026);
  add_random_joints(physical, math, joint_count, side, random);
  // Shorter joints for the speed case: 1-30 m, a typical jointed rock mass.
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (nmm::NamedCurve& c : physical.curves) {
    auto& line = c.polylines[0];
    const Point2 d = (line[1] - line[0]).normalized();
    line[1] = line[0] + (1.0 + 29.0 * unit(random)) * d;
  }
  nmm::validate_physical_mesh(physical);
  std::vector<int> joints(physical.curves.size());
  for (std::size_t i = 0; i < joints.size(); ++i)
    joints[i] = static_cast<int>(i);
  const auto start = std::chrono::steady_clock::now();
  const nmm::CoverSystem cs = nmm::build_cover_system(math, physical, joints);
  const double total =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const std::string problem = check(cs, math, side * side);
  std::printf("speed: %d math triangles (size %.3f m), %zu joints -> %d cut triangles, %d "
              "physical edges, %d covers, %d elements, %d blocks, %d loops\n",
              math.n_triangles(), size, physical.curves.size(), cs.stats.cut_triangles,
              cs.stats.physical_edges, cs.n_covers(), cs.n_elements(), cs.n_blocks(), cs.n_loops());
  std::printf("  math mesh %.3f s; cover mesher %.3f s = physical arrangement %.3f s (%.0f%%) + "
              "cut triangles %.3f s (%.0f%%) + covers/elements/loops %.3f s (%.0f%%)\n",
              math_seconds, total, cs.stats.seconds_physical_arrangement,
              100.0 * cs.stats.seconds_physical_arrangement / total, cs.stats.seconds_cut_triangles,
              100.0 * cs.stats.seconds_cut_triangles / total, cs.stats.seconds_rest,
              100.0 * cs.stats.seconds_rest / total);
  std::printf("  peak memory %.0f MB; invariants: %s\n", peak_memory_mb(),
              problem.empty() ? "exact" : problem.c_str());
  return problem.empty() ? 0 : 1;
}

} // namespace

int main(int argc, char** argv) {
  const std::string what = argc > 1 ? argv[1] : "speed";
  if (what == "robustness")
    return robustness(argc > 2 ? std::atoi(argv[2]) : 1000);
  if (what == "speed")
    return speed(argc > 2 ? std::atof(argv[2]) : 1e5, argc > 3 ? std::atoi(argv[3]) : 2000);
  std::fprintf(stderr, "usage: bench_cover_mesher robustness [N] | speed [TRIANGLES] [JOINTS]\n");
  return 2;
}
