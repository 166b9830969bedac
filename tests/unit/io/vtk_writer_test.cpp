// SPDX-License-Identifier: MIT
// Every file is read back with VTK's own XML readers (and the .pvd with VTK's XML parser).
#include "io/cover_mesh_output.hpp"
#include "io/vtk_writer.hpp"
#include "mesh/error.hpp"

#include "../../support/process.hpp"
#include "../../support/temp_dir.hpp"
#include "../../support/vtk_readers.hpp"
#include <gtest/gtest.h>
#include <unistd.h>
#include <vtkCell.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCellType.h>
#include <vtkDataArray.h>
#include <vtkDataSetTriangleFilter.h>
#include <vtkFieldData.h>
#include <vtkIdList.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkUnstructuredGrid.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace nmm {
namespace {

namespace fs = std::filesystem;
using testing::component_names;
using testing::PvdEntry;
using testing::read_pvd;
using testing::read_text;
using testing::read_vtp;
using testing::read_vtu;
using testing::text_values;

// ---------------------------------------------------------------------------------------
// Helpers

/// A fresh directory per test, removed afterwards.
class VtkWriterTest : public ::testing::Test {
protected:
  /// Files in the test directory whose name ends in ".tmp" (atomic writes leave none).
  [[nodiscard]] std::vector<fs::path> temporary_files() const {
    std::vector<fs::path> result;
    for (const auto& entry : fs::recursive_directory_iterator(dir_))
      if (entry.path().extension() == ".tmp")
        result.push_back(entry.path());
    return result;
  }
  testing::TempDir temp_{"nmm_vtk_writer"};
  fs::path dir_ = temp_.path();
};

/// Checks a read-back array's name, type (Float64 or Int32), shape and values.
void expect_array(vtkFieldData* data,
                  const std::string& name,
                  int n_components,
                  const std::vector<double>& values,
                  bool integer) {
  vtkDataArray* array = data->GetArray(name.c_str());
  ASSERT_NE(array, nullptr) << "no array " << name;
  EXPECT_EQ(array->GetDataType(), integer ? VTK_INT : VTK_DOUBLE) << name;
  EXPECT_EQ(array->GetDataTypeSize(), integer ? 4 : 8) << name;
  EXPECT_EQ(array->GetNumberOfComponents(), n_components) << name;
  ASSERT_EQ(array->GetNumberOfValues(), static_cast<vtkIdType>(values.size())) << name;
  for (std::size_t k = 0; k < values.size(); ++k)
    EXPECT_EQ(array->GetComponent(static_cast<vtkIdType>(k) / n_components,
                                  static_cast<int>(k % static_cast<std::size_t>(n_components))),
              values[k])
        << name << " value " << k;
}

/// True when every byte of @p text is printable ASCII or XML whitespace: no raw binary data
/// (which makes the file ill-formed XML; issue 43).
bool is_plain_text(const std::string& text) {
  return std::all_of(text.begin(), text.end(), [](char c) {
    const auto u = static_cast<unsigned char>(c);
    return (u >= 0x20 && u < 0x7f) || c == '\n' || c == '\t' || c == '\r';
  });
}

std::vector<Point2> cell_points(vtkDataSet* data, vtkIdType cell) {
  vtkNew<vtkIdList> ids;
  data->GetCellPoints(cell, ids);
  std::vector<Point2> result;
  for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k) {
    double p[3];
    data->GetPoint(ids->GetId(k), p);
    EXPECT_EQ(p[2], 0.0);
    result.emplace_back(p[0], p[1]);
  }
  return result;
}

double triangle_area(const Point2& a, const Point2& b, const Point2& c) {
  const Point2 u = b - a;
  const Point2 v = c - a;
  return 0.5 * (u.x() * v.y() - u.y() * v.x());
}

/// Sum of |areas| of the triangles VTK's ear cutting makes of every cell (what ParaView's
/// Tetrahedralize filter draws), per input cell.
std::vector<double> triangulated_areas(vtkUnstructuredGrid* grid) {
  vtkNew<vtkDataSetTriangleFilter> triangulate;
  triangulate->SetInputData(grid);
  triangulate->Update();
  vtkUnstructuredGrid* triangles = triangulate->GetOutput();
  // The filter keeps cell data, so the original cell survives in our `cell` array.
  vtkDataArray* source = triangles->GetCellData()->GetArray("cell");
  EXPECT_NE(source, nullptr);
  std::vector<double> result(static_cast<std::size_t>(grid->GetNumberOfCells()), 0.0);
  if (source == nullptr)
    return result;
  for (vtkIdType t = 0; t < triangles->GetNumberOfCells(); ++t) {
    EXPECT_EQ(triangles->GetCellType(t), VTK_TRIANGLE);
    const auto p = cell_points(triangles, t);
    result[static_cast<std::size_t>(source->GetComponent(t, 0))] +=
        std::abs(triangle_area(p[0], p[1], p[2]));
  }
  return result;
}

bool properly_cross(const Point2& a, const Point2& b, const Point2& c, const Point2& d) {
  const auto side = [](const Point2& o, const Point2& p, const Point2& q) {
    const double z = triangle_area(o, p, q);
    return z > 1e-14 ? 1 : (z < -1e-14 ? -1 : 0);
  };
  return side(a, b, c) * side(a, b, d) < 0 && side(c, d, a) * side(c, d, b) < 0;
}

/// Number of pairs of edges of the closed loop that cross (bridges included).
int crossings(const std::vector<Point2>& loop) {
  int count = 0;
  const std::size_t n = loop.size();
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j)
      if (properly_cross(loop[i], loop[(i + 1) % n], loop[j], loop[(j + 1) % n]))
        ++count;
  return count;
}

std::vector<Point2> coordinates(const std::vector<Point2>& points, const std::vector<int>& loop) {
  std::vector<Point2> result;
  for (const int i : loop)
    result.push_back(points[static_cast<std::size_t>(i)]);
  return result;
}

/// Appends @p loop to @p points and returns its indices.
std::vector<int> add_loop(std::vector<Point2>& points, const Loop& loop) {
  std::vector<int> indices;
  for (const Point2& p : loop) {
    indices.push_back(static_cast<int>(points.size()));
    points.push_back(p);
  }
  return indices;
}

std::vector<std::int32_t> iota_ids(std::size_t n) {
  std::vector<std::int32_t> ids(n);
  for (std::size_t k = 0; k < n; ++k)
    ids[k] = static_cast<std::int32_t>(k);
  return ids;
}

// ---------------------------------------------------------------------------------------
// DataArrays

TEST(DataArrays, VectorsGetThreeComponentsAndNamesMustBeUnique) {
  DataArrays arrays;
  const std::vector<Point2> v{{1, 2}, {3, 4}};
  arrays.add_vectors("displacement", v).add("block", std::vector<std::int32_t>{7, 8});
  const DataArray* displacement = arrays.find("displacement");
  ASSERT_NE(displacement, nullptr);
  EXPECT_EQ(displacement->n_components, 3);
  EXPECT_EQ(displacement->n_tuples(), 2U);
  EXPECT_EQ(std::get<std::vector<double>>(displacement->values),
            (std::vector<double>{1, 2, 0, 3, 4, 0}));
  EXPECT_TRUE(arrays.find("block")->is_integer());
  EXPECT_EQ(arrays.find("missing"), nullptr);
  EXPECT_THROW(arrays.add("block", std::vector<double>{1.0, 2.0}), std::logic_error);
  EXPECT_THROW(arrays.add("stress", std::vector<double>{1.0, 2.0}, 3), std::logic_error);
}

TEST(DataArrays, VectorComponentsAreNamedXYZAndOtherNamesNeedOnePerComponent) {
  DataArrays arrays;
  const std::vector<Point2> v{{1, 2}};
  arrays.add_vectors("velocity", v)
      .add("stress", std::vector<double>{1, 2, 3}, 3, {"sxx", "syy", "sxy"})
      .add("state_name", std::vector<std::string>{"open", "locked"});
  EXPECT_EQ(arrays.find("velocity")->component_names, (std::vector<std::string>{"x", "y", "z"}));
  EXPECT_EQ(arrays.find("stress")->component_names,
            (std::vector<std::string>{"sxx", "syy", "sxy"}));
  EXPECT_TRUE(arrays.find("state_name")->is_text());
  EXPECT_EQ(arrays.find("state_name")->n_tuples(), 2U);
  EXPECT_THROW(arrays.add("principal", std::vector<double>{1, 2}, 2, {"s1"}), std::logic_error);
}

// ---------------------------------------------------------------------------------------
// write_vtu

TEST_F(VtkWriterTest, VtuRoundTripsPointsCellsAndEveryKindOfArray) {
  PolygonMeshData data;
  data.points = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {2, 0}, {2, 1}};
  data.cells = {{{0, 1, 2}, {}}, {{0, 2, 3}, {}}, {{1, 4, 5, 2}, {}}};
  const std::vector<Point2> displacement{{0.1, 0}, {0.2, 0}, {0.3, 0.1},
                                         {0, 0},   {0.5, 0}, {0.5, -0.25}};
  data.point_data.add_vectors("displacement", displacement);
  data.cell_data.add("block", std::vector<std::int32_t>{4, 4, 9})
      .add("stress", std::vector<double>{1, 2, 3, 4, 5, 6, 7, 8, 9.5}, 3)
      .add("flags", std::vector<std::int32_t>{1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12}, 4);
  data.field_data.add_value("TimeValue", 0.125);

  const fs::path file = dir_ / "step_000001.vtu";
  write_vtu(file, data);

  const auto grid = read_vtu(file);
  ASSERT_EQ(grid->GetNumberOfPoints(), 6);
  ASSERT_EQ(grid->GetNumberOfCells(), 3);
  EXPECT_EQ(grid->GetCellType(0), VTK_TRIANGLE);
  EXPECT_EQ(grid->GetCellType(1), VTK_TRIANGLE);
  EXPECT_EQ(grid->GetCellType(2), VTK_POLYGON);
  EXPECT_EQ(cell_points(grid, 2).size(), 4U);
  double p[3];
  grid->GetPoint(5, p);
  EXPECT_EQ(p[0], 2.0);
  EXPECT_EQ(p[1], 1.0);
  EXPECT_EQ(grid->GetPoints()->GetDataType(), VTK_DOUBLE);
  expect_array(grid->GetPointData(), "displacement", 3,
               {0.1, 0, 0, 0.2, 0, 0, 0.3, 0.1, 0, 0, 0, 0, 0.5, 0, 0, 0.5, -0.25, 0}, false);
  expect_array(grid->GetCellData(), "block", 1, {4, 4, 9}, true);
  expect_array(grid->GetCellData(), "stress", 3, {1, 2, 3, 4, 5, 6, 7, 8, 9.5}, false);
  expect_array(grid->GetCellData(), "flags", 4, {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12}, true);
  expect_array(grid->GetFieldData(), "TimeValue", 1, {0.125}, false);

  // Compressed binary data in base64 inside each DataArray, as promised: the whole file is
  // text, so well-formed XML, and has no AppendedData, which ParaView 5.11 cannot read with
  // Debian 12's expat, raw or base64 (issue 43).
  const std::string text = read_text(file);
  EXPECT_NE(text.find("compressor=\"vtkLZ4DataCompressor\""), std::string::npos);
  EXPECT_NE(text.find("format=\"binary\""), std::string::npos);
  EXPECT_EQ(text.find("format=\"appended\""), std::string::npos);
  EXPECT_EQ(text.find("AppendedData"), std::string::npos);
  EXPECT_EQ(text.find("format=\"ascii\""), std::string::npos);
  EXPECT_TRUE(is_plain_text(text));
  EXPECT_TRUE(temporary_files().empty());
}

TEST_F(VtkWriterTest, ComponentNamesAndTextArraysReadBack) {
  PolygonMeshData data;
  data.points = {{0, 0}, {1, 0}, {0, 1}};
  data.cells = {{{0, 1, 2}, {}}};
  const std::vector<Point2> displacement{{0.1, 0}, {0.2, 0}, {0.3, 0.1}};
  data.point_data.add_vectors("displacement", displacement);
  data.cell_data.add("stress", std::vector<double>{1, 2, 3}, 3, {"sxx", "syy", "sxy"})
      .add("covers", std::vector<std::int32_t>{4, 5, 6}, 3, {"node0", "node1", "node2"})
      .add("kind_name", std::vector<std::string>{"VEM block"});
  data.field_data.add("legend", std::vector<std::string>{"0 open", "1 sliding", "2 locked", ""});
  write_vtu(dir_ / "named.vtu", data);

  const auto grid = read_vtu(dir_ / "named.vtu");
  EXPECT_EQ(component_names(grid->GetPointData(), "displacement"),
            (std::vector<std::string>{"x", "y", "z"}));
  EXPECT_EQ(component_names(grid->GetCellData(), "stress"),
            (std::vector<std::string>{"sxx", "syy", "sxy"}));
  EXPECT_EQ(component_names(grid->GetCellData(), "covers"),
            (std::vector<std::string>{"node0", "node1", "node2"}));
  expect_array(grid->GetCellData(), "stress", 3, {1, 2, 3}, false);
  EXPECT_EQ(text_values(grid->GetCellData(), "kind_name"), std::vector<std::string>{"VEM block"});
  EXPECT_EQ(text_values(grid->GetFieldData(), "legend"),
            (std::vector<std::string>{"0 open", "1 sliding", "2 locked", ""}));
  EXPECT_TRUE(is_plain_text(read_text(dir_ / "named.vtu")));
}

TEST_F(VtkWriterTest, WrongArraySizeOrIndexIsAProgrammerError) {
  PolygonMeshData data;
  data.points = {{0, 0}, {1, 0}, {0, 1}};
  data.cells = {{{0, 1, 2}, {}}};
  data.cell_data.add("block", std::vector<std::int32_t>{1, 2});
  EXPECT_THROW(write_vtu(dir_ / "a.vtu", data), std::logic_error);
  data.cell_data = {};
  data.cells = {{{0, 1, 3}, {}}};
  EXPECT_THROW(write_vtu(dir_ / "a.vtu", data), std::logic_error);
  EXPECT_FALSE(fs::exists(dir_ / "a.vtu"));
  EXPECT_TRUE(temporary_files().empty());
}

// ---------------------------------------------------------------------------------------
// Keyhole polygons

struct HoleCase {
  const char* name;
  Loop outer;
  std::vector<Loop> holes;
};

std::vector<HoleCase> hole_cases() {
  return {
      {"square with one hole",
       {{0, 0}, {4, 0}, {4, 4}, {0, 4}},
       {{{1, 1}, {2, 1}, {2, 2}, {1, 2}}}},
      // Outer clockwise, holes of both orientations, one hole right of the other so that
      // the left hole's nearest outer vertex is behind the right hole.
      {"two holes in a row, mixed orientations",
       {{0, 0}, {0, 10}, {10, 10}, {10, 0}},
       {{{2, 4}, {4, 4}, {4, 6}, {2, 6}}, {{6, 3}, {6, 7}, {8, 7}, {8, 3}}}},
      // A thin notch cuts in from the right just below the hole: the outer vertex nearest
      // to the hole's rightmost vertex, (7.2, 4.9), is on the far side of the notch.
      {"hole behind a notch",
       {{0, 0},
        {10, 0},
        {10, 4.9},
        {7.2, 4.9},
        {5.5, 4.9},
        {5.5, 5.1},
        {10, 5.1},
        {10, 10},
        {0, 10}},
       {{{6, 5.3}, {7, 5.3}, {7, 6}, {6, 6}}}},
      // A triangle with three holes, the middle one with collinear vertices.
      {"three holes in a triangle",
       {{0, 0}, {12, 0}, {6, 10}},
       {{{5, 1}, {7, 1}, {6, 2}},
        {{3, 1}, {4, 1}, {3.5, 2}},
        {{5.5, 4}, {6.5, 4}, {6.25, 5}, {6, 6}}}},
  };
}

TEST(KeyholeLoop, AreaIsOuterMinusHolesAndBridgesCrossNothing) {
  for (const HoleCase& c : hole_cases()) {
    SCOPED_TRACE(c.name);
    std::vector<Point2> points;
    PolygonCell cell;
    cell.outer = add_loop(points, c.outer);
    for (const Loop& hole : c.holes)
      cell.holes.push_back(add_loop(points, hole));
    const std::vector<int> loop = keyhole_loop(points, cell);
    EXPECT_EQ(loop.size(), points.size() + 2 * c.holes.size());
    const std::vector<Point2> xy = coordinates(points, loop);
    EXPECT_NEAR(signed_area(xy), area(Polygon{c.outer, c.holes}), 1e-12);
    EXPECT_EQ(crossings(xy), 0);
  }
}

TEST_F(VtkWriterTest, PolygonWithHolesIsOneKeyholeCellOfAreaOuterMinusHoles) {
  PolygonMeshData data;
  for (const HoleCase& c : hole_cases()) {
    PolygonCell cell;
    cell.outer = add_loop(data.points, c.outer);
    for (const Loop& hole : c.holes)
      cell.holes.push_back(add_loop(data.points, hole));
    data.cells.push_back(cell);
  }
  const fs::path file = dir_ / "holes.vtu";
  write_vtu(file, data);

  const auto grid = read_vtu(file);
  const auto cases = hole_cases();
  ASSERT_EQ(grid->GetNumberOfCells(), static_cast<vtkIdType>(cases.size()));
  EXPECT_EQ(grid->GetNumberOfPoints(), static_cast<vtkIdType>(data.points.size()));
  for (std::size_t c = 0; c < cases.size(); ++c) {
    SCOPED_TRACE(cases[c].name);
    const auto cell = static_cast<vtkIdType>(c);
    EXPECT_EQ(grid->GetCellType(cell), VTK_POLYGON);
    const std::vector<Point2> written = cell_points(grid, cell);
    EXPECT_NEAR(signed_area(written), area(Polygon{cases[c].outer, cases[c].holes}), 1e-12);
    EXPECT_EQ(crossings(written), 0);
  }
  // Not checked, because it does not hold with VTK 9.1: vtkPolygon's ear cutting (used by
  // ParaView's Triangulate and Tetrahedralize) returns no triangles for a zero-width
  // keyhole, and ParaView's surface rendering draws the fan of vertex 0, which covers the
  // holes. docs/output.md says so.
}

TEST_F(VtkWriterTest, ConcavePolygonStartsAtAVertexWhoseFanCoversItExactly) {
  // An arrow head, listed from a tip: the fan from (0,0) would cover the notch; the fan from
  // the reflex vertex (1,2) is exact (ParaView draws a polygon as the fan of vertex 0).
  const Loop arrow{{0, 0}, {4, 2}, {0, 4}, {1, 2}};
  // An L shape given clockwise: only its reflex corner (1,1) sees the whole polygon.
  const Loop ell{{0, 0}, {0, 2}, {1, 2}, {1, 1}, {2, 1}, {2, 0}};
  // A comb is star-shaped from no vertex: written as given (made counter-clockwise).
  const Loop comb{{0, 0}, {5, 0}, {5, 2}, {4, 2}, {4, 1}, {3, 1},
                  {3, 2}, {2, 2}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
  const std::vector<Loop> loops{arrow, ell, comb};
  PolygonMeshData data;
  for (const Loop& loop : loops)
    data.cells.push_back({add_loop(data.points, loop), {}});
  data.cell_data.add("cell", iota_ids(loops.size()));
  write_vtu(dir_ / "concave.vtu", data);

  const auto grid = read_vtu(dir_ / "concave.vtu");
  ASSERT_EQ(grid->GetNumberOfCells(), 3);
  const std::vector<double> triangulated = triangulated_areas(grid);
  for (vtkIdType c = 0; c < 3; ++c) {
    const Loop& loop = loops[static_cast<std::size_t>(c)];
    const std::vector<Point2> p = cell_points(grid, c);
    ASSERT_EQ(p.size(), loop.size());
    EXPECT_GT(signed_area(p), 0.0) << "written counter-clockwise";
    // ParaView's Tetrahedralize (VTK's ear cutting) fills exactly the polygon.
    EXPECT_NEAR(triangulated[static_cast<std::size_t>(c)], std::abs(signed_area(loop)), 1e-12);
    if (c == 2) {
      EXPECT_EQ(p.front(), Point2(0, 0)) << "no start vertex helps: order kept";
      continue;
    }
    double fan = 0.0;
    for (std::size_t k = 1; k + 1 < p.size(); ++k) {
      const double t = triangle_area(p[0], p[k], p[k + 1]);
      EXPECT_GE(t, 0.0) << "cell " << c << " fan triangle " << k;
      fan += std::abs(t);
    }
    EXPECT_DOUBLE_EQ(fan, std::abs(signed_area(loop)));
  }
}

// ---------------------------------------------------------------------------------------
// .vtp

TEST_F(VtkWriterTest, ContactPointsRoundTripAsVertices) {
  PointCloudData data;
  data.points = {{0.5, 1.0}, {2.0, 1.5}, {3.0, -1.0}};
  const std::vector<Point2> normal{{0, -10}, {0, -20}, {1, -5}};
  data.point_data.add_vectors("normal_force", normal)
      .add("shear_force", std::vector<double>{1.5, -2.5, 0.0})
      .add("state", std::vector<std::int32_t>{0, 1, 2});
  data.field_data.add_value("TimeValue", 2.0);
  write_vtp_points(dir_ / "contacts_000001.vtp", data);

  const auto poly = read_vtp(dir_ / "contacts_000001.vtp");
  ASSERT_EQ(poly->GetNumberOfPoints(), 3);
  EXPECT_EQ(poly->GetNumberOfVerts(), 3);
  EXPECT_EQ(poly->GetNumberOfLines(), 0);
  double p[3];
  poly->GetPoint(1, p);
  EXPECT_EQ(p[0], 2.0);
  EXPECT_EQ(p[1], 1.5);
  expect_array(poly->GetPointData(), "normal_force", 3, {0, -10, 0, 0, -20, 0, 1, -5, 0}, false);
  expect_array(poly->GetPointData(), "shear_force", 1, {1.5, -2.5, 0.0}, false);
  expect_array(poly->GetPointData(), "state", 1, {0, 1, 2}, true);
  expect_array(poly->GetFieldData(), "TimeValue", 1, {2.0}, false);
  EXPECT_TRUE(temporary_files().empty());
}

TEST_F(VtkWriterTest, EmptyContactSetIsAValidFile) {
  PointCloudData data;
  data.point_data.add("state", std::vector<std::int32_t>{});
  write_vtp_points(dir_ / "none.vtp", data);
  const auto poly = read_vtp(dir_ / "none.vtp");
  EXPECT_EQ(poly->GetNumberOfPoints(), 0);
}

TEST_F(VtkWriterTest, PolylinesRoundTripWithCellData) {
  PolylineData data;
  data.points = {{0, 0}, {1, 0}, {2, 1}, {5, 5}, {6, 5}};
  data.lines = {{0, 1, 2}, {3, 4}};
  data.cell_data.add("joint", std::vector<std::int32_t>{3, -1});
  data.point_data.add("opening", std::vector<double>{0, 0.1, 0.2, 0.3, 0.4});
  write_vtp_lines(dir_ / "joints.vtp", data);

  const auto poly = read_vtp(dir_ / "joints.vtp");
  ASSERT_EQ(poly->GetNumberOfLines(), 2);
  EXPECT_EQ(poly->GetNumberOfPoints(), 5);
  EXPECT_EQ(poly->GetCellType(0), VTK_POLY_LINE);
  EXPECT_EQ(poly->GetCellType(1), VTK_LINE);
  EXPECT_EQ(cell_points(poly, 0).size(), 3U);
  expect_array(poly->GetCellData(), "joint", 1, {3, -1}, true);
  expect_array(poly->GetPointData(), "opening", 1, {0, 0.1, 0.2, 0.3, 0.4}, false);
}

// ---------------------------------------------------------------------------------------
// Atomic writes and user errors

TEST_F(VtkWriterTest, OverwritingReplacesTheFileAndLeavesNoTemporary) {
  PolygonMeshData data;
  data.points = {{0, 0}, {1, 0}, {0, 1}};
  data.cells = {{{0, 1, 2}, {}}};
  const fs::path file = dir_ / "mesh.vtu";
  write_vtu(file, data);
  data.points.emplace_back(1, 1);
  data.cells.push_back({{1, 3, 2}, {}});
  write_vtu(file, data);
  EXPECT_EQ(read_vtu(file)->GetNumberOfCells(), 2);
  EXPECT_TRUE(temporary_files().empty());
}

/// Runs @p write and checks it throws an InputError whose message names @p named.
template <class Write> void expect_input_error_naming(const fs::path& named, Write&& write) {
  try {
    write();
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(named.string()), std::string::npos) << e.what();
  }
}

TEST_F(VtkWriterTest, UnwritableDirectoryIsAnInputErrorNamingIt) {
  PolygonMeshData data;
  data.points = {{0, 0}, {1, 0}, {0, 1}};
  data.cells = {{{0, 1, 2}, {}}};

  const fs::path missing = dir_ / "no_such_dir";
  expect_input_error_naming(missing, [&] { write_vtu(missing / "mesh.vtu", data); });

  const fs::path not_a_directory = dir_ / "plain_file";
  std::ofstream(not_a_directory) << "x";
  expect_input_error_naming(not_a_directory,
                            [&] { write_vtu(not_a_directory / "mesh.vtu", data); });

  const fs::path taken = dir_ / "taken.vtu"; // a directory where the file should go
  fs::create_directory(taken);
  expect_input_error_naming(taken, [&] { write_vtu(taken, data); });

  const fs::path read_only = dir_ / "read_only";
  fs::create_directory(read_only);
  fs::permissions(read_only, fs::perms::owner_read | fs::perms::owner_exec);
  if (::access(read_only.c_str(), W_OK) == 0) {
    // root ignores permissions; the cases above still cover the error path.
    std::cout << "[ info     ] running as root: read-only directory case skipped\n";
  } else {
    expect_input_error_naming(read_only, [&] { write_vtu(read_only / "mesh.vtu", data); });
    PvdSeries series(read_only / "case.pvd");
    expect_input_error_naming(read_only, [&] { series.add(0.0, {read_only / "step.vtu"}); });
  }
  fs::permissions(read_only, fs::perms::owner_all);
  EXPECT_TRUE(temporary_files().empty());
}

// ---------------------------------------------------------------------------------------
// PvdSeries

TEST_F(VtkWriterTest, PvdIsValidAfterEveryAddAndListsEntriesInOrder) {
  fs::create_directory(dir_ / "steps");
  PolygonMeshData mesh;
  mesh.points = {{0, 0}, {1, 0}, {0, 1}};
  mesh.cells = {{{0, 1, 2}, {}}};
  PointCloudData contacts;
  contacts.points = {{0.5, 0.5}};

  const fs::path pvd = dir_ / "case.pvd";
  PvdSeries series(pvd);
  EXPECT_FALSE(fs::exists(pvd)) << "nothing is written before the first add()";
  struct Part {
    double time;
    fs::path file;
    int part;
    std::string listed;
  };
  // Three output steps; the second has two parts (elements and contacts).
  const std::vector<std::vector<Part>> steps{
      {{0.0, dir_ / "step_000000.vtu", 0, "step_000000.vtu"}},
      {{0.1 + 0.2, dir_ / "step_000010.vtu", 0, "step_000010.vtu"},
       {0.1 + 0.2, dir_ / "contacts_000010.vtp", 1, "contacts_000010.vtp"}},
      {{1.0e-3 / 3.0, dir_ / "steps" / "a&b <'quoted'>.vtu", 0, "steps/a&b <'quoted'>.vtu"}},
  };
  std::vector<Part> listed;
  for (const std::vector<Part>& step : steps) {
    std::vector<fs::path> files;
    for (const Part& p : step) {
      if (p.part == 0)
        write_vtu(p.file, mesh);
      else
        write_vtp_points(p.file, contacts);
      files.push_back(p.file);
      listed.push_back(p);
    }
    series.add(step.front().time, files);

    const std::vector<PvdEntry> lines = read_pvd(pvd);
    ASSERT_EQ(lines.size(), listed.size());
    for (std::size_t k = 0; k < listed.size(); ++k) {
      EXPECT_EQ(lines[k].time, listed[k].time) << "exact round trip";
      EXPECT_EQ(lines[k].part, listed[k].part);
      EXPECT_EQ(lines[k].file, listed[k].listed);
      EXPECT_TRUE(fs::exists(dir_ / lines[k].file)) << "relative to the .pvd";
    }
    EXPECT_EQ(series.entries().size(), listed.size());
    EXPECT_TRUE(temporary_files().empty());
  }
  for (const PvdEntry& line : read_pvd(pvd))
    EXPECT_EQ(line.name, "") << "a series without part names names no part";
  // The entry VTK parsed really is the file: read it through the .pvd's relative path.
  EXPECT_EQ(read_vtu(dir_ / read_pvd(pvd).back().file)->GetNumberOfCells(), 1);
  EXPECT_NE(read_text(pvd).find("a&amp;b &lt;&apos;quoted&apos;&gt;.vtu"), std::string::npos);
}

TEST_F(VtkWriterTest, PvdNamesEachPartThatHasAName) {
  PolygonMeshData mesh;
  mesh.points = {{0, 0}, {1, 0}, {0, 1}};
  mesh.cells = {{{0, 1, 2}, {}}};
  std::vector<fs::path> files;
  for (const char* name : {"a.vtu", "b.vtu", "c.vtu"}) {
    files.push_back(dir_ / name);
    write_vtu(files.back(), mesh);
  }
  PvdSeries series(dir_ / "case.pvd", {"elements", "contacts & <more>"});
  series.add(0.5, files);
  const std::vector<PvdEntry> lines = read_pvd(dir_ / "case.pvd");
  ASSERT_EQ(lines.size(), 3U);
  EXPECT_EQ(lines[0].name, "elements");
  EXPECT_EQ(lines[1].name, "contacts & <more>");
  EXPECT_EQ(lines[2].name, "") << "part 2 has no name";
  EXPECT_EQ(read_text(dir_ / "case.pvd").find("name=\"\""), std::string::npos);
  // A restored series (a restart) is named as well.
  series.restore({{0.0, 1, "b.vtu"}});
  EXPECT_EQ(read_pvd(dir_ / "case.pvd").at(0).name, "contacts & <more>");
}

TEST_F(VtkWriterTest, PvdInAMissingDirectoryIsAnInputErrorAndListsNothing) {
  const fs::path missing = dir_ / "gone";
  PvdSeries series(missing / "case.pvd");
  expect_input_error_naming(missing, [&] { series.add(0.0, {missing / "step_000000.vtu"}); });
  EXPECT_TRUE(series.entries().empty());
}

// ---------------------------------------------------------------------------------------
// Cover mesher output

/// Three elements: a plain triangle, an element of two atoms (a quadrilateral and a
/// triangle, cut by a joint through its triangle), and an element with a hole.
CoverSystem small_cover_system() {
  CoverSystem covers;
  Element plain;
  plain.triangle = 0;
  plain.covers = {0, 1, 2};
  plain.material = 0;
  plain.block = 0;
  plain.polygons = {Polygon{{{0, 0}, {2, 0}, {0, 2}}, {}}};
  plain.area = 2.0;
  Element cut;
  cut.triangle = 1;
  cut.covers = {3, 4, 5};
  cut.material = 1;
  cut.block = 1;
  cut.polygons = {Polygon{{{2, 0}, {3, 0}, {2.5, 1}, {1.5, 1}}, {}},
                  Polygon{{{1, 2}, {1.5, 1.5}, {1.25, 2}}, {}}};
  cut.area = area(cut.polygons[0]) + area(cut.polygons[1]);
  Element holed;
  holed.triangle = 2;
  holed.covers = {6, 7, 8};
  holed.material = 0;
  holed.block = 2;
  holed.polygons = {Polygon{{{10, 0}, {20, 0}, {10, 10}}, {{{12, 2}, {14, 2}, {12, 4}}}}};
  holed.area = area(holed.polygons[0]);
  covers.elements = {plain, cut, holed};
  return covers;
}

TEST_F(VtkWriterTest, CoverMeshHasOneCellPerAtomWithItsElementsData) {
  const CoverSystem covers = small_cover_system();
  const fs::path file = dir_ / "mesh.vtu";
  write_cover_mesh_vtu(file, covers);

  const auto grid = read_vtu(file);
  ASSERT_EQ(grid->GetNumberOfCells(), 4);
  EXPECT_EQ(grid->GetNumberOfPoints(), 3 + 4 + 3 + 6);
  vtkCellData* cells = grid->GetCellData();
  expect_array(cells, "element", 1, {0, 1, 1, 2}, true);
  expect_array(cells, "triangle", 1, {0, 1, 1, 2}, true);
  expect_array(cells, "covers", 3, {0, 1, 2, 3, 4, 5, 3, 4, 5, 6, 7, 8}, true);
  EXPECT_EQ(component_names(cells, "covers"),
            (std::vector<std::string>{"node0", "node1", "node2"}));
  expect_array(cells, "material", 1, {0, 1, 1, 0}, true);
  expect_array(cells, "block", 1, {0, 1, 1, 2}, true);
  expect_array(cells, "n_atoms", 1, {1, 2, 2, 1}, true);
  const double cut_area = covers.elements[1].area;
  expect_array(cells, "area", 1, {2.0, cut_area, cut_area, 48.0}, false);
  EXPECT_EQ(grid->GetCellType(0), VTK_TRIANGLE);
  EXPECT_EQ(grid->GetCellType(1), VTK_POLYGON);
  EXPECT_EQ(grid->GetCellType(3), VTK_POLYGON);
  // Each written polygon has the area of its atom; the holed one is a keyhole.
  const std::vector<double> atom_areas{2.0, area(covers.elements[1].polygons[0]),
                                       area(covers.elements[1].polygons[1]), 48.0};
  for (vtkIdType c = 0; c < 4; ++c)
    EXPECT_NEAR(signed_area(cell_points(grid, c)), atom_areas[static_cast<std::size_t>(c)], 1e-12);
  EXPECT_EQ(cell_points(grid, 3).size(), 3U + 3U + 2U);
}

TEST_F(VtkWriterTest, MathMeshHasTrianglesNodeIdsAndCoverCounts) {
  MathMesh mesh;
  mesh.nodes = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
  CoverSystem covers;
  covers.node_covers = {{0}, {1, 2}, {}, {3}};

  write_math_mesh_vtu(dir_ / "math_mesh.vtu", mesh, &covers);
  const auto grid = read_vtu(dir_ / "math_mesh.vtu");
  ASSERT_EQ(grid->GetNumberOfCells(), 2);
  ASSERT_EQ(grid->GetNumberOfPoints(), 4);
  EXPECT_EQ(grid->GetCellType(0), VTK_TRIANGLE);
  EXPECT_EQ(grid->GetCellType(1), VTK_TRIANGLE);
  vtkNew<vtkIdList> ids;
  grid->GetCellPoints(1, ids);
  ASSERT_EQ(ids->GetNumberOfIds(), 3);
  EXPECT_EQ(ids->GetId(0), 0);
  EXPECT_EQ(ids->GetId(1), 2);
  EXPECT_EQ(ids->GetId(2), 3);
  expect_array(grid->GetCellData(), "triangle", 1, {0, 1}, true);
  expect_array(grid->GetPointData(), "node", 1, {0, 1, 2, 3}, true);
  expect_array(grid->GetPointData(), "n_covers", 1, {1, 2, 0, 1}, true);

  write_math_mesh_vtu(dir_ / "bare.vtu", mesh);
  const auto bare = read_vtu(dir_ / "bare.vtu");
  EXPECT_EQ(bare->GetPointData()->GetArray("n_covers"), nullptr);
  expect_array(bare->GetPointData(), "node", 1, {0, 1, 2, 3}, true);
}

TEST_F(VtkWriterTest, BoundaryLoopsBecomePolylinesSplitWhereTheJointChanges) {
  CoverSystem covers;
  BoundaryLoop square; // free boundary, then joint 3 along the top and left, then free
  square.block = 5;
  square.vertices = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  square.edges.resize(4);
  square.edges[2].joint = 3;
  square.edges[3].joint = 3;
  BoundaryLoop hole; // all free: one closed polyline
  hole.block = 5;
  hole.vertices = {{0.4, 0.4}, {0.4, 0.6}, {0.6, 0.6}};
  hole.edges.resize(3);
  covers.loops = {square, hole};

  write_boundary_vtp(dir_ / "boundary.vtp", covers);
  const auto poly = read_vtp(dir_ / "boundary.vtp");
  ASSERT_EQ(poly->GetNumberOfLines(), 3);
  EXPECT_EQ(poly->GetNumberOfPoints(), 7);
  expect_array(poly->GetCellData(), "block", 1, {5, 5, 5}, true);
  expect_array(poly->GetCellData(), "joint", 1, {-1, 3, -1}, true);
  expect_array(poly->GetCellData(), "loop", 1, {0, 0, 1}, true);
  // Free run: (0,0) -> (1,0) -> (1,1); joint run: (1,1) -> (0,1) -> (0,0).
  const std::vector<Point2> free_run = cell_points(poly, 0);
  const std::vector<Point2> joint_run = cell_points(poly, 1);
  ASSERT_EQ(joint_run.size(), 3U);
  ASSERT_EQ(free_run.size(), 3U);
  EXPECT_EQ(joint_run.front(), Point2(1, 1));
  EXPECT_EQ(joint_run.back(), Point2(0, 0));
  EXPECT_EQ(free_run.front(), Point2(0, 0));
  EXPECT_EQ(free_run.back(), Point2(1, 1));
  const std::vector<Point2> closed = cell_points(poly, 2);
  ASSERT_EQ(closed.size(), 4U);
  EXPECT_EQ(closed.front(), closed.back());
}

} // namespace
} // namespace nmm
