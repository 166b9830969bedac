// SPDX-License-Identifier: MIT
// examples/17_hertz_contact (issue 8): Hertz's line contact, a cylinder pressed on a block,
// by the `nmm` program as a user runs it; the contact pressure read back from the contact
// points' `pressure` and `length` (docs/output.md) with VTK's reader.
#include "../support/vtk_readers.hpp"
#include "example_run.hpp"
#include <gtest/gtest.h>
#include <vtkDataArray.h>
#include <vtkPointData.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

namespace nmm {
namespace {

using testing::Example;
using testing::ExampleRun;

/// The closed form of the example's case (README): plane strain, frictionless.
struct Hertz {
  double radius = 1.0;     ///< m
  double load = 2.0e7;     ///< N/m on the whole cylinder: 1e7 Pa on its radius, twice
  double modulus = 0.0;    ///< E* = 1 / ((1 - nu1^2) / E1 + (1 - nu2^2) / E2)
  double half_width = 0.0; ///< a = sqrt(4 P R / (pi E*))
  double peak = 0.0;       ///< p0 = sqrt(P E* / (pi R))
  Hertz() {
    modulus = 1.0 / ((1.0 - 0.3 * 0.3) / 210.0e9 + (1.0 - 0.33 * 0.33) / 70.0e9);
    half_width = std::sqrt(4.0 * load * radius / (std::numbers::pi * modulus));
    peak = std::sqrt(load * modulus / (std::numbers::pi * radius));
  }
};

/// What the last contacts_NNNNNN.vtp of a run says.
struct Contact {
  double peak = 0.0;       ///< largest `pressure`, Pa
  double force = 0.0;      ///< sum of `pressure` x `length`: the springs' force, N/m
  double half_width = 0.0; ///< largest x of a closed point, m
};

Contact read_contact(const testing::fs::path& file) {
  const auto points = testing::read_vtp(file);
  vtkDataArray* pressure = points->GetPointData()->GetArray("pressure");
  vtkDataArray* length = points->GetPointData()->GetArray("length");
  vtkDataArray* state = points->GetPointData()->GetArray("state");
  Contact contact;
  EXPECT_TRUE(pressure != nullptr && length != nullptr && state != nullptr) << file;
  if (pressure == nullptr || length == nullptr || state == nullptr)
    return contact;
  for (vtkIdType i = 0; i < points->GetNumberOfPoints(); ++i) {
    if (state->GetTuple1(i) == 0.0)
      continue;
    contact.peak = std::max(contact.peak, pressure->GetTuple1(i));
    contact.force += pressure->GetTuple1(i) * length->GetTuple1(i);
    contact.half_width = std::max(contact.half_width, points->GetPoint(i)[0]);
  }
  return contact;
}

class HertzExample : public Example {
protected:
  /// Runs the example with `[analysis] penalty` set to @p penalty (x E).
  Contact run_with_penalty(double penalty) {
    const testing::fs::path example = testing::fs::path(NMM_EXAMPLES_DIR) / "17_hertz_contact";
    const std::string name = "penalty_" + std::to_string(static_cast<int>(penalty));
    const testing::fs::path folder = dir() / (name + "_case");
    testing::fs::create_directories(folder);
    testing::fs::copy_file(example / "hertz.geo", folder / "hertz.geo");
    std::string text = testing::read_text(example / "case.toml");
    const std::string key = "\npenalty = ";
    const std::size_t at = text.find(key);
    EXPECT_NE(at, std::string::npos) << "case.toml has no penalty line";
    if (at == std::string::npos)
      return {};
    const std::size_t end = text.find_first_of(" \n#", at + key.size());
    text.replace(at + key.size(), end - at - key.size(), std::to_string(penalty));
    testing::write_text(folder / "case.toml", text);
    const ExampleRun run = run_case(folder / "case.toml", name);
    EXPECT_TRUE(run.summary.at("warnings").items.empty());
    EXPECT_EQ(run.last("step_cuts"), 0.0);
    return read_contact(dir() / name / "contacts_000001.vtp");
  }
};

TEST_F(HertzExample, PeakPressureWithinOnePercentOfHertzWhateverThePenalty) {
  // A quarter of a steel cylinder (R = 1 m, E = 210 GPa, nu = 0.3) pressed by P = 2e7 N/m on
  // half of an aluminium block (E = 70 GPa, nu = 0.33), rollers on the symmetry line, one
  // static step, order-1 covers, the boundary spaced a / 20 in the contact zone: Hertz's
  // a = 20.845 mm, p0 = 610.81 MPa (README).
  const Hertz hertz;
  const Contact soft = run_with_penalty(100.0);
  const Contact stiff = run_with_penalty(1000.0);
  for (const Contact& contact : {soft, stiff}) {
    // Measured: -0.31% at 100 E, -0.03% at 1000 E; the goal of issue 8 is 1% (the VEM dam
    // paper: 1.7% with VEM, 3.6% with FEM). At n = 5, 10, 40, 80: -0.84/-0.09%,
    // -0.40/+0.13%, -0.26/-0.10%, -0.25/-0.18%, tending to -0.25% (Shi's linearised gap
    // carries the master's stretch: docs/formulation.md, "Known limitations"); so 1% holds
    // from n = 5 on, with room for the 0.3% the penalty moves it.
    EXPECT_NEAR(contact.peak, hertz.peak, 0.01 * hertz.peak);
    // Statics: the springs carry the load on the quarter cylinder, P / 2, to rounding.
    EXPECT_NEAR(contact.force, 0.5 * hertz.load, 1e-9 * hertz.load);
    // The pressed parts end where the gap profile crosses zero, within a boundary spacing
    // h = a / 20 of Hertz's a (measured +0.002% at 100 E, -0.54% at 1000 E).
    EXPECT_NEAR(contact.half_width, hertz.half_width, hertz.half_width / 20.0);
  }
  // The springs' compliance: their stiffness per length is the penalty times E over the mean
  // math edge (0.025 m here, 24 times the spacing in the contact zone), so at 100 E they let
  // the faces sink into each other by 0.74 um, at 1000 E by 0.08 um. Measured change of the
  // peak from 100 E to 1000 E: 0.28% (n = 10: 0.53%, n = 40: 0.16%, halving with each
  // refinement); the goal of issue 8 is < 0.5%.
  EXPECT_LT(std::abs(stiff.peak / soft.peak - 1.0), 0.005);
}

} // namespace
} // namespace nmm
