// SPDX-License-Identifier: MIT
// reduced_strength() (contact/joint_law.hpp): the strength reduction of `nmm fos` divides the
// friction coefficient, the cohesion and the tensile strength by F and keeps the stiffnesses;
// F = 1 keeps every bit.
#include "contact/joint_law.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace nmm {
namespace {

const JointStrength joint{0.6, 2.0e4, 5.0e3, 1.0e10, 2.0e9};

TEST(ReducedStrength, DividesTanPhiCohesionAndTensileStrengthByTheFactor) {
  for (const double factor : {0.5, 1.3, 2.0, 10.0}) {
    const JointStrength reduced = reduced_strength(joint, factor);
    // Rounding of tan, a division and atan: a few ulp.
    EXPECT_NEAR(std::tan(reduced.friction_angle), std::tan(joint.friction_angle) / factor, 1e-15);
    EXPECT_DOUBLE_EQ(reduced.cohesion, joint.cohesion / factor);
    EXPECT_DOUBLE_EQ(reduced.tensile_strength, joint.tensile_strength / factor);
    EXPECT_EQ(reduced.normal_stiffness, joint.normal_stiffness);
    EXPECT_EQ(reduced.shear_stiffness, joint.shear_stiffness);
    // Below pi/2 however much it is raised (F < 1).
    EXPECT_LT(reduced.friction_angle, std::acos(-1.0) / 2.0);
  }
}

TEST(ReducedStrength, FactorOneKeepsEveryBit) {
  const JointStrength same = reduced_strength(joint, 1.0);
  EXPECT_EQ(same.friction_angle, joint.friction_angle);
  EXPECT_EQ(same.cohesion, joint.cohesion);
  EXPECT_EQ(same.tensile_strength, joint.tensile_strength);
}

} // namespace
} // namespace nmm
