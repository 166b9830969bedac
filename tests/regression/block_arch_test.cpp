// SPDX-License-Identifier: MIT
// examples/09_block_arch end to end (label regression;slow: about 3.5 s per run): the
// voussoir arch stands under 0.7 times its limit-analysis collapse load and collapses under
// 1.5 times it (the case as shipped) by the mechanism limit_analysis.py predicts, hinges
// opening at joints 0 and 11 (intrados), 3 and 8 (extrados), 5 and 6 (intrados).
#include "../support/case_fixtures.hpp"
#include "../support/vtk_readers.hpp"
#include "example_run.hpp"
#include <gtest/gtest.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkIdList.h>
#include <vtkPointData.h>
#include <vtkUnstructuredGrid.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace nmm {
namespace {

namespace fs = std::filesystem;
using testing::ExampleRun;
using testing::PvdEntry;
using testing::read_pvd;
using testing::read_text;
using testing::read_vtu;
using testing::replaced;

const fs::path example = fs::path(NMM_EXAMPLES_DIR) / "09_block_arch";

// The arch of block_arch.geo: 11 voussoirs between radial joints at 180 k / 11 degrees
// from the right springing, intrados radius 1.8 m, extrados 2.2 m, on a base slab.
constexpr int n_voussoirs = 11;
constexpr double intrados = 1.8;
constexpr double extrados = 2.2;
// limit_analysis.py: the collapse load of the arch, N per metre.
constexpr double collapse_load = 51463.3;

/// The rigid motion of one block fitted to its points: centroid before and after, rotation.
struct BlockMotion {
  std::array<double, 2> start{};
  std::array<double, 2> now{};
  double angle = 0.0;
  bool found = false;

  /// Where the material point that started at @p x is now, if it moved with the block.
  [[nodiscard]] std::array<double, 2> place(const std::array<double, 2>& x) const {
    const double c = std::cos(angle);
    const double s = std::sin(angle);
    const double dx = x[0] - start[0];
    const double dy = x[1] - start[1];
    return {now[0] + c * dx - s * dy, now[1] + s * dx + c * dy};
  }
};

/// The opening of each joint k = 0 .. 11 at its intrados and extrados ends, m: the
/// separation of the two blocks' copies of the end point along the joint's normal (positive
/// apart), each block moved rigidly by its best-fit motion (the elastic strains, 1e-5, are
/// far below the millimetres measured here).
struct JointOpening {
  double at_intrados = 0.0;
  double at_extrados = 0.0;
};

std::vector<JointOpening> joint_openings(const fs::path& step_file) {
  const vtkSmartPointer<vtkUnstructuredGrid> grid = read_vtu(step_file);
  vtkDataArray* displacement = grid->GetPointData()->GetArray("displacement");
  vtkDataArray* block = grid->GetCellData()->GetArray("block");
  EXPECT_NE(displacement, nullptr);
  EXPECT_NE(block, nullptr);
  if (displacement == nullptr || block == nullptr)
    return {};
  std::map<int, std::set<vtkIdType>> points_of_block;
  for (vtkIdType c = 0; c < grid->GetNumberOfCells(); ++c) {
    vtkIdList* ids = grid->GetCell(c)->GetPointIds();
    for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k)
      points_of_block[static_cast<int>(block->GetComponent(c, 0))].insert(ids->GetId(k));
  }
  // Voussoir v (0 at the right springing) by the angle of its centroid; the base is number 11.
  std::vector<BlockMotion> motion(n_voussoirs + 1);
  for (const auto& [id, points] : points_of_block) {
    BlockMotion m;
    std::vector<std::array<double, 4>> pairs; // start x, y; now x, y
    for (const vtkIdType p : points) {
      double x[3];
      grid->GetPoint(p, x);
      pairs.push_back({x[0] - displacement->GetComponent(p, 0),
                       x[1] - displacement->GetComponent(p, 1), x[0], x[1]});
    }
    for (const auto& q : pairs) {
      for (int i = 0; i < 2; ++i) {
        m.start[i] += q[i] / static_cast<double>(pairs.size());
        m.now[i] += q[2 + i] / static_cast<double>(pairs.size());
      }
    }
    double cross = 0.0;
    double dot = 0.0;
    for (const auto& q : pairs) {
      const double ax = q[0] - m.start[0];
      const double ay = q[1] - m.start[1];
      const double bx = q[2] - m.now[0];
      const double by = q[3] - m.now[1];
      cross += ax * by - ay * bx;
      dot += ax * bx + ay * by;
    }
    m.angle = std::atan2(cross, dot);
    m.found = true;
    const int v = m.start[1] < 0.0
                      ? n_voussoirs
                      : static_cast<int>(std::atan2(m.start[1], m.start[0]) / (M_PI / n_voussoirs));
    EXPECT_TRUE(v >= 0 && v <= n_voussoirs && !motion[static_cast<std::size_t>(v)].found)
        << "block " << id << " starts at (" << m.start[0] << ", " << m.start[1] << ")";
    if (v >= 0 && v <= n_voussoirs)
      motion[static_cast<std::size_t>(v)] = m;
  }
  EXPECT_EQ(points_of_block.size(), static_cast<std::size_t>(n_voussoirs + 1))
      << "11 voussoirs and the base";

  std::vector<JointOpening> openings;
  for (int k = 0; k <= n_voussoirs; ++k) {
    const double a = M_PI * k / n_voussoirs;
    // Joint k lies between the block on its right (voussoir k - 1, the base for k = 0) and
    // the one on its left (voussoir k, the base for k = 11); its normal points to the left.
    const BlockMotion& right = motion[static_cast<std::size_t>(k == 0 ? n_voussoirs : k - 1)];
    const BlockMotion& left = motion[static_cast<std::size_t>(k)];
    const double nx = -std::sin(a);
    const double ny = std::cos(a);
    const double sin_a = k == n_voussoirs ? 0.0 : std::sin(a);
    const auto gap = [&](double r) {
      const std::array<double, 2> end{r * std::cos(a), r * sin_a};
      const std::array<double, 2> l = left.place(end);
      const std::array<double, 2> q = right.place(end);
      return (l[0] - q[0]) * nx + (l[1] - q[1]) * ny;
    };
    openings.push_back({gap(intrados), gap(extrados)});
  }
  return openings;
}

std::string case_text_with(double force, double end_time) {
  std::string text = read_text(example / "case.toml");
  text = replaced(text, "geometry = \"block_arch.geo\"",
                  "geometry = \"" + (example / "block_arch.geo").string() + "\"");
  text = replaced(text, "force = [0.0, -77195.0]", "force = [0.0, " + std::to_string(-force) + "]");
  return replaced(text, "end_time = 0.3 ", "end_time = " + std::to_string(end_time) + " ");
}

/// Runs examples/09_block_arch as the user does (testing::Example).
class BlockArch : public testing::Example {};

TEST_F(BlockArch, StandsUnderSevenTenthsOfItsCollapseLoad) {
  // The shipped case with 0.7 P_c instead of 1.5 P_c, run to 0.3 s (the load is full from
  // 0.1 s on). Elastic: the crown of a clamped slender elastic arch moves 0.016 P R^3 / (E I)
  // = 0.08 mm under this load (P = 36 kN/m, R = 2 m, E I = 5.3e7 N m^2: bending and
  // shortening); shear in this thick arch, the elastic base and joints opening in part
  // soften it. Measured: at most 0.19 mm, and it no longer moves after the ramp
  // (0.2 to 0.3 s: 1e-6 m). Bounds: 0.5 mm (the collapse falls 6.4 mm in 0.18 s) and
  // 2e-5 m of creep over the last 0.1 s (at 0.95 P_c the arch sinks 0.7 mm in it).
  const fs::path case_file = dir() / "case.toml";
  testing::write_text(case_file, case_text_with(0.7 * collapse_load, 0.3));
  const ExampleRun run = run_case(case_file, "out");
  const std::vector<double>& time = run.history.at("time");
  const std::vector<double>& uy = run.history.at("key.uy");
  ASSERT_FALSE(time.empty());
  ASSERT_EQ(uy.size(), time.size());
  EXPECT_NEAR(time.back(), 0.3, 1e-9);
  double largest = 0.0;
  double at_0_2 = 0.0;
  for (std::size_t k = 0; k < uy.size(); ++k) {
    largest = std::max(largest, std::abs(uy[k]));
    if (time[k] <= 0.2 + 1e-9)
      at_0_2 = uy[k];
  }
  EXPECT_LT(largest, 0.5e-3) << "the key block moved more than an elastic arch would";
  EXPECT_GT(largest, 0.02e-3) << "the load did not reach the arch";
  EXPECT_LT(std::abs(uy.back() - at_0_2), 2e-5) << "the arch still moves under a constant load";
}

TEST_F(BlockArch, CollapsesUnderOneAndAHalfTimesItByThePredictedHingesWithoutGainingEnergy) {
  // The case as shipped: 1.5 P_c, ramped in over 0.1 s, 0.3 s: the crown falls several
  // centimetres and the hinges turn well past the 3 degrees at which the contacts of an
  // opening joint change from an edge-to-edge pair to angle contacts (that change used to
  // throw the blocks apart: docs/formulation.md).
  const ExampleRun run = this->run("09_block_arch");
  const fs::path out = dir() / "09_block_arch";
  EXPECT_NE(run.process.out.find("warnings: none"), std::string::npos) << run.process.out;
  EXPECT_NEAR(run.last("time"), 0.3, 1e-9);
  EXPECT_LT(std::abs(run.last("key.ux")), 1e-4) << "symmetric: the key block drops";
  // The fall. Rigid blocks on the predicted hinges (limit_analysis.py, finite rotations)
  // lower the crown by 48.6 mm in 0.3 s under 1.5 P_c. nmm's arch carries 0.90 to 0.95 P_c
  // (README): it falls as rigid blocks do under 1.5 P_c plus the capacity it lacks, 1.55
  // to 1.6 P_c: 58.2 to 69.1 mm (--factor 1.55, 1.6). Measured: 64.6 mm.
  EXPECT_LT(run.last("key.uy"), -58.2e-3);
  EXPECT_GT(run.last("key.uy"), -69.1e-3);
  // The energy balance. Nothing but the contacts can put energy in, and the collapse of
  // nearly rigid blocks turning about hinges dissipates little: the kinetic energy stays
  // below the work of the loads (it starts at rest) and, once the mechanism moves (from
  // 0.15 s, 3 mm of fall), above nine tenths of it. Measured: at most 0.998 of it; at
  // least 0.954 (where hinges change from edge-to-edge to angle contacts, which absorb
  // the springs' penetration).
  const std::vector<double>& time = run.history.at("time");
  const std::vector<double>& kinetic = run.history.at("kinetic_energy");
  const std::vector<double>& work = run.history.at("load_work");
  double most = 0.0;
  double least = 1.0;
  for (std::size_t k = 0; k < time.size(); ++k) {
    EXPECT_LE(kinetic[k], work[k]) << "at t = " << time[k] << " s";
    if (work[k] > 0.0)
      most = std::max(most, kinetic[k] / work[k]);
    if (time[k] >= 0.15)
      least = std::min(least, kinetic[k] / work[k]);
  }
  std::printf("block arch: key block fell %.2f mm; kinetic energy / work of the loads at most "
              "%.4f, from 0.15 s at least %.4f\n",
              -1e3 * run.last("key.uy"), most, least);
  EXPECT_GT(least, 0.9);

  // The last step file: the six predicted hinges open, by the same amount on both sides;
  // every other joint stays closed (a joint the mechanism did not predict would open by
  // centimetres, like the others). Measured: 33.2 mm at the springings, 95.4 mm at joints 3
  // and 8, 62.2 mm at the key block's joints, the same on both sides to 0.02 mm; the
  // others below 0.07 mm.
  std::string last_step;
  for (const PvdEntry& entry : read_pvd(out / "case.pvd")) {
    if (entry.part == 0)
      last_step = entry.file;
  }
  ASSERT_FALSE(last_step.empty());
  const std::vector<JointOpening> opening = joint_openings(out / last_step);
  ASSERT_EQ(opening.size(), static_cast<std::size_t>(n_voussoirs + 1));
  const std::map<int, std::pair<bool, double>> hinges = {
      // joint: (opens at the intrados?, at least this much)
      {0, {true, 20e-3}}, {3, {false, 60e-3}}, {5, {true, 40e-3}},
      {6, {true, 40e-3}}, {8, {false, 60e-3}}, {11, {true, 20e-3}}};
  for (int k = 0; k <= n_voussoirs; ++k) {
    const JointOpening& o = opening[static_cast<std::size_t>(k)];
    std::printf("joint %2d: intrados %+.3f mm, extrados %+.3f mm\n", k, 1e3 * o.at_intrados,
                1e3 * o.at_extrados);
    const auto hinge = hinges.find(k);
    if (hinge == hinges.end()) {
      EXPECT_LT(std::max(std::abs(o.at_intrados), std::abs(o.at_extrados)), 0.5e-3)
          << "joint " << k << " opened";
      continue;
    }
    const auto [at_intrados, least_opening] = hinge->second;
    // The hinge is the other end, closed.
    EXPECT_GT(at_intrados ? o.at_intrados : o.at_extrados, least_opening) << "joint " << k;
    EXPECT_LT(std::abs(at_intrados ? o.at_extrados : o.at_intrados), 0.5e-3) << "joint " << k;
    const JointOpening& mirror = opening[static_cast<std::size_t>(n_voussoirs - k)];
    EXPECT_NEAR(o.at_intrados, mirror.at_intrados, 0.5e-3) << "joint " << k;
    EXPECT_NEAR(o.at_extrados, mirror.at_extrados, 0.5e-3) << "joint " << k;
  }
}

} // namespace
} // namespace nmm
