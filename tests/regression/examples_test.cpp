// SPDX-License-Identifier: MIT
// The bundled examples give the right answers their READMEs state (issue 4), run end to end
// by the `nmm` program as a user runs them. The slow ones are in slow_examples_test.cpp.
#include "example_run.hpp"
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace nmm {
namespace {

using testing::Example;
using testing::ExampleRun;
using testing::Json;

TEST_F(Example, GravityColumnSettlesByTheExactQuadratic) {
  // examples/07_gravity_column: a column of height H under its own weight between smooth
  // walls on a smooth base, plane strain. Exact: u_x = 0, u_y = -rho g (H y - y²/2) / M with
  // the constrained modulus M = E (1 - nu) / ((1 + nu) (1 - 2 nu)) = 1.2e9 Pa,
  // syy = -rho g (H - y), sxx = nu / (1 - nu) syy, sxy = 0 (README).
  const ExampleRun example = run("07_gravity_column");
  EXPECT_TRUE(example.summary.at("warnings").items.empty());
  const double rho_g = 2500.0 * 9.81;
  const double height = 10.0;
  const double young = 1.0e9;
  const double poisson = 0.25;
  const double modulus = young * (1.0 - poisson) / ((1.0 + poisson) * (1.0 - 2.0 * poisson));
  auto settlement = [&](double y) { return -rho_g * (height * y - y * y / 2.0) / modulus; };
  const double top = settlement(height); // -1.021875 mm
  // The field is quadratic and order-1 covers hold every quadratic, so what is left is the
  // rounding of the solve: measured 7e-13 (top) and 5e-13 (middle) relative. 1e-10 leaves
  // room for another BLAS or thread count and is five orders below the error of order-0
  // covers on this mesh (1.3e-5).
  EXPECT_NEAR(example.monitor("top", "uy"), top, 1e-10 * std::abs(top));
  EXPECT_NEAR(example.monitor("middle", "uy"), settlement(5.0), 1e-10 * std::abs(top));
  EXPECT_EQ(example.last("top.uy"), example.monitor("top", "uy")); // both %.17g
  for (const char* monitor : {"top", "middle", "bottom"})
    EXPECT_NEAR(example.monitor(monitor, "ux"), 0.0, 1e-10 * std::abs(top)) << monitor;
  // Stresses: the element's linear stress read at the monitor's current position. The stress
  // field moves with the element's origin and the monitor with its own point; the two moves
  // differ by the strain times their distance (2e-4 x 0.25 m at most), which the gradient
  // rho g turns into 1.2 Pa = 5e-6 rho g H. Measured at most 1.5e-6 rho g H (at the base).
  const double weight = rho_g * height; // 245.25 kPa
  const double k0 = poisson / (1.0 - poisson);
  for (const auto& [monitor, y] : {std::pair{"middle", 5.0}, std::pair{"bottom", 0.0}}) {
    EXPECT_NEAR(example.monitor(monitor, "syy"), -rho_g * (height - y), 5e-6 * weight) << monitor;
    EXPECT_NEAR(example.monitor(monitor, "sxx"), -k0 * rho_g * (height - y), 5e-6 * weight)
        << monitor;
    EXPECT_NEAR(example.monitor(monitor, "sxy"), 0.0, 5e-6 * weight) << monitor;
  }
  EXPECT_NEAR(example.monitor("top", "syy"), 0.0, 5e-6 * weight);
}

TEST_F(Example, SingleJointWedgeSlidesDownItsJointAtTheCoulombRate) {
  // examples/14_single_joint_in_triangle: one joint dipping 30 degrees across a triangle held
  // at its base; the wedge above it (friction angle 20 degrees) slides as a rigid block:
  // a = g (sin 30 - tan 20 cos 30) = 1.8128 m/s^2, s = a t^2 / 2 = 0.9064 m and v = a t
  // after 1 s, kinetic energy rho A v^2 / 2 with the wedge's area A = 15.470 m^2 (README).
  const ExampleRun example = run("14_single_joint_in_triangle");
  EXPECT_TRUE(example.summary.at("warnings").items.empty());
  const double pi = 3.14159265358979323846;
  const double dip = pi / 6.0;
  const double a = 9.81 * (std::sin(dip) - std::tan(pi / 9.0) * std::cos(dip));
  const double t = example.last("time");
  EXPECT_NEAR(t, 1.0, 1e-9);
  const double slid = example.monitor("wedge", "ux") * std::cos(dip) -
                      example.monitor("wedge", "uy") * std::sin(dip);
  const double speed = std::hypot(example.monitor("wedge", "vx"), example.monitor("wedge", "vy"));
  // The wedge is elastic and rides on contact springs; what it adds to the rigid block's
  // motion is its elastic vibration after the start: measured +0.018% on the distance,
  // +0.008% on the speed (+0.1% with E ten times smaller, so it is elastic). 0.1% is five
  // times the measured error and a ninth of what 0.1 degree less friction changes (0.9%).
  EXPECT_NEAR(slid, 0.5 * a * t * t, 1e-3 * 0.5 * a * t * t);
  EXPECT_NEAR(speed, a * t, 1e-3 * a * t);
  // The wedge: the triangle above the joint, from A = (5 / tan 60, 5) on the left face to
  // B on the right face and the apex (5, 5 tan 60).
  const double t60 = std::tan(pi / 3.0);
  const double ax = 5.0 / t60;
  const double bx = (10.0 * t60 - 5.0 - ax * std::tan(dip)) / (t60 - std::tan(dip));
  const double by = (10.0 - bx) * t60;
  const double area = 0.5 * std::abs((bx - ax) * (5.0 * t60 - 5.0) - (5.0 - ax) * (by - 5.0));
  const double energy = 0.5 * 2500.0 * area * (a * t) * (a * t);
  EXPECT_NEAR(example.last("kinetic_energy"), energy, 2e-3 * energy); // measured +0.02%
}

TEST_F(Example, SingleJointWedgeStandsWhenItsFrictionExceedsTheDip) {
  // examples/14_single_joint_in_triangle/case_stable.toml: the same wedge with a friction
  // angle of 32 degrees on the 30 degree joint stays put. Measured: it moves 3.8e-5 m in 1 s
  // (the joint's springs taking up its weight's slope component, then a creep of about
  // 1.4e-5 m/s: docs/formulation.md, "Anchors") and is at 1.3e-5 m/s at the end. With 29.9
  // degrees it would slide 9.9 mm in 1 s; 1e-4 m is a hundredth of that.
  const ExampleRun example = run_case(std::filesystem::path(NMM_EXAMPLES_DIR) /
                                          "14_single_joint_in_triangle" / "case_stable.toml",
                                      "14_stable");
  EXPECT_TRUE(example.summary.at("warnings").items.empty());
  EXPECT_NEAR(example.last("time"), 1.0, 1e-9);
  EXPECT_LT(std::hypot(example.monitor("wedge", "ux"), example.monitor("wedge", "uy")), 1e-4);
  EXPECT_LT(std::hypot(example.monitor("wedge", "vx"), example.monitor("wedge", "vy")), 1e-4);
  // Pairs along the joint at the limit of friction (the wedge's elastic shear is uneven
  // along it) chatter between lock and slide. In a dynamic step the chatter rule lets them
  // slide at their limit, so no lock is held beyond friction (before 2026-11-28, thirteenth
  // session: 478 of the 500 steps, up to 2.17 times the limit), and summary.json reports
  // what the held slides' friction did along motions that turned back: measured 4 steps,
  // 0.0104 J. The bound, 0.1 J, is 1.4% of the work of gravity on the wedge's 3.8e-5 m
  // (38,675 kg x 9.81 x sin 30 deg x 3.8e-5 m = 7.2 J).
  const auto& counters = example.summary.at("counters");
  EXPECT_EQ(counters.at("locks_beyond_friction").number, 0.0);
  EXPECT_EQ(example.summary.at("max_lock_excess").number, 0.0);
  EXPECT_LT(counters.at("slide_feed_work").number, 0.1);
}

TEST_F(Example, JointedDoubleCantileverLayersEachCarryHalfTheLoad) {
  // examples/16_jointed_double_cantilever: a cantilever 10 m long and 1 m deep split along its
  // axis by a frictionless joint into two layers h = 0.5 m deep, under q = 1 kN/m on the top,
  // plane stress, E = 1 GPa, nu = 0.25. The layers bend alike, each under q/2 (the joint
  // passes q/2 down): tip deflection (q/2) L^4 / (8 E h^3/12) = 0.06 m, four times the bonded
  // beam's bending, plus Timoshenko's shear deflection (q/2) L^2 / (2 kappa G h) = 1.5e-4 m
  // (kappa = 5/6); the layers slide on each other at the tip by h theta = h (q/2) L^3 /
  // (6 E h^3/12) = 4 mm (README).
  const ExampleRun example = run("16_jointed_double_cantilever");
  EXPECT_TRUE(example.summary.at("warnings").items.empty());
  const double q = 1.0e3;
  const double length = 10.0;
  const double h = 0.5;
  const double young = 1.0e9;
  const double shear_modulus = young / (2.0 * 1.25);
  const double inertia = h * h * h / 12.0;
  const double bending = 0.5 * q * std::pow(length, 4) / (8.0 * young * inertia);
  const double shear = 0.5 * q * length * length / (2.0 * 5.0 / 6.0 * shear_modulus * h);
  const double deflection = bending + shear;
  const double slip = h * 0.5 * q * std::pow(length, 3) / (6.0 * young * inertia);
  // Measured: -0.085% (upper layer), -0.055% (lower), slip -0.08%; no warning (the load is
  // ramped: in one step the contacts' linearised gaps make energy, a warning). The formula holds
  // the end section at its axis; holding the whole end (as here) stiffens it a little (-1% in
  // examples/01, whose length is 5 depths against the layers' 20), and the shear factor is
  // uncertain by 25% of 0.25% (Timoshenko-Goodier's 3/2 against 6/5): 0.3% covers both.
  for (const char* tip : {"upper_tip", "lower_tip"})
    EXPECT_NEAR(example.monitor(tip, "uy"), -deflection, 3e-3 * deflection) << tip;
  EXPECT_NEAR(example.monitor("lower_face", "ux") - example.monitor("upper_face", "ux"), slip,
              3e-3 * slip);
}

TEST_F(Example, JointedDoubleCantileverLoadedInOneStaticStepWarnsOfTheEnergyItsContactsMake) {
  // examples/16 with its load on at once instead of ramped over 8 steps: step 1 slides the
  // layers 4 mm on each other while their faces turn 0.008 rad, the contacts' linearised
  // gap misses 3e-5 m, and step 2 starts with springs holding 375 J no load has done: the
  // balance misses by 0.76 (measured), above energy_tolerance (0.05), and the static step
  // warns (the ramped case, above, closes to 1.5e-2 and does not). The result is still right
  // to 0.3%: step 2 pushes the faces out.
  std::string text = testing::example_variant("16_jointed_double_cantilever", "case.toml", "");
  const std::string ramp = "ramp = [0.0, 8.0]";
  const std::size_t at = text.find(ramp);
  ASSERT_NE(at, std::string::npos);
  text.erase(at, ramp.size());
  const std::filesystem::path at_once = dir() / "at_once.toml";
  testing::write_text(at_once, text);
  const ExampleRun run = run_case(at_once, "at_once", {"--steps", "3"});
  const std::vector<double>& error = run.history.at("energy_error");
  ASSERT_EQ(error.size(), 3U);
  EXPECT_LT(error[0], 1e-6);
  EXPECT_GT(error[1], 0.5);
  const std::vector<testing::Json>& warnings = run.summary.at("warnings").items;
  ASSERT_EQ(warnings.size(), 1U);
  EXPECT_NE(warnings[0].string.find("step 2: the energy balance misses by"), std::string::npos)
      << warnings[0].string;
  EXPECT_NE(warnings[0].string.find("ramp"), std::string::npos) << warnings[0].string;
  EXPECT_NEAR(run.monitor("upper_tip", "uy"), -0.06015, 3e-3 * 0.06015);
}

/// blocks.csv of a run: per block id, the (x, y) at step 0 and the (ux, uy) at the last step.
struct Vector {
  double x = 0.0;
  double y = 0.0;
  [[nodiscard]] double dot(const Vector& v) const { return x * v.x + y * v.y; }
};

struct BlockMotion {
  std::map<int, Vector> start;
  std::map<int, Vector> moved;
};

BlockMotion read_block_motion(const std::filesystem::path& file) {
  std::istringstream in(testing::read_text(file));
  std::string line;
  std::getline(in, line); // step,time,block,material,x,y,ux,uy,...
  BlockMotion motion;
  long last = -1;
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::istringstream row(line);
    for (std::string cell; std::getline(row, cell, ',');)
      cells.push_back(cell);
    const long step = std::stol(cells[0]);
    const int block = std::stoi(cells[2]);
    if (step == 0)
      motion.start[block] = {std::stod(cells[4]), std::stod(cells[5])};
    if (step > last) {
      last = step;
      motion.moved.clear();
    }
    motion.moved[block] = {std::stod(cells[6]), std::stod(cells[7])};
  }
  return motion;
}

TEST_F(Example, RoadCutJointSetsSlideTheDaylightingWedgeAtTheCoulombRate) {
  // examples/18_road_cut_joint_sets: two generated joint sets cut a road cut into DDA blocks.
  // Limit equilibrium (README): the blocks above the lowest daylighting joint of the first
  // set (through (25.5, 9) at -35 degrees) and left of the toe (x < 26) rest on 35 degree
  // joints free behind, so at phi = 25 they slide with a = g (sin 35 - tan 25 cos 35) =
  // 1.8796 m/s^2, 37.59 mm in 0.2 s, and every other block is held; at phi = 40 none moves.
  const ExampleRun example = run("18_road_cut_joint_sets");
  // The one warning: the joint set's note of the joints it dropped (README).
  ASSERT_EQ(example.summary.at("warnings").items.size(), 1U);
  EXPECT_NE(example.summary.at("warnings").items[0].string.find("[[joint_set]]"),
            std::string::npos);
  const double pi = 3.14159265358979323846;
  const double dip = 35.0 * pi / 180.0;
  const double t = example.last("time");
  const double slide =
      0.5 * 9.81 * (std::sin(dip) - std::tan(25.0 * pi / 180.0) * std::cos(dip)) * t * t;
  const Vector along{std::cos(dip), -std::sin(dip)};
  const Vector normal{std::sin(dip), std::cos(dip)};
  const BlockMotion motion = read_block_motion(dir() / "18_road_cut_joint_sets" / "blocks.csv");
  std::vector<int> wedge;
  for (const auto& [block, centroid] : motion.start)
    if (Vector{centroid.x - 25.5, centroid.y - 9.0}.dot(normal) > 0.0 && centroid.x < 26.0)
      wedge.push_back(block);
  std::vector<int> moved;
  for (const Json& item : example.summary.at("moved_blocks").items)
    moved.push_back(static_cast<int>(item.at("block").number));
  EXPECT_EQ(moved, wedge);
  for (const int block : wedge) {
    const Vector u = motion.moved.at(block);
    // The blocks of the wedge push and part as they go (README): measured -7.5% (the top
    // block) to +13.9% (a 0.02 m^2 block at the face), the wedge's area-weighted mean +0.4%.
    // 20% tells sliding from standing (0 mm), not one degree of friction (9% on a); the rate
    // itself is held to 0.5% on single wedges by JointSetCase (verification).
    EXPECT_NEAR(u.dot(along), slide, 0.2 * slide) << block;
    EXPECT_LT(std::abs(u.dot(normal)), 0.01 * slide) << block; // along the joint
  }
  const ExampleRun stands = run_case(std::filesystem::path(NMM_EXAMPLES_DIR) /
                                         "18_road_cut_joint_sets" / "case_phi40.toml",
                                     "18_phi40");
  EXPECT_TRUE(stands.summary.at("moved_blocks").items.empty());
  // Only the springs settling: measured 0.22 mm at most; 1 mm is 3% of the slide at 25.
  for (const auto& [block, u] : read_block_motion(dir() / "18_phi40" / "blocks.csv").moved)
    EXPECT_LT(std::hypot(u.x, u.y), 1e-3) << block;
}

TEST_F(Example, BoltedTunnelSettlesItsCrownAsKirschsHoleOverTheExcavationsSteps) {
  // examples/19_bolted_tunnel_stages: a 6 m tunnel 115 m deep in blocky rock (133 DDA blocks
  // of two generated joint sets), the in-situ stress held in stage 1, the tunnel excavated
  // over the 20 steps of stage 2 with five grouted bolts, 40 steps to settle. Kirsch's hole
  // in the elastic continuum (README): the crown moves 1.40 mm down. Measured: 1.271 mm
  // bolted, 1.282 mm unbolted (-9%, -8%: DDA blocks strain uniformly); 15% holds that and
  // tells a jack (the contacts' forces taken off at once, or a spring of a corner deep
  // behind a face, pushed the crown 1.6 to 6 mm up) or a lost release from it.
  const ExampleRun bolted = run("19_bolted_tunnel_stages");
  const ExampleRun unbolted = run_case(std::filesystem::path(NMM_EXAMPLES_DIR) /
                                           "19_bolted_tunnel_stages" / "case_unbolted.toml",
                                       "19_unbolted");
  const double sv = 2650.0 * 9.81 * 115.0;
  const double p = 0.75 * sv; // (sv + sh) / 2, k0 = 0.5
  const double s = 0.25 * sv; // (sv - sh) / 2
  const double shear_modulus = 1.0e10 / 2.5;
  const double crown = 3.0 / (2.0 * shear_modulus) * (p + (3.0 - 4.0 * 0.25) * s); // theta = 90
  for (const ExampleRun* run : {&bolted, &unbolted}) {
    const std::vector<double>& uy = run->history.at("crown.uy");
    ASSERT_EQ(uy.size(), 65U);
    // Stage 1 holds the in-situ stress: 4e-6 m measured, 0.3% of the excavation's.
    EXPECT_LT(std::abs(uy[4]), 0.01 * crown);
    // Released over 20 steps, the first moves the crown by about 1/20 of it (2% measured).
    EXPECT_LT(std::abs(uy[5]), 0.1 * crown);
    EXPECT_LT(uy.back(), 0.0);
    EXPECT_NEAR(-uy.back(), crown, 0.15 * crown);
    EXPECT_LT(run->last("energy_error"), 0.05);
    // The joint set's note and the chatter rule's locks (README); no energy, penetration or
    // cut-step warning.
    for (const Json& warning : run->summary.at("warnings").items) {
      const std::string& text = warning.string;
      EXPECT_TRUE(text.find("[[joint_set]]") != std::string::npos ||
                  text.find("held locked beyond") != std::string::npos)
          << text;
    }
  }
  // The bolts hold the crown a little (0.9% measured), all elastic and pulled.
  EXPECT_LT(-bolted.last("crown.uy"), -unbolted.last("crown.uy"));
  const auto& bolts = bolted.summary.at("bolts").items;
  ASSERT_EQ(bolts.size(), 5U);
  for (const Json& bolt : bolts) {
    EXPECT_EQ(bolt.at("state").string, "elastic") << bolt.at("name").string;
    EXPECT_GT(bolt.at("force").number, 0.0) << bolt.at("name").string;
    EXPECT_LT(bolt.at("force").number, 1.33e5) << bolt.at("name").string;
  }
}

} // namespace
} // namespace nmm
