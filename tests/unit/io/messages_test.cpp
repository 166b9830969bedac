// SPDX-License-Identifier: MIT
// Messages a user can act on: the warning of a block too small for the cover mesh says where
// it is, what cuts it and a fix within max_triangles; a VTK write that fails is reported by
// nmm with the file and the reason, never in VTK's own words on stderr.
#include "io/atomic_file.hpp"
#include "io/case_runner.hpp"
#include "io/cover_warnings.hpp"
#include "io/vtk_writer.hpp"

#include "../../support/case_fixtures.hpp"
#include <gtest/gtest.h>
#include <sys/resource.h>

#include <cmath>
#include <csignal>
#include <filesystem>
#include <string>
#include <vector>

namespace nmm {
namespace {

namespace fs = std::filesystem;
using testing::plate_case;
using testing::replaced;
using testing::TempDir;

void expect_all(const std::string& text, const std::vector<std::string>& parts) {
  for (const std::string& part : parts)
    EXPECT_NE(text.find(part), std::string::npos) << "\"" << part << "\" not in:\n" << text;
}

// ---------------------------------------------------------------------------------------
// A block too small for the cover mesh

/// The warnings of the plate with its corner cut off, with @p cover_mesh_lines added to
/// [cover_mesh].
std::vector<std::string> corner_warnings(const fs::path& dir, const std::string& cover_mesh_lines) {
  testing::write_text(dir / "corner.geo", testing::corner_geo());
  std::string text = replaced(plate_case, "plate.geo", "corner.geo");
  text = replaced(text, "order = 0\n", "order = 0\n" + cover_mesh_lines);
  testing::write_text(dir / "case.toml", text + "[joints.cut]\nfriction_angle = 30.0\n");
  const CaseAnalysis analysis(read_case_file(dir / "case.toml"));
  return analysis.warnings();
}

/// The one warning of @p warnings about a tiny block ("" and a failure if not one).
std::string tiny_block_warning_of(const std::vector<std::string>& warnings) {
  std::vector<std::string> found;
  for (const std::string& w : warnings) {
    if (w.find("is too small for the cover mesh") != std::string::npos)
      found.push_back(w);
  }
  EXPECT_EQ(found.size(), 1u);
  return found.empty() ? std::string() : found.front();
}

TEST(TinyBlockWarning, SaysWhereTheBlockIsWhatCutsItAndACoverSizeWithinMaxTriangles) {
  const TempDir dir("nmm_messages");
  const std::string warning = tiny_block_warning_of(corner_warnings(dir.path(), ""));
  // Its place: the bounding box of the corner piece, and the groups along it.
  expect_all(warning, {"corner.geo: block ",
                       " of \"rock\" (5e-05 m² around (1.995, 0.005): x 1.99 "
                       "to 2 m, y 0 to 0.01 m; along ",
                       "curve \"base\"", "curve \"right\"", "joint \"cut\"",
                       "is too small for the cover mesh of size 0.3 m"});
  // The fixes that fit: trim the joint; a cover size that resolves the piece (half of
  // sqrt(5e-5 / (1e-3 6 sqrt(3)/4)) = 0.139 m, rounded down), whose 2 m² of triangles of
  // 0.06 m are 1283, well within max_triangles.
  expect_all(warning, {"trim joint \"cut\" near (1.995, 0.005)",
                       "[cover_mesh] size = 0.06 (about 1283 triangles; max_triangles = 5000000)"});
}

TEST(TinyBlockWarning, NeverSuggestsAGlobalSizeThatMaxTrianglesForbids) {
  const TempDir dir("nmm_messages");
  const std::vector<std::string> warnings = corner_warnings(dir.path(), "max_triangles = 1000\n");
  const std::string warning = tiny_block_warning_of(warnings);
  EXPECT_EQ(warning.find("[cover_mesh] size ="), std::string::npos) << warning;
  // Nor the warning of blocks much smaller than the triangles (coarse stress): a size below
  // sqrt(5e-5) m = 0.00707 m needs 92,000 triangles.
  bool small_block_warned = false;
  for (const std::string& w : warnings) {
    if (w.find("much smaller than the math triangles") == std::string::npos)
      continue;
    small_block_warned = true;
    EXPECT_EQ(w.find("use a size below"), std::string::npos) << w;
    expect_all(w, {"make the cover mesh finer around it only",
                   "a size below 0.007071 m "
                   "everywhere would need about 92376 triangles, more than max_triangles = 1000"});
  }
  EXPECT_TRUE(small_block_warned);
  expect_all(warning,
             {"trim joint \"cut\"",
              "a cover mesh finer around the block only: [cover_mesh] kind = \"gmsh\" on a .msh "
              "geometry with triangles of about 0.06 m around (1.995, 0.005)",
              "would need about 1283 triangles, more than max_triangles = 1000"});
}

TEST(TinyBlockWarning, ResolvingSizeKeepsTheCoversOfThePieceAboveTheRatioOfTheirStar) {
  const double star = 6.0 * std::sqrt(3.0) / 4.0;
  // A compact piece inside one star: its area is the ratio of the star at that size.
  const double compact = resolving_cover_size(5e-5, 0.014, 1e-3);
  EXPECT_NEAR(5e-5, 1e-3 * star * compact * compact, 1e-15);
  // A strip 0.1 mm wide and 2 m long: a cover holds 2 h of it.
  const double strip = resolving_cover_size(2e-4, 2.0, 1e-3);
  EXPECT_NEAR(1e-4 * 2.0 * strip, 1e-3 * star * strip * strip, 1e-12);
  EXPECT_LT(strip, std::sqrt(2e-4 / (1e-3 * star))) << "finer than the whole-piece estimate";
  EXPECT_TRUE(std::isinf(resolving_cover_size(5e-5, 0.014, 0.0)));
}

// ---------------------------------------------------------------------------------------
// VTK's messages

TEST(VtkMessages, AFailedWriteNamesTheFileAndTheReasonAndVtkPrintsNothing) {
  const TempDir dir("nmm_messages");
  // 20,000 triangles with varied values: far more than the 4 KiB the limit lets through.
  PolygonMeshData data;
  std::vector<double> values;
  for (int k = 0; k < 20000; ++k) {
    const double x = k;
    data.points.insert(data.points.end(), {Point2(x, 0.0), Point2(x + 1.0, 0.0), Point2(x, 1.0)});
    data.cells.push_back(PolygonCell{{3 * k, 3 * k + 1, 3 * k + 2}, {}});
    values.push_back(std::sin(0.37 * x) * 1e5);
  }
  data.cell_data.add("value", values);
  const fs::path file = dir.path() / "step_000000.vtu";
  struct rlimit saved {};
  ASSERT_EQ(::getrlimit(RLIMIT_FSIZE, &saved), 0);
  const auto old_handler = std::signal(SIGXFSZ, SIG_IGN); // as nmm does (io/cli.cpp)
  struct rlimit limit = saved;
  limit.rlim_cur = 4096;
  ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &limit), 0);
  std::string message;
  ::testing::internal::CaptureStderr();
  try {
    write_vtu(file, data);
  } catch (const OutputWriteError& error) {
    message = error.what();
  }
  const std::string printed = ::testing::internal::GetCapturedStderr();
  ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &saved), 0);
  std::signal(SIGXFSZ, old_handler);
  expect_all(message, {"file too large: cannot write '" + file.string() + "' (File too large)",
                       "file-size limit of 4096 bytes", "ulimit -f"});
  EXPECT_EQ(printed, "") << "VTK's own text reached stderr";
  EXPECT_FALSE(fs::exists(file));
}

} // namespace
} // namespace nmm
