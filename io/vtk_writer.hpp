// SPDX-License-Identifier: MIT
// io/vtk_writer.hpp — VTK XML output (.vtu, .vtp) and .pvd time series for ParaView
// (DESIGN.md "Contracts users see / Output"; docs/output.md lists every file and array).
// Solver-independent: callers fill plain data structs; VTK stays inside io/vtk_writer.cpp.
#pragma once

#include "mesh/geometry.hpp"

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace nmm {

/// One named array of point, cell or field data: n_tuples() tuples of n_components values,
/// stored tuple by tuple (x0 y0 z0 x1 y1 z1 ...). Real values are written as Float64,
/// integer values as Int32, text as a VTK String array (ParaView lists it in the
/// spreadsheet and in hover tooltips, and colours by it as categories).
struct DataArray {
  std::string name;
  int n_components = 1;
  std::variant<std::vector<double>, std::vector<std::int32_t>, std::vector<std::string>> values;
  /// Names of the components, shown by ParaView instead of 0, 1, 2 (e.g. "sxx", "syy",
  /// "sxy"): empty, or one per component.
  std::vector<std::string> component_names;

  [[nodiscard]] bool is_integer() const noexcept {
    return std::holds_alternative<std::vector<std::int32_t>>(values);
  }
  [[nodiscard]] bool is_text() const noexcept {
    return std::holds_alternative<std::vector<std::string>>(values);
  }
  [[nodiscard]] std::size_t n_values() const noexcept;
  /// n_values() / n_components.
  [[nodiscard]] std::size_t n_tuples() const noexcept;
};

/// The arrays attached to points, to cells or to the whole data set. Adding a field is one
/// call: `data.cell_data.add("block", blocks);`, `data.point_data.add_vectors("velocity", v);`.
/// Names must be unique within one DataArrays (ParaView picks arrays by name).
class DataArrays {
public:
  /// Adds a real array of @p n_components values per tuple (1 scalar, 3 vector, 9 tensor...),
  /// its components named @p component_names (none, or one name per component).
  /// @pre values.size() is a multiple of n_components > 0; @p name not used yet.
  DataArrays& add(std::string name,
                  std::vector<double> values,
                  int n_components = 1,
                  std::vector<std::string> component_names = {});
  /// Adds an integer array (ids, counts, flags), written as Int32.
  DataArrays& add(std::string name,
                  std::vector<std::int32_t> values,
                  int n_components = 1,
                  std::vector<std::string> component_names = {});
  /// Adds a text array of one string per tuple (e.g. a name for each value of an integer
  /// code, or a legend in field data).
  DataArrays& add(std::string name, std::vector<std::string> values);
  /// Adds 2D vectors as 3-component tuples (x, y, 0) with components named "x", "y", "z":
  /// ParaView's Warp By Vector, Glyph and Stream Tracer only accept 3-component vectors.
  DataArrays& add_vectors(std::string name, std::span<const Point2> vectors);
  /// Adds a single real value (one tuple, one component), e.g. field data `TimeValue`.
  DataArrays& add_value(std::string name, double value);

  [[nodiscard]] const std::vector<DataArray>& arrays() const noexcept { return arrays_; }
  [[nodiscard]] bool empty() const noexcept { return arrays_.empty(); }
  /// The array called @p name, or nullptr.
  [[nodiscard]] const DataArray* find(std::string_view name) const noexcept;

private:
  DataArrays& push(DataArray array);
  std::vector<DataArray> arrays_;
};

/// One polygon cell: an outer loop of point indices and, optionally, holes inside it. The
/// orientation of each loop is free (as for nmm::Polygon); the writer orients them.
struct PolygonCell {
  std::vector<int> outer;
  std::vector<std::vector<int>> holes;
};

/// A 2D unstructured mesh of polygons for write_vtu(). Point data holds one tuple per point,
/// cell data one tuple per cell; field data arrays hold any number of tuples.
struct PolygonMeshData {
  /// Coordinates in metres (written with z = 0).
  std::vector<Point2> points;
  std::vector<PolygonCell> cells;
  DataArrays point_data;
  DataArrays cell_data;
  /// Whole-data-set values, e.g. `field_data.add_value("TimeValue", t)`.
  DataArrays field_data;
};

/// Points with data, for write_vtp_points() (contacts: position, forces, state).
struct PointCloudData {
  std::vector<Point2> points;
  DataArrays point_data;
  DataArrays field_data;
};

/// Polylines with data, for write_vtp_lines() (joints and boundaries drawn as lines).
struct PolylineData {
  std::vector<Point2> points;
  /// Point indices of each polyline, in order. A closed polyline repeats its first index.
  std::vector<std::vector<int>> lines;
  DataArrays point_data;
  DataArrays cell_data;
  DataArrays field_data;
};

/// Writes @p data as a VTK XML unstructured grid (.vtu): LZ4-compressed binary data, base64-
/// encoded inside each DataArray element, so that the whole file is well-formed XML without
/// an AppendedData element (ParaView 5.11 with an expat that defers reparsing, such as Debian
/// 12's since its fix of CVE-2023-52425, refuses appended data, raw or base64).
/// A cell of 3 points without holes becomes a VTK_TRIANGLE, every other cell one VTK_POLYGON.
/// VTK polygons cannot have holes, so a cell with holes is written as one keyhole loop (see
/// keyhole_loop()). The start vertex of a hole-free polygon is rotated, where possible, to a
/// vertex from which the triangle fan covers the polygon exactly: ParaView draws polygons as
/// fans from their first vertex, so a star-shaped concave polygon then renders correctly.
/// The file appears atomically: it is written to `file` + ".tmp" and renamed.
/// @throws InputError naming the directory or file when it cannot be written.
/// @throws std::logic_error when an index is out of range or an array has the wrong size.
void write_vtu(const std::filesystem::path& file, const PolygonMeshData& data);

/// Writes @p data as VTK XML poly data (.vtp), one VTK_VERTEX cell per point; same format,
/// atomicity and errors as write_vtu().
void write_vtp_points(const std::filesystem::path& file, const PointCloudData& data);

/// Writes @p data as VTK XML poly data (.vtp), one VTK_POLY_LINE cell (VTK_LINE for two
/// points) per polyline; same format, atomicity and errors as write_vtu().
void write_vtp_lines(const std::filesystem::path& file, const PolylineData& data);

/// The single loop of point indices that write_vtu() writes for @p cell: the outer loop
/// counter-clockwise, each hole clockwise and joined to the rest by a zero-width "keyhole"
/// bridge walked there and back, so the bridge ends appear twice. The bridge runs from a hole
/// vertex of maximal x to the nearest vertex it can see, crossing no edge of the outer loop,
/// of any hole or of an earlier bridge (hole elimination as in ear clipping). The shoelace
/// area of the result is |outer| - sum |holes|. Without holes: the outer loop, made
/// counter-clockwise.
/// @pre every index is valid in @p points; loops have at least 3 vertices.
[[nodiscard]] std::vector<int> keyhole_loop(std::span<const Point2> points,
                                            const PolygonCell& cell);

/// A ParaView .pvd time series (a VTK "Collection" file) listing data files by time.
///
/// Every add() rewrites the whole .pvd atomically, so a run that stops at any moment leaves a
/// valid series of everything written so far. Nothing is written before the first add().
class PvdSeries {
public:
  /// One line of the series.
  struct Entry {
    double time = 0.0;
    int part = 0;
    /// Path of the data file relative to the .pvd's directory, with '/' separators.
    std::string file;
  };

  /// @param pvd_file    the .pvd to (re)write; its directory must exist when add() is called.
  /// @param part_names  the `name` attribute of each part's DataSet lines, by part number
  ///                    (ParaView names the series' blocks so); a part without one has none.
  explicit PvdSeries(std::filesystem::path pvd_file, std::vector<std::string> part_names = {});

  /// Appends the data files of one output step at @p time, in seconds, and rewrites the .pvd
  /// once. The files (absolute or relative to the current directory) are the step's parts,
  /// in order (0: elements .vtu, 1: contacts .vtp...): ParaView shows each part as a block.
  /// @throws InputError naming the .pvd when it cannot be written (nothing is added then).
  void add(double time, const std::vector<std::filesystem::path>& parts);

  /// Replaces the series by @p entries (a restart: the steps written up to the checkpoint)
  /// and rewrites the .pvd. @throws InputError as add().
  void restore(std::vector<Entry> entries);

  [[nodiscard]] const std::filesystem::path& file() const noexcept { return pvd_file_; }
  [[nodiscard]] const std::vector<Entry>& entries() const noexcept { return entries_; }

private:
  void write() const;
  std::filesystem::path pvd_file_;
  std::vector<std::string> part_names_;
  std::vector<Entry> entries_;
};

} // namespace nmm
