// SPDX-License-Identifier: MIT
// The block results of blocks.csv: a block's centroid, displacement, rotation, velocity and
// angular velocity as a rigid fit of its material (exact for a rigid motion, DDA and NMM
// blocks), its state by the documented rules, and the file's rows.
#include "io/block_results.hpp"
#include "io/case_runner.hpp"
#include "io/step_output.hpp"

#include "../../support/case_fixtures.hpp"
#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

namespace nmm {
namespace {

using testing::plate_case;
using testing::read_text;
using testing::replaced;
using testing::TempDir;
using testing::write_case;

/// The plate of plate_case (2 m x 1 m, one block) as an NMM body or as one DDA block.
std::string plate_of(bool dda) {
  return dda ? replaced(plate_case, "[materials.rock]\n", "[materials.rock]\nmodel = \"dda\"\n")
             : std::string(plate_case);
}

/// @p model with every polygon vertex and cover position moved by the rigid motion
/// x -> centre + R(theta) (x - centre) + shift.
Model moved_rigidly(Model model, const Point2& centre, double theta, const Point2& shift) {
  const Eigen::Rotation2Dd turn(theta);
  const auto map = [&](Point2& x) { x = centre + turn * (x - centre) + shift; };
  for (ModelElement& element : model.elements) {
    for (Polygon& polygon : element.polygons) {
      for (Point2& x : polygon.outer)
        map(x);
      for (Loop& hole : polygon.holes)
        for (Point2& x : hole)
          map(x);
    }
  }
  for (ModelCover& cover : model.covers)
    map(cover.position);
  return model;
}

class BlockResults : public ::testing::TestWithParam<bool> {
protected:
  BlockResults() : dir_("nmm_block_results") {}
  [[nodiscard]] const std::filesystem::path& dir() const { return dir_.path(); }

private:
  TempDir dir_;
};

TEST_P(BlockResults, RigidMotionGivesTheExactDisplacementRotationAndVelocities) {
  const CaseAnalysis analysis(read_case_file(write_case(dir(), plate_of(GetParam()))));
  const Model& model = analysis.model();
  ASSERT_EQ(model.blocks.size(), 1u);
  BlockTracker tracker(model, step_points(model));
  const Point2 centroid(1.0, 0.5);
  const Eigen::VectorXd still = Eigen::VectorXd::Zero(model.n_dofs());
  const BlockMotion start = tracker.motions(model, still, true)[0];
  EXPECT_NEAR((start.centroid - centroid).norm(), 0.0, 1e-14);
  EXPECT_EQ(start.rotation, 0.0);
  EXPECT_NEAR(start.radius, std::sqrt(1.25), 1e-14);

  // Turned by 0.7 rad about a point off the block and shifted: the centroid moves by the
  // image of the centroid, the rotation is the angle, in a step of 0.1 s.
  const Point2 pivot(-0.4, 2.0);
  const Point2 shift(0.3, -0.2);
  const double theta = 0.7;
  const Model turned = moved_rigidly(model, pivot, theta, shift);
  tracker.update(turned, 0.1);
  const Point2 image = pivot + Eigen::Rotation2Dd(theta) * (centroid - pivot) + shift;
  const BlockMotion step = tracker.motions(turned, still, true)[0];
  EXPECT_NEAR((step.centroid - image).norm(), 0.0, 1e-13);
  EXPECT_NEAR((step.displacement - (image - centroid)).norm(), 0.0, 1e-13);
  EXPECT_NEAR(step.rotation, theta, 1e-13);
  EXPECT_NEAR((step.velocity - (image - centroid) / 0.1).norm(), 0.0, 1e-12);
  EXPECT_NEAR(step.angular_velocity, theta / 0.1, 1e-12);

  // The velocity field of a rigid motion v = v0 + omega J (x - pivot), fitted.
  Eigen::VectorXd velocity = Eigen::VectorXd::Zero(turned.n_dofs());
  const Point2 v0(0.5, -1.5);
  const double omega = -2.0;
  for (int cover = 0; cover < turned.n_covers(); ++cover)
    turned.set_rigid_motion(cover, v0, omega, pivot, velocity);
  const BlockMotion field = tracker.motions(turned, velocity, false)[0];
  const Point2 arm = image - pivot;
  EXPECT_NEAR((field.velocity - (v0 + omega * Point2(-arm.y(), arm.x()))).norm(), 0.0, 1e-12);
  EXPECT_NEAR(field.angular_velocity, omega, 1e-12);

  // Past half a turn and on past a whole one, the rotation stays continuous (no wrap).
  double angle = theta;
  for (const double next : {2.5, 4.0, 5.5, 7.0}) {
    tracker.update(moved_rigidly(model, pivot, next, shift), 0.1);
    angle = tracker.motions(model, still, true)[0].rotation;
    EXPECT_NEAR(angle, next, 1e-12);
  }
  EXPECT_NEAR(tracker.displacements()[0].norm(),
              (pivot + Eigen::Rotation2Dd(7.0) * (centroid - pivot) + shift - centroid).norm(),
              1e-12);

  // The state round-trips.
  BlockTracker restored(model, step_points(model));
  restored.restore(tracker.state());
  EXPECT_EQ(restored.state(), tracker.state());
  EXPECT_THROW(restored.restore(Eigen::VectorXd::Zero(5)), InputError);
}

INSTANTIATE_TEST_SUITE_P(NmmAndDda,
                         BlockResults,
                         ::testing::Values(false, true),
                         [](const ::testing::TestParamInfo<bool>& param) {
                           return param.param ? std::string("Dda") : std::string("Nmm");
                         });

TEST(BlockStates, FollowTheDocumentedRules) {
  const TempDir dir("nmm_block_states");
  // The plate of plate_case, dynamic, unheld: nothing but its motion decides.
  const std::string free_plate =
      replaced(replaced(plate_case, "[[boundary]]\ncurve = \"base\"\nfix = \"xy\"\n", ""),
               "kind = \"static\"", "kind = \"dynamic\"\ntime_step = 1.0e-3");
  const CaseAnalysis unheld(read_case_file(write_case(dir.path(), free_plate)));
  std::vector<BlockMotion> motions(1);
  motions[0].radius = 1.0;
  const auto state = [&](const CaseAnalysis& analysis) {
    return block_states(analysis.model(), analysis.stepper().contact(), analysis.stepper().scene(),
                        motions, 1e-3)[0];
  };
  EXPECT_EQ(state(unheld), BlockState::resting); // not moving
  motions[0].velocity = Point2(0.0, -0.1);
  EXPECT_EQ(state(unheld), BlockState::free);
  motions[0].velocity = Point2::Zero();
  motions[0].angular_velocity = 0.01;
  EXPECT_EQ(state(unheld), BlockState::free); // spinning, touching nothing

  // Held by its base: a motion about a centre inside the block is rotating, a motion whose
  // centre of rotation lies outside it is resting (no contact slides).
  const CaseAnalysis held(read_case_file(write_case(dir.path(), plate_case)));
  EXPECT_EQ(state(held), BlockState::rotating);
  motions[0].velocity = Point2(0.02, 0.0);
  EXPECT_EQ(state(held), BlockState::resting);
  motions[0].angular_velocity = 0.0;
  motions[0].velocity = Point2(0.0, 5e-4);
  EXPECT_EQ(state(held), BlockState::resting); // below the tolerance

  for (const BlockState s : {BlockState::resting, BlockState::sliding, BlockState::rotating,
                             BlockState::free, BlockState::excavated})
    EXPECT_FALSE(std::string(block_state_name(s)).empty());
  EXPECT_STREQ(block_state_name(BlockState::excavated), "excavated");
}

TEST(BlocksCsv, HeaderIsTheContractAndEveryBlockHasARowPerOutputStep) {
  const TempDir dir("nmm_blocks_csv");
  const auto file = dir.path() / "blocks.csv";
  std::uintmax_t after_first = 0;
  {
    BlocksWriter writer(file, {"rock", "odd,name"});
    std::vector<BlockMotion> motions(2);
    motions[1].centroid = Point2(0.1 + 0.2, -2.0);
    motions[1].rotation = 1.0 / 3.0;
    const std::vector<BlockState> states{BlockState::resting, BlockState::sliding};
    writer.write_step(0, 0.0, motions, states);
    after_first = writer.bytes();
    writer.write_step(10, 0.5, motions, states);
  }
  const std::string text = read_text(file);
  std::istringstream in(text);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "step,time,block,material,x,y,ux,uy,rotation,vx,vy,omega,state");
  std::getline(in, line);
  EXPECT_EQ(line, "0,0,0,rock,0,0,0,0,0,0,0,0,resting");
  std::getline(in, line);
  EXPECT_EQ(line, "0,0,1,\"odd,name\",0.30000000000000004,-2,0,0,0.33333333333333331,0,0,0,"
                  "sliding");
  int rows = 2;
  while (std::getline(in, line))
    ++rows;
  EXPECT_EQ(rows, 4);
  // A restart continues after the first step's rows, dropping the rest.
  {
    BlocksWriter again(file, {"rock", "odd,name"}, after_first);
    EXPECT_EQ(again.bytes(), after_first);
  }
  EXPECT_EQ(read_text(file), text.substr(0, after_first));
}

} // namespace
} // namespace nmm
