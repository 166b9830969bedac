// SPDX-License-Identifier: MIT
// Curves resolved as the cover mesh resolves them: the automatic sampling follows the cover
// size, curves coarser than the cover mesh are warned about, curve_tolerance is refused for
// a .msh, and a .geo's own mesh sizes grade a gmsh cover mesh on request.
#include "io/case_file.hpp"
#include "io/case_runner.hpp"
#include "io/gmsh_reader.hpp"
#include "mesh/error.hpp"
#include "mesh/geometry.hpp"

#include "../../support/json_reader.hpp"
#include "../../support/process.hpp"
#include "../../support/temp_dir.hpp"
#include <gmsh.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <string>
#include <vector>

namespace nmm {
namespace {

namespace fs = std::filesystem;
using testing::TempDir;

fs::path data(const std::string& name) { return fs::path(NMM_TEST_DATA_DIR) / name; }

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

/// The case of tests/data/tunnel.geo (or a .msh of it) at cover size 0.5 m: one dynamic step.
std::string tunnel_case(const std::string& geometry, const std::string& cover_mesh_keys = "") {
  return "geometry = \"" + geometry + "\"\n[cover_mesh]\nsize = 0.5\n" + cover_mesh_keys +
         "[materials.rock]\ndensity = 2600.0\nyoung = 1.0e9\npoisson = 0.25\n"
         "[[boundary]]\ncurve = \"base\"\nfix = \"xy\"\n[analysis]\nsteps = 1\n";
}

/// tunnel.geo meshed by gmsh with @p size_max (0: gmsh's defaults, no sizes at all) into
/// @p directory as @p name.
fs::path tunnel_msh(const fs::path& directory, const std::string& name, double size_max) {
  const fs::path msh = directory / name;
  const GmshSession session;
  gmsh::open(data("tunnel.geo").string());
  if (size_max > 0.0)
    gmsh::option::setNumber("Mesh.MeshSizeMax", size_max);
  gmsh::model::mesh::generate(2);
  gmsh::write(msh.string());
  return msh;
}

/// Largest distance between the circle of radius @p r about @p centre and the chords of
/// @p loop (vertices on it), and the longest chord.
std::pair<double, double> chord_deviation(const Loop& loop, const Point2& centre, double r) {
  double deviation = 0.0;
  double longest = 0.0;
  for (std::size_t i = 0; i < loop.size(); ++i) {
    const Point2& a = loop[i];
    const Point2& b = loop[(i + 1) % loop.size()];
    EXPECT_NEAR((a - centre).norm(), r, 1e-9);
    const double half = 0.5 * (b - a).norm();
    deviation = std::max(deviation, r - std::sqrt(r * r - half * half));
    longest = std::max(longest, 2.0 * half);
  }
  return {deviation, longest};
}

TEST(CurvesAndCoverMesh, SixMetreTunnelAtCoverSizeHalfAMetreIsA64GonWithin5mm) {
  // Before the cover size counted, the tolerance was 1e-3 of the diagonal (22.6 mm): a
  // 32-gon, 14 mm off the circle, chords of 0.59 m across triangles of 0.5 m (in examples/02,
  // 89 m across, a 16-gon of 1.17 m chords).
  const TempDir directory("nmm_curve_resolution");
  testing::write_text(directory.path() / "case.toml", tunnel_case(data("tunnel.geo").string()));
  const CaseGeometry geometry = build_case_geometry(read_case_file(directory.path() / "case.toml"));
  const Loop& tunnel = geometry.physical.regions.at(0).polygons.at(0).holes.at(0);
  const auto [deviation, longest] = chord_deviation(tunnel, {8.0, 8.0}, 3.0);
  // 1e-2 of the cover size: 5 mm. Quarter arcs halved until within it: 16 chords each.
  EXPECT_EQ(tunnel.size(), 64U);
  EXPECT_LE(deviation, 0.005);
  EXPECT_NEAR(deviation, 3.0 * (1.0 - std::cos(std::numbers::pi / 64.0)), 1e-12); // 3.6 mm
  EXPECT_LE(longest, 0.5);
  EXPECT_TRUE(geometry.physical.warnings.empty()) << geometry.physical.warnings.front();
}

TEST(CurvesAndCoverMesh, LongCurvesAreSampledNoCoarserThanTheCoverSize) {
  // A circle of radius 100 m sampled to 1e-2 of a 2 m cover size (2 cm) would have chords of
  // 4 m; the chords are bounded by the cover size instead. An explicit tolerance is only a
  // deviation: 0.1 m gives chords of 4.9 m, 31 mm off the circle, coarser than the covers.
  const TempDir directory("nmm_curve_resolution");
  const fs::path geo = directory.path() / "big_hole.geo";
  testing::write_text(geo, "SetFactory(\"OpenCASCADE\");\nRectangle(1) = {-200, -200, 0, 400, "
                           "400};\nDisk(2) = {0, 0, 0, 100};\nBooleanDifference(3) = "
                           "{Surface{1}; Delete;}{Surface{2}; Delete;};\nPhysical "
                           "Surface(\"rock\") = {3};\n");
  const auto hole = [](const PhysicalMesh& physical) {
    return chord_deviation(physical.regions.at(0).polygons.at(0).holes.at(0), {0, 0}, 100.0);
  };
  GeometryReadOptions options;
  options.cover_size = 2.0;
  const PhysicalMesh automatic = read_physical_mesh(geo, options);
  const auto [deviation, longest] = hole(automatic);
  EXPECT_LE(longest, 2.0);
  EXPECT_LE(deviation, 0.02);
  EXPECT_TRUE(automatic.warnings.empty());
  options.curve_tolerance = 0.1;
  const PhysicalMesh given = read_physical_mesh(geo, options);
  const auto [given_deviation, given_longest] = hole(given);
  EXPECT_GT(given_longest, 2.0);
  EXPECT_LE(given_deviation, 0.1);
  ASSERT_EQ(given.warnings.size(), 1U) << "chords of 4.9 m on triangles of 2 m";
  EXPECT_TRUE(contains(given.warnings[0], "the outline of Physical Surface \"rock\" is coarser "
                                          "than the cover mesh"))
      << given.warnings[0];
  EXPECT_TRUE(contains(given.warnings[0], "lower [cover_mesh] curve_tolerance to at most"))
      << given.warnings[0];
}

TEST(CurvesAndCoverMesh, CoarseMshCurveIsWarnedAboutAtTheEndOfTheRunAndInTheSummary) {
  const TempDir directory("nmm_curve_resolution");
  // gmsh's defaults on tunnel.geo (no mesh sizes): the tunnel a 12-gon of 1.55 m chords.
  const fs::path coarse = tunnel_msh(directory.path(), "coarse.msh", 0.0);
  testing::write_text(directory.path() / "case.toml", tunnel_case(coarse.string()));
  CaseAnalysis analysis(read_case_file(directory.path() / "case.toml"));
  const auto warned = std::find_if(
      analysis.warnings().begin(), analysis.warnings().end(),
      [](const std::string& w) { return contains(w, "Physical Curve \"tunnel\" is coarser"); });
  ASSERT_NE(warned, analysis.warnings().end());
  for (const std::string part :
       {"coarse.msh: Physical Curve \"tunnel\" is coarser than the cover mesh: 12 segments where "
        "it bends are longer than [cover_mesh] size = 0.5 m, the longest 1.55 m",
        "about 0.1 m off the curve it stands for",
        "mesh the curve finer in gmsh (a mesh size of at most 0.5 m along it"})
    EXPECT_TRUE(contains(*warned, part)) << *warned;
  // Named once: the surface's outline along the tunnel is the Physical Curve's.
  EXPECT_EQ(std::count_if(analysis.warnings().begin(), analysis.warnings().end(),
                          [](const std::string& w) { return contains(w, "coarser"); }),
            1);
  const RunResult result = run_case(analysis, {});
  EXPECT_NE(std::find(result.warnings.begin(), result.warnings.end(), *warned),
            result.warnings.end());
  const testing::Json summary =
      testing::parse_json(testing::read_text(directory.path() / "out" / "summary.json"));
  bool in_summary = false;
  for (const testing::Json& item : summary.at("warnings").items)
    in_summary = in_summary || item.string == *warned;
  EXPECT_TRUE(in_summary);
}

TEST(CurvesAndCoverMesh, FineMshCurveIsNotWarnedAbout) {
  const TempDir directory("nmm_curve_resolution");
  const fs::path fine = tunnel_msh(directory.path(), "fine.msh", 0.3);
  testing::write_text(directory.path() / "case.toml", tunnel_case(fine.string()));
  const CaseAnalysis analysis(read_case_file(directory.path() / "case.toml"));
  for (const std::string& w : analysis.warnings())
    EXPECT_FALSE(contains(w, "coarser than the cover mesh")) << w;
}

TEST(CurvesAndCoverMesh, CurveToleranceIsRefusedForAMshNamingTheFileAndTheKey) {
  const std::string text = tunnel_case("tunnel.msh", "curve_tolerance = 0.01\n");
  try {
    (void)parse_case_text(text, "case.toml");
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& error) {
    const std::string message = error.what();
    EXPECT_TRUE(contains(message, "case.toml:4:")) << message;
    EXPECT_TRUE(contains(message, "[cover_mesh] curve_tolerance cannot apply to the .msh "
                                  "geometry 'tunnel.msh'"))
        << message;
    EXPECT_TRUE(contains(message, "remove curve_tolerance")) << message;
  }
  // 0 is the automatic tolerance, which means nothing for a .msh: accepted.
  EXPECT_NO_THROW(
      (void)parse_case_text(tunnel_case("tunnel.msh", "curve_tolerance = 0\n"), "case.toml"));
  // Through the library as well.
  const TempDir directory("nmm_curve_resolution");
  const fs::path msh = tunnel_msh(directory.path(), "tunnel.msh", 0.3);
  GeometryReadOptions options;
  options.curve_tolerance = 0.01;
  try {
    (void)read_physical_mesh(msh, options);
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& error) {
    EXPECT_TRUE(contains(error.what(), msh.string() + ": [cover_mesh] curve_tolerance = 0.01 m "
                                                      "cannot apply to a .msh"))
        << error.what();
  }
}

/// Triangles of @p mesh whose centroid lies within @p radius of @p centre.
int triangles_near(const MathMesh& mesh, const Point2& centre, double radius) {
  int count = 0;
  for (const auto& t : mesh.triangles) {
    Point2 centroid = Point2::Zero();
    for (const int n : t)
      centroid += mesh.nodes[static_cast<std::size_t>(n)] / 3.0;
    count += (centroid - centre).norm() < radius ? 1 : 0;
  }
  return count;
}

TEST(CurvesAndCoverMesh, GeoSizeFieldGradesTheGmshCoverMeshWhenTheCaseAsksForIt) {
  // refined_point.geo: a Threshold field of 0.1 m near (2, 2), 1 m from 4 m away; size 1 m.
  const TempDir directory("nmm_curve_resolution");
  const std::string base = "geometry = \"" + data("refined_point.geo").string() +
                           "\"\n[cover_mesh]\nkind = \"gmsh\"\nsize = 1.0\n";
  const std::string rest = "[materials.rock]\nyoung = 1.0e9\npoisson = 0.25\ndensity = 1.0\n"
                           "[analysis]\nsteps = 1\n";
  testing::write_text(directory.path() / "uniform.toml", base + rest);
  testing::write_text(directory.path() / "graded.toml", base + "geometry_sizes = true\n" + rest);
  const MathMesh uniform =
      build_case_geometry(read_case_file(directory.path() / "uniform.toml")).math;
  const MathMesh graded =
      build_case_geometry(read_case_file(directory.path() / "graded.toml")).math;
  // Triangles of 0.1 m within 0.5 m of the point: about 0.79 m^2 / 0.0043 m^2 = 180.
  const int near = triangles_near(graded, {2.0, 2.0}, 0.5);
  const int far = triangles_near(graded, {7.0, 7.0}, 0.5);
  EXPECT_GT(near, 100);
  EXPECT_LE(far, 4);
  EXPECT_LE(triangles_near(uniform, {2.0, 2.0}, 0.5), 4) << "the .geo's field is ignored";
  EXPECT_GT(graded.n_triangles(), 2 * uniform.n_triangles());
  // The graded mesh still covers the square exactly.
  double area = 0.0;
  for (const auto& t : graded.triangles)
    area += signed_area(std::vector<Point2>{graded.nodes[static_cast<std::size_t>(t[0])],
                                            graded.nodes[static_cast<std::size_t>(t[1])],
                                            graded.nodes[static_cast<std::size_t>(t[2])]});
  EXPECT_NEAR(area, 100.0, 1e-9);
}

TEST(CurvesAndCoverMesh, GeometrySizesWithoutAGmshCoverMeshFromAGeoIsWarnedToHaveNoEffect) {
  const CaseSpec regular =
      parse_case_text(tunnel_case("tunnel.geo", "geometry_sizes = true\n"), "case.toml");
  EXPECT_TRUE(regular.cover_mesh.geometry_sizes);
  ASSERT_EQ(regular.warnings.size(), 1U);
  EXPECT_TRUE(contains(regular.warnings[0], "case.toml:4: [cover_mesh] geometry_sizes has no "
                                            "effect on a regular cover mesh"))
      << regular.warnings[0];
  const CaseSpec msh = parse_case_text(
      tunnel_case("tunnel.msh", "kind = \"gmsh\"\ngeometry_sizes = true\n"), "case.toml");
  ASSERT_EQ(msh.warnings.size(), 1U);
  EXPECT_TRUE(contains(msh.warnings[0], "geometry_sizes has no effect with a .msh geometry"))
      << msh.warnings[0];
  EXPECT_FALSE(parse_case_text(tunnel_case("tunnel.geo"), "case.toml").cover_mesh.geometry_sizes);
}

} // namespace
} // namespace nmm
