// SPDX-License-Identifier: MIT
// tests/verification/excavation_test.cpp — excavation in stages (`[[stage]]`, issue 46 item
// 3) against Kirsch: continuous elastic rock under an in-situ stress (sxx, syy) in stage 1,
// a circular opening of radius a excavated in stage 2, its tractions released over the
// stage's steps. At the wall (plane strain, tension positive, theta from x) the excavation
// moves the rock by u_r = a / (2G) (P + (3 - 4 nu) S cos 2 theta), P = (sxx + syy) / 2,
// S = (sxx - syy) / 2 (Kirsch 1898; Jaeger, Cook and Zimmerman 8.4), and the hoop stress is
// sxx + syy - 2 (sxx - syy) cos 2 theta. A quarter of a 120 a x 120 a plate (rollers on the
// axes, the in-situ tractions on the outer edges: the finite plate moves the wall by about
// (a / R)^2 = 0.03% more than the infinite one, 2.3% of the small side displacement of
// k0 = 0.5 at R = 20 a), order-1 covers on a gmsh math mesh graded
// from a / 20 at the wall, the circle sampled to 1e-4 m (the automatic curve_tolerance, 1e-2
// of the largest edge, 2 m, would make the wall a 16-gon 0.02 m off the circle, whose
// corners put the hoop stress 13-33% off). Tolerance 2% of each wall value (the issue's): the
// side's displacement P + (3 - 4 nu) S is a difference of terms two to three times larger.
#include "io/case_file.hpp"
#include "io/case_runner.hpp"
#include "mesh/error.hpp"

#include "../support/json_reader.hpp"
#include "../support/process.hpp"
#include <gtest/gtest.h>

#include <cstdio>
#include <sstream>
#include <string>

namespace nmm {
namespace {

using testing::parse_json;
using testing::read_text;
using testing::TempDir;
using testing::write_text;

constexpr double young = 1.0e10;
constexpr double poisson = 0.25;
constexpr double radius = 1.0;
constexpr double half = 60.0; // the quarter plate's side, m

/// The quarter plate of side @p side with the quarter disc "tunnel" at the origin and the
/// rock around it; without @p tunnel the opening is there from the start (no "tunnel").
/// @p jointed: the circle is the joint "wall" between the two (two blocks in contact).
std::string plate_geo(double side = half, bool tunnel = true, bool jointed = false) {
  std::ostringstream geo;
  geo << "a = " << radius << ";\nR = " << side << ";\nh = a / 20;\nH = 4.0;\n"
      << "Point(1) = {0, 0, 0, h};\nPoint(2) = {a, 0, 0, h};\nPoint(3) = {R, 0, 0, H};\n"
      << "Point(4) = {R, R, 0, H};\nPoint(5) = {0, R, 0, H};\nPoint(6) = {0, a, 0, h};\n"
      << "Line(1) = {1, 2};\nLine(2) = {2, 3};\nLine(3) = {3, 4};\nLine(4) = {4, 5};\n"
      << "Line(5) = {5, 6};\nLine(6) = {6, 1};\nCircle(7) = {2, 1, 6};\n"
      << "Curve Loop(1) = {2, 3, 4, 5, -7};\nPlane Surface(1) = {1};\n"
      << "Physical Surface(\"rock\") = {1};\n"
      << "Physical Curve(\"right\") = {3};\nPhysical Curve(\"top\") = {4};\n";
  if (tunnel)
    geo << "Curve Loop(2) = {1, 7, 6};\nPlane Surface(2) = {2};\n"
        << "Physical Surface(\"tunnel\") = {2};\n"
        << "Physical Curve(\"bottom\") = {1, 2};\nPhysical Curve(\"left\") = {5, 6};\n"
        << (jointed ? "Physical Curve(\"wall\") = {7};\n" : "");
  else
    geo << "Physical Curve(\"bottom\") = {2};\nPhysical Curve(\"left\") = {5};\n";
  return geo.str();
}

/// The case: stage "in_situ" (one static step under the in-situ stress), then stage
/// "excavate" of @p release_steps static steps removing "tunnel", displacements counted
/// from its start; monitors just inside the rock at the side (a, 0) and the crown (0, a).
/// @p cover_mesh replaces the [cover_mesh] keys; without @p tunnel, the opening of
/// plate_geo(side, false) in one static step instead of the stages. @p jointed: the joint
/// "wall" of plate_geo(side, true, true), frictional.
std::string plate_case(double sxx,
                       double syy,
                       int release_steps,
                       const std::string& cover_mesh = "kind = \"gmsh\"\ngeometry_sizes = true\n"
                                                       "size = 4.0\ncurve_tolerance = 1.0e-4\n",
                       bool tunnel = true,
                       bool jointed = false) {
  std::ostringstream text;
  text.precision(17);
  text << "geometry = \"plate.geo\"\n[cover_mesh]\n" << cover_mesh << "order = 1\n";
  for (const char* material : {"rock", "tunnel"}) {
    if (!tunnel && std::string(material) == "tunnel")
      continue;
    text << "[materials." << material << "]\nyoung = " << young << "\npoisson = " << poisson
         << "\ninitial_stress = [" << sxx << ", " << syy << ", 0.0]\n";
  }
  text << "[[boundary]]\ncurve = \"left\"\nfix = \"x\"\n[[boundary]]\ncurve = \"bottom\"\n"
       << "fix = \"y\"\n[[load]]\ncurve = \"right\"\ntraction = [" << sxx << ", 0.0]\n"
       << "[[load]]\ncurve = \"top\"\ntraction = [0.0, " << syy << "]\n"
       << (jointed ? "[joints.wall]\nfriction_angle = 30.0\n" : "")
       << "[analysis]\nkind = \"static\"\n"
       << (tunnel ? "" : "steps = 1\n") << "[[monitor]]\nname = \"side\"\npoint = ["
       << radius * (1.0 + 1e-6) << ", 0.0]\n"
       << "[[monitor]]\nname = \"crown\"\npoint = [0.0, " << radius * (1.0 + 1e-6) << "]\n";
  if (tunnel)
    text << "[[stage]]\nname = \"in_situ\"\nsteps = 1\n"
         << "[[stage]]\nname = \"excavate\"\nsteps = " << release_steps
         << "\nexcavate = [\"tunnel\"]\nreset_displacement = true\n";
  return text.str();
}

struct WallValues {
  double side_u = 0.0;     ///< ux at (a, 0) since the excavation's start, m
  double crown_u = 0.0;    ///< uy at (0, a), m
  double side_hoop = 0.0;  ///< syy at (a, 0), Pa
  double crown_hoop = 0.0; ///< sxx at (0, a), Pa
  double in_situ_u = 0.0;  ///< the largest monitor displacement after stage 1, m
  /// ux at (a, 0) and uy at (0, a) at the end of each step of the excavation's stage, m.
  std::vector<double> side_steps;
  std::vector<double> crown_steps;
  std::vector<std::string> warnings;
  std::string history; ///< history.csv
  std::string summary; ///< summary.json
};

WallValues excavate(double sxx, double syy, int release_steps, bool jointed = false) {
  const TempDir dir("nmm_excavation");
  write_text(dir.path() / "plate.geo", plate_geo(half, true, jointed));
  const std::string cover_mesh = "kind = \"gmsh\"\ngeometry_sizes = true\nsize = 4.0\n"
                                 "curve_tolerance = 1.0e-4\n";
  write_text(dir.path() / "case.toml",
             plate_case(sxx, syy, release_steps, cover_mesh, true, jointed));
  CaseAnalysis analysis(read_case_file(dir.path() / "case.toml"));
  RunOptions options;
  options.output_dir = dir.path() / "out";
  WallValues wall;
  options.on_step = [&](const RunProgress& progress) {
    const std::vector<MonitorValues> now = analysis.monitor_values();
    if (progress.report->step == 1) {
      for (const MonitorValues& m : now)
        wall.in_situ_u = std::max({wall.in_situ_u, std::abs(m.ux), std::abs(m.uy)});
    } else {
      wall.side_steps.push_back(now[0].ux);
      wall.crown_steps.push_back(now[1].uy);
    }
  };
  wall.warnings = run_case(analysis, options).warnings;
  const std::vector<MonitorValues> m = analysis.monitor_values();
  wall.side_u = m[0].ux;
  wall.side_hoop = m[0].syy;
  wall.crown_u = m[1].uy;
  wall.crown_hoop = m[1].sxx;
  wall.history = read_text(dir.path() / "out" / "history.csv");
  wall.summary = read_text(dir.path() / "out" / "summary.json");
  return wall;
}

/// Kirsch's radial displacement of the excavation at the wall, angle @p theta from x.
double kirsch_u(double sxx, double syy, double theta) {
  const double shear_modulus = young / (2.0 * (1.0 + poisson));
  return radius / (2.0 * shear_modulus) *
         ((sxx + syy) / 2.0 + (3.0 - 4.0 * poisson) * (sxx - syy) / 2.0 * std::cos(2.0 * theta));
}

double kirsch_hoop(double sxx, double syy, double theta) {
  return sxx + syy - 2.0 * (sxx - syy) * std::cos(2.0 * theta);
}

struct InSitu {
  double sxx;
  double syy;
  int release_steps;
};

class ExcavatedOpening : public ::testing::TestWithParam<InSitu> {};

TEST_P(ExcavatedOpening, MovesAndStressesItsWallAsKirschToTwoPercent) {
  const InSitu& c = GetParam();
  const WallValues wall = excavate(c.sxx, c.syy, c.release_steps);
  constexpr double pi = 3.14159265358979323846;
  const double side_u = kirsch_u(c.sxx, c.syy, 0.0);
  const double crown_u = kirsch_u(c.sxx, c.syy, pi / 2.0);
  const double side_hoop = kirsch_hoop(c.sxx, c.syy, 0.0);
  const double crown_hoop = kirsch_hoop(c.sxx, c.syy, pi / 2.0);
  std::printf("[excavation] sxx %g syy %g, %d steps: side u %.5f, crown u %.5f, side hoop "
              "%.5f, crown hoop %.5f of Kirsch; stage 1 moved %.3g m\n",
              c.sxx, c.syy, c.release_steps, wall.side_u / side_u, wall.crown_u / crown_u,
              wall.side_hoop / side_hoop, wall.crown_hoop / crown_hoop, wall.in_situ_u);
  EXPECT_NEAR(wall.side_u, side_u, 0.02 * std::abs(side_u));
  EXPECT_NEAR(wall.crown_u, crown_u, 0.02 * std::abs(crown_u));
  EXPECT_NEAR(wall.side_hoop, side_hoop, 0.02 * std::abs(side_hoop));
  EXPECT_NEAR(wall.crown_hoop, crown_hoop, 0.02 * std::abs(crown_hoop));
  // Stage 1 is the in-situ state in equilibrium: nothing moves before the excavation.
  EXPECT_LT(wall.in_situ_u, 1e-6 * std::abs(crown_u));
  // history.csv and summary.json name the stages.
  const std::string header = wall.history.substr(0, wall.history.find('\n'));
  EXPECT_EQ(header.substr(header.rfind(',') + 1), "stage");
  EXPECT_NE(wall.history.find(",in_situ\n"), std::string::npos);
  EXPECT_EQ(wall.history.substr(wall.history.rfind(',', wall.history.size() - 2)), ",excavate\n");
  const testing::Json summary = parse_json(wall.summary);
  EXPECT_EQ(summary.at("stage").string, "excavate");
  ASSERT_EQ(summary.at("stages").items.size(), 2u);
  EXPECT_EQ(summary.at("stages").items[1].at("first_step").number, 2.0);
}

INSTANTIATE_TEST_SUITE_P(Stages,
                         ExcavatedOpening,
                         ::testing::Values(InSitu{-5.0e6, -10.0e6, 4},    // k0 = 0.5, released in 4
                                           InSitu{-8.0e6, -8.0e6, 1},     // hydrostatic, at once
                                           InSitu{-12.0e6, -6.0e6, 10})); // k0 = 2

/// The opening's disc a block of its own, held by the frictional joint "wall" along the
/// circle (its springs preloaded with the in-situ traction, so that stage 1 is in
/// equilibrium): excavated, the disc's contacts go with it, and the forces they held the rock
/// with are released as loads on the rock's wall, evenly over the stage's steps, as the
/// tractions of the continuous region above are. Step by step the wall moves as the
/// continuous rock's does, to 1e-3 of the excavation's displacement (measured: 1e-4, the
/// contact points' forces standing for the traction along the wall), the first step by
/// 1/n of it to 1% (the continuous rock's steps themselves differ by 0.5%: stresses added
/// on the moved geometry), and the wall ends as Kirsch's hole to 2%. All at once, the
/// first step would move it the whole way.
class JointedOpening : public ::testing::TestWithParam<InSitu> {};

TEST_P(JointedOpening, ReleasesItsContactForcesAsTheContinuousRocksTractions) {
  const InSitu& c = GetParam();
  const WallValues wall = excavate(c.sxx, c.syy, c.release_steps, true);
  const WallValues rock = excavate(c.sxx, c.syy, c.release_steps, false);
  constexpr double pi = 3.14159265358979323846;
  const double side_u = kirsch_u(c.sxx, c.syy, 0.0);
  const double crown_u = kirsch_u(c.sxx, c.syy, pi / 2.0);
  std::printf("[excavation] jointed, sxx %g syy %g, %d steps: side u %.5f, crown u %.5f, side "
              "hoop %.5f, crown hoop %.5f of Kirsch; stage 1 moved %.3g m; first step %.5f "
              "of 1/n\n",
              c.sxx, c.syy, c.release_steps, wall.side_u / side_u, wall.crown_u / crown_u,
              wall.side_hoop / kirsch_hoop(c.sxx, c.syy, 0.0),
              wall.crown_hoop / kirsch_hoop(c.sxx, c.syy, pi / 2.0), wall.in_situ_u,
              wall.crown_steps.front() * c.release_steps / wall.crown_u);
  EXPECT_NEAR(wall.side_u, side_u, 0.02 * std::abs(side_u));
  EXPECT_NEAR(wall.crown_u, crown_u, 0.02 * std::abs(crown_u));
  EXPECT_NEAR(wall.side_hoop, kirsch_hoop(c.sxx, c.syy, 0.0),
              0.02 * std::abs(kirsch_hoop(c.sxx, c.syy, 0.0)));
  EXPECT_NEAR(wall.crown_hoop, kirsch_hoop(c.sxx, c.syy, pi / 2.0),
              0.02 * std::abs(kirsch_hoop(c.sxx, c.syy, pi / 2.0)));
  EXPECT_LT(wall.in_situ_u, 1e-6 * std::abs(crown_u));
  ASSERT_EQ(wall.side_steps.size(), static_cast<std::size_t>(c.release_steps));
  ASSERT_EQ(rock.side_steps.size(), wall.side_steps.size());
  for (std::size_t i = 0; i < wall.side_steps.size(); ++i) {
    EXPECT_NEAR(wall.side_steps[i], rock.side_steps[i], 1e-3 * std::abs(rock.side_u))
        << "step " << i + 1;
    EXPECT_NEAR(wall.crown_steps[i], rock.crown_steps[i], 1e-3 * std::abs(rock.crown_u))
        << "step " << i + 1;
  }
  const double n = c.release_steps;
  EXPECT_NEAR(wall.crown_steps.front(), wall.crown_u / n, 0.01 * std::abs(wall.crown_u) / n);
  EXPECT_NEAR(wall.side_steps.front(), wall.side_u / n, 0.01 * std::abs(wall.side_u) / n);
  for (const std::string& warning : wall.warnings)
    ADD_FAILURE() << warning;
}

INSTANTIATE_TEST_SUITE_P(Stages,
                         JointedOpening,
                         ::testing::Values(InSitu{-5.0e6, -10.0e6, 4},    // k0 = 0.5
                                           InSitu{-12.0e6, -6.0e6, 10})); // k0 = 2

/// A block of rock of length L beside a prop block, both under the in-situ stress (-p, -p),
/// between rollers (top and bottom held in y, the outer ends in x) and joined by the joint
/// "cut" at x = L: excavating the prop frees the rock's face, which the forces of their
/// contacts held. Released over n steps, the face moves by k/n of p L / M at step k (M =
/// E (1 - nu) / ((1 + nu) (1 - 2 nu)), the constrained modulus of plane strain: the rock
/// keeps eyy = 0), its sxx goes to 0 and its syy to -p (1 - nu / (1 - nu)). Constant strain:
/// exact for DDA and VEM blocks and NMM covers of either order, to the solver's rounding
/// and the monitor's 1e-6 m from the face (1e-4 of the displacement).
struct Box {
  std::string model; ///< the materials' model
  std::string cover; ///< the [cover_mesh] keys
  double length;     ///< L, m
  int release_steps; ///< n
};

class ExcavatedProp : public ::testing::TestWithParam<Box> {};

TEST_P(ExcavatedProp, FreesTheRocksFaceEvenlyOverTheStage) {
  const Box& box = GetParam();
  const double p = 2.0e6;
  const double length = box.length;
  std::ostringstream geo;
  geo << "L = " << length << ";\nPoint(1) = {0, 0, 0};\nPoint(2) = {L, 0, 0};\n"
      << "Point(3) = {2 * L, 0, 0};\nPoint(4) = {2 * L, 1, 0};\nPoint(5) = {L, 1, 0};\n"
      << "Point(6) = {0, 1, 0};\nLine(1) = {1, 2};\nLine(2) = {2, 3};\nLine(3) = {3, 4};\n"
      << "Line(4) = {4, 5};\nLine(5) = {5, 6};\nLine(6) = {6, 1};\nLine(7) = {2, 5};\n"
      << "Curve Loop(1) = {1, 7, 5, 6};\nPlane Surface(1) = {1};\n"
      << "Curve Loop(2) = {2, 3, 4, -7};\nPlane Surface(2) = {2};\n"
      << "Physical Surface(\"rock\") = {1};\nPhysical Surface(\"prop\") = {2};\n"
      << "Physical Curve(\"cut\") = {7};\nPhysical Curve(\"ends\") = {3, 6};\n"
      << "Physical Curve(\"rollers\") = {1, 2, 4, 5};\n";
  std::ostringstream text;
  text.precision(17);
  text << "geometry = \"box.geo\"\n[cover_mesh]\n" << box.cover << "\n";
  for (const char* material : {"rock", "prop"})
    text << "[materials." << material << "]\nmodel = \"" << box.model << "\"\nyoung = " << young
         << "\npoisson = " << poisson << "\ninitial_stress = [" << -p << ", " << -p << ", 0.0]\n";
  text << "[joints.cut]\nfriction_angle = 30.0\n"
       << "[[boundary]]\ncurve = \"ends\"\nfix = \"x\"\n"
       << "[[boundary]]\ncurve = \"rollers\"\nfix = \"y\"\n"
       << "[analysis]\nkind = \"static\"\n[[monitor]]\nname = \"face\"\npoint = [" << length - 1e-6
       << ", 0.5]\n"
       << "[[stage]]\nname = \"in_situ\"\nsteps = 1\n[[stage]]\nname = \"excavate\"\nsteps = "
       << box.release_steps << "\nexcavate = [\"prop\"]\nreset_displacement = true\n";
  SCOPED_TRACE(box.model + ", " + box.cover);
  const TempDir dir("nmm_excavation_prop");
  write_text(dir.path() / "box.geo", geo.str());
  write_text(dir.path() / "case.toml", text.str());
  CaseAnalysis analysis(read_case_file(dir.path() / "case.toml"));
  RunOptions options;
  options.output_dir = dir.path() / "out";
  std::vector<MonitorValues> steps;
  options.on_step = [&](const RunProgress& progress) {
    if (progress.report->step > 1)
      steps.push_back(analysis.monitor_values()[0]);
  };
  const RunResult result = run_case(analysis, options);
  const double m = young * (1.0 - poisson) / ((1.0 + poisson) * (1.0 - 2.0 * poisson));
  const double u = p * length / m;
  ASSERT_EQ(steps.size(), static_cast<std::size_t>(box.release_steps));
  for (std::size_t k = 0; k < steps.size(); ++k) {
    const double done = static_cast<double>(k + 1) / box.release_steps;
    EXPECT_NEAR(steps[k].ux, done * u, 1e-4 * u) << "step " << k + 1;
    EXPECT_NEAR(steps[k].sxx, -(1.0 - done) * p, 1e-6 * p) << "step " << k + 1;
  }
  EXPECT_NEAR(steps.back().syy, -p * (1.0 - poisson / (1.0 - poisson)), 1e-6 * p);
  // (Order-1 covers of a regular mesh warn that their release over steps is not verified
  // near an opening's curved wall; here it is exact.)
  for (const std::string& warning : result.warnings) {
    if (warning.find("is not verified yet") == std::string::npos)
      ADD_FAILURE() << warning;
  }
}

INSTANTIATE_TEST_SUITE_P(
    Stages,
    ExcavatedProp,
    ::testing::Values(Box{"dda", "kind = \"regular\"\nsize = 0.5", 1.0, 5},
                      Box{"vem", "kind = \"regular\"\nsize = 0.5", 2.5, 3},
                      Box{"nmm", "kind = \"regular\"\nsize = 0.3", 1.0, 4},
                      Box{"nmm", "kind = \"regular\"\nsize = 0.3\norder = 1", 2.5, 5},
                      Box{"nmm", "kind = \"gmsh\"\nsize = 0.2\norder = 1", 1.0, 2}));

/// The monitors' values at the end of the case @p text on plate_geo(@p side, @p tunnel).
std::vector<MonitorValues> wall_after(const std::string& text, double side, bool tunnel) {
  const TempDir dir("nmm_excavation_same");
  write_text(dir.path() / "plate.geo", plate_geo(side, tunnel));
  write_text(dir.path() / "case.toml", text);
  CaseAnalysis analysis(read_case_file(dir.path() / "case.toml"));
  RunOptions options;
  options.output_dir = dir.path() / "out";
  (void)run_case(analysis, options);
  return analysis.monitor_values();
}

/// On a regular math mesh, which the wall cuts the same way with or without the region
/// "tunnel", the rock excavated in stage 2 is the rock meshed with the opening from the start:
/// the same covers and pieces carry the same loads (the tunnel's supports, covers and loads
/// gone with it), so the wall moves and is stressed the same to rounding (1e-9). Released
/// in one step: over several, order-1 covers of a cut mesh are not right yet (the crown's
/// stress 0.03 a inside the rock, -9.5 MPa and +11 MPa over 3 steps against -4.5 and -0.16 in
/// one; order 0 agrees to 0.5%), and the case warns (below).
TEST(ExcavatedOpening, IsTheOpeningMeshedFromTheStartOnTheSameMathMesh) {
  const std::string regular = "size = 0.1\n";
  const double side = 5.0;
  const auto staged = wall_after(plate_case(-5.0e6, -10.0e6, 1, regular), side, true);
  const auto meshed = wall_after(plate_case(-5.0e6, -10.0e6, 1, regular, false), side, false);
  // 1e-9 of the wall's displacement (1e-3 m) and of the in-situ stress (1e7 Pa).
  for (std::size_t k = 0; k < 2; ++k) {
    const char* where = k == 0 ? "side" : "crown";
    EXPECT_NEAR(staged[k].ux, meshed[k].ux, 1e-12) << where;
    EXPECT_NEAR(staged[k].uy, meshed[k].uy, 1e-12) << where;
    EXPECT_NEAR(staged[k].sxx, meshed[k].sxx, 1e-2) << where;
    EXPECT_NEAR(staged[k].syy, meshed[k].syy, 1e-2) << where;
  }
}

TEST(ExcavatedOpening, ReleasedOverStepsOnACutOrderOneMeshWarns) {
  const TempDir dir("nmm_excavation_warns");
  write_text(dir.path() / "plate.geo", plate_geo(5.0, true));
  write_text(dir.path() / "case.toml", plate_case(-5.0e6, -10.0e6, 3, "size = 0.1\n"));
  const CaseAnalysis analysis(read_case_file(dir.path() / "case.toml"));
  ASSERT_EQ(analysis.warnings().size(), 1u);
  EXPECT_NE(analysis.warnings()[0].find("releases its excavation over 3 steps"), std::string::npos)
      << analysis.warnings()[0];
  write_text(dir.path() / "case.toml", plate_case(-5.0e6, -10.0e6, 1, "size = 0.1\n"));
  EXPECT_TRUE(CaseAnalysis(read_case_file(dir.path() / "case.toml")).warnings().empty());
}

} // namespace
} // namespace nmm
