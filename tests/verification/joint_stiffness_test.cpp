// SPDX-License-Identifier: MIT
// Joint stiffness (issue 46, item 4): a joint's `normal_stiffness` and `shear_stiffness`
// (Pa/m) act per unit length of its edge-to-edge contacts, each then a Goodman joint element
// of that stiffness (Riahi et al., eq. 21 and 43). A stack of blocks pressed by p shortens by
// the blocks' elastic shortening plus n p / kn; a joint sheared below its friction limit
// slips by tau / ks. DDA blocks and NMM bodies, two stiffnesses each, to 0.5%.
#include "io/case_runner.hpp"
#include "mesh/error.hpp"

#include "../support/process.hpp"
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>

namespace nmm {
namespace {

using testing::TempDir;
using testing::write_text;

/// A column 1 m wide of @p blocks blocks 0.5 m tall, cut by horizontal joints "j" at every
/// 0.5 m; Physical Curves "base" (y = 0), "top", "left" and "right", Physical Point "corner"
/// (0, 0).
std::string column_geo(int blocks) {
  const double h = 0.5 * blocks;
  std::ostringstream geo;
  geo << "Point(1) = {0, 0, 0};\nPoint(2) = {1, 0, 0};\nPoint(3) = {1, " << h
      << ", 0};\nPoint(4) = {0, " << h << ", 0};\n"
      << "Line(1) = {1, 2};\nLine(2) = {2, 3};\nLine(3) = {3, 4};\nLine(4) = {4, 1};\n"
      << "Curve Loop(1) = {1, 2, 3, 4};\nPlane Surface(1) = {1};\n";
  std::string joints;
  for (int k = 1; k < blocks; ++k) {
    const int a = 10 + 2 * k;
    geo << "Point(" << a << ") = {0, " << 0.5 * k << ", 0};\nPoint(" << a + 1 << ") = {1, "
        << 0.5 * k << ", 0};\nLine(" << a << ") = {" << a << ", " << a + 1 << "};\n";
    joints += (joints.empty() ? "" : ", ") + std::to_string(a);
  }
  geo << "Physical Surface(\"rock\") = {1};\nPhysical Curve(\"base\") = {1};\n"
      << "Physical Curve(\"top\") = {3};\nPhysical Curve(\"j\") = {" << joints << "};\n"
      << "Physical Curve(\"left\") = {4};\nPhysical Curve(\"right\") = {2};\n"
      << "Physical Point(\"corner\") = {1};\n";
  return geo.str();
}

constexpr double young = 1.0e9;  // Pa, Poisson's ratio 0: uniaxial stress, no lateral strain
constexpr double gauge = 2.0e-5; // m: the distance between the points that measure the slip

/// The case of a column of @p blocks blocks, the joints of stiffness @p kn, @p ks, the top
/// pressed by @p pressure; Shi's static steps of 1 s; monitors "top" at (0.5, top) and
/// "above", "below" 10 um either side of the lowest joint at x = 0.5. Without @p shear the
/// base is held in y and its corner in x; with it the base is held and the column is in
/// uniform shear @p shear: the traction (shear, -pressure) on the top and the complementary
/// shear on its sides, (0, -shear) on the left and (0, shear) on the right, so that every
/// point of the joint slips alike (a shear on the top alone would also bend the column).
std::string column_case(
    const std::string& model, int blocks, double kn, double ks, double pressure, double shear) {
  std::ostringstream c;
  c.precision(17);
  c << "geometry = \"column.geo\"\n[cover_mesh]\nsize = 0.25\n"
    << "[materials.rock]\nmodel = \"" << model << "\"\ndensity = 2000.0\nyoung = " << young
    << "\npoisson = 0.0\n"
    << "[joints.j]\nfriction_angle = 30.0\nnormal_stiffness = " << kn
    << "\nshear_stiffness = " << ks << "\n"
    << "[contact]\nfriction_angle = 30.0\n"
    << "[[boundary]]\ncurve = \"base\"\nfix = \"" << (shear != 0.0 ? "xy" : "y") << "\"\n";
  if (shear == 0.0)
    c << "[[boundary]]\npoint = \"corner\"\nfix = \"x\"\n";
  c << "[[load]]\ncurve = \"top\"\ntraction = [" << shear << ", " << -pressure << "]\n";
  if (shear != 0.0)
    c << "[[load]]\ncurve = \"left\"\ntraction = [0.0, " << -shear << "]\n"
      << "[[load]]\ncurve = \"right\"\ntraction = [0.0, " << shear << "]\n";
  c << "[analysis]\nkind = \"static\"\nsteps = 8\ntime_step = 1.0\n"
    << "[[monitor]]\nname = \"top\"\npoint = [0.5, " << 0.5 * blocks << "]\n"
    << "[[monitor]]\nname = \"above\"\npoint = [0.5, " << 0.5 + gauge / 2 << "]\n"
    << "[[monitor]]\nname = \"below\"\npoint = [0.5, " << 0.5 - gauge / 2 << "]\n";
  return c.str();
}

/// What a column's run ends with.
struct ColumnRun {
  std::vector<MonitorValues> monitors; ///< top, above, below
  double worst_energy_error = 0.0;     ///< largest energy_error of any step
  double largest_contact_energy = 0.0; ///< J
  double external_work = 0.0;          ///< at the end, J
};

/// Runs the case's steps.
ColumnRun run_column(const TempDir& dir, int blocks, const std::string& text) {
  write_text(dir.path() / "column.geo", column_geo(blocks));
  write_text(dir.path() / "case.toml", text);
  CaseAnalysis analysis(read_case_file(dir.path() / "case.toml"));
  ColumnRun run;
  for (long k = 0; k < analysis.spec().analysis.steps; ++k) {
    const StepReport report = analysis.stepper().step(std::numeric_limits<double>::infinity());
    run.worst_energy_error = std::max(run.worst_energy_error, report.energy_error);
    run.largest_contact_energy = std::max(run.largest_contact_energy, report.contact_energy);
    run.external_work = report.external_work;
  }
  run.monitors = analysis.monitor_values();
  return run;
}

/// @p text with the first @p from replaced by @p to.
std::string with(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos)
    text.replace(at, from.size(), to);
  return text;
}

struct StiffnessCase {
  const char* model;
  double stiffness; ///< kn = ks, Pa/m
};

class JointStiffness : public ::testing::TestWithParam<StiffnessCase> {};

TEST_P(JointStiffness, PressedStackShortensByTheBlocksAndNTimesPOverKn) {
  const StiffnessCase& c = GetParam();
  const TempDir dir("nmm_joint_stiffness");
  const int blocks = 3; // two joints
  const double p = 1.0e6;
  const std::vector<MonitorValues> m =
      run_column(dir, blocks, column_case(c.model, blocks, c.stiffness, c.stiffness, p, 0.0))
          .monitors;
  const double height = 0.5 * blocks;
  const double expected = -(p * height / young + (blocks - 1) * p / c.stiffness);
  EXPECT_NEAR(m[0].uy, expected, 5e-3 * std::abs(expected))
      << c.model << " kn = " << c.stiffness << ": joints' share "
      << (m[0].uy + p * height / young) / expected;
}

TEST_P(JointStiffness, JointShearedBelowItsFrictionLimitSlipsByTauOverKs) {
  const StiffnessCase& c = GetParam();
  const TempDir dir("nmm_joint_stiffness");
  // Two blocks, the lower one held at its base, pressed by 1 MPa and in a uniform shear of
  // 0.1 MPa, a sixth of the friction limit (tan 30 degrees x 1 MPa). The slip is the
  // difference of the points 10 um above and below the joint, less the rock's own shear
  // strain between them (tau / G x 20 um, 4e-4 of the slip at the stiffer joint).
  const double p = 1.0e6;
  const double tau = 1.0e5;
  const std::vector<MonitorValues> m =
      run_column(dir, 2, column_case(c.model, 2, 1.0e10, c.stiffness, p, tau)).monitors;
  const double shear_modulus = young / 2.0; // Poisson's ratio 0
  const double slip = m[1].ux - m[2].ux - tau / shear_modulus * gauge;
  EXPECT_NEAR(slip, tau / c.stiffness, 5e-3 * tau / c.stiffness)
      << c.model << " ks = " << c.stiffness;
}

INSTANTIATE_TEST_SUITE_P(DdaAndNmm,
                         JointStiffness,
                         ::testing::Values(StiffnessCase{"dda", 1.0e9},
                                           StiffnessCase{"dda", 1.0e10},
                                           StiffnessCase{"nmm", 1.0e9},
                                           StiffnessCase{"nmm", 1.0e10}),
                         [](const ::testing::TestParamInfo<StiffnessCase>& param) {
                           return std::string(param.param.model) +
                                  (param.param.stiffness < 5e9 ? "Soft" : "Stiff");
                         });

TEST(JointStiffness, SuddenShearBalancesItsEnergyWithTheJointsOwnShearStiffness) {
  // The sheared column of above loaded at once in dynamic steps (0.2 ms), its joint a hundred
  // times softer in shear than in compression: it vibrates, and its locked shear springs store
  // a quarter of the loads' work at times. The energy balance counts them with ks (the
  // normal stiffness would make their energy a hundred times too large).
  for (const char* model : {"dda", "nmm"}) {
    const TempDir dir("nmm_joint_stiffness_energy");
    std::string text = column_case(model, 2, 1.0e10, 1.0e8, 1.0e6, 1.0e5);
    text = with(text, "kind = \"static\"\nsteps = 8\ntime_step = 1.0",
                "kind = \"dynamic\"\nsteps = 300\ntime_step = 2.0e-4");
    const ColumnRun run = run_column(dir, 2, text);
    EXPECT_GT(run.largest_contact_energy, 0.1 * run.external_work) << model;
    EXPECT_LT(run.worst_energy_error, 1e-2) << model;
  }
}

TEST(JointStiffness, ZeroOrNegativeStiffnessIsAnErrorNamingTheFileAndLine) {
  const TempDir dir("nmm_joint_stiffness_bad");
  write_text(dir.path() / "column.geo", column_geo(2));
  for (const std::string key : {"normal_stiffness", "shear_stiffness"}) {
    for (const char* value : {"0.0", "-1.0e9"}) {
      std::string text = column_case("dda", 2, 1e9, 1e9, 1e6, 0.0);
      const std::string line = key + " = 1000000000";
      const std::size_t at = text.find(line);
      ASSERT_NE(at, std::string::npos) << text;
      text.replace(at, line.size(), key + " = " + value);
      write_text(dir.path() / "case.toml", text);
      try {
        static_cast<void>(read_case_file(dir.path() / "case.toml"));
        ADD_FAILURE() << key << " = " << value << " accepted";
      } catch (const InputError& error) {
        const std::string message = error.what();
        const int n = key == "normal_stiffness" ? 11 : 12; // the key's line
        EXPECT_NE(message.find((dir.path() / "case.toml").string() + ":" + std::to_string(n) + ":"),
                  std::string::npos)
            << message;
        EXPECT_NE(message.find("[joints.j] " + key), std::string::npos) << message;
        EXPECT_NE(message.find("> 0"), std::string::npos) << message;
      }
    }
  }
}

} // namespace
} // namespace nmm
