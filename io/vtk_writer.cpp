// SPDX-License-Identifier: MIT
#include "io/vtk_writer.hpp"

#include "io/atomic_file.hpp"
#include "io/text.hpp"
#include "mesh/error.hpp"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCellType.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkIdTypeArray.h>
#include <vtkLogger.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkOutputWindow.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkStringArray.h>
#include <vtkTypeInt32Array.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLPolyDataWriter.h>
#include <vtkXMLUnstructuredGridWriter.h>

#include <algorithm>
#include <bit>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <fstream>
#include <iostream>
#include <limits>
#include <numeric>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <system_error>
#include <type_traits>
#include <utility>

namespace nmm {

namespace fs = std::filesystem;

// ----------------------------------------------------------------------------------------
// DataArray, DataArrays

std::size_t DataArray::n_values() const noexcept {
  return std::visit([](const auto& v) { return v.size(); }, values);
}

std::size_t DataArray::n_tuples() const noexcept {
  return n_components > 0 ? n_values() / static_cast<std::size_t>(n_components) : 0;
}

namespace {

/// Checks a caller's promise in every build type. Why not NMM_ASSERT: a wrong array size or
/// cell index would otherwise give a file that ParaView rejects or crashes on, long after
/// the run, and the check costs nothing next to the file I/O.
void require(bool condition, const std::string& message) {
  if (!condition)
    throw std::logic_error("vtk_writer: " + message);
}

} // namespace

DataArrays& DataArrays::push(DataArray array) {
  require(!array.name.empty(), "a data array needs a name");
  require(array.n_components > 0,
          "array '" + array.name + "' has " + std::to_string(array.n_components) + " components");
  require(array.n_values() % static_cast<std::size_t>(array.n_components) == 0,
          "array '" + array.name + "' has " + std::to_string(array.n_values()) +
              " values, not a multiple of its " + std::to_string(array.n_components) +
              " components");
  require(array.component_names.empty() ||
              array.component_names.size() == static_cast<std::size_t>(array.n_components),
          "array '" + array.name + "' has " + std::to_string(array.component_names.size()) +
              " component names for " + std::to_string(array.n_components) + " components");
  require(find(array.name) == nullptr, "array name '" + array.name + "' used twice");
  arrays_.push_back(std::move(array));
  return *this;
}

DataArrays& DataArrays::add(std::string name,
                            std::vector<double> values,
                            int n_components,
                            std::vector<std::string> component_names) {
  return push(
      DataArray{std::move(name), n_components, std::move(values), std::move(component_names)});
}

DataArrays& DataArrays::add(std::string name,
                            std::vector<std::int32_t> values,
                            int n_components,
                            std::vector<std::string> component_names) {
  return push(
      DataArray{std::move(name), n_components, std::move(values), std::move(component_names)});
}

DataArrays& DataArrays::add(std::string name, std::vector<std::string> values) {
  return push(DataArray{std::move(name), 1, std::move(values), {}});
}

DataArrays& DataArrays::add_vectors(std::string name, std::span<const Point2> vectors) {
  std::vector<double> values;
  values.reserve(3 * vectors.size());
  for (const Point2& v : vectors) {
    values.push_back(v.x());
    values.push_back(v.y());
    values.push_back(0.0);
  }
  return add(std::move(name), std::move(values), 3, {"x", "y", "z"});
}

DataArrays& DataArrays::add_value(std::string name, double value) {
  return add(std::move(name), std::vector<double>{value}, 1);
}

const DataArray* DataArrays::find(std::string_view name) const noexcept {
  const auto it = std::find_if(arrays_.begin(), arrays_.end(),
                               [&](const DataArray& a) { return a.name == name; });
  return it == arrays_.end() ? nullptr : &*it;
}

// ----------------------------------------------------------------------------------------
// Planar predicates for the keyhole bridges and the fan start

namespace {

/// Twice the signed area of (o, a, b): > 0 when b lies left of the line o -> a.
double cross(const Point2& o, const Point2& a, const Point2& b) {
  const Point2 u = a - o;
  const Point2 v = b - o;
  return u.x() * v.y() - u.y() * v.x();
}

/// Sign of cross() with a relative tolerance, so that vertices split along a straight edge
/// (boundary loops are split at every math edge) count as collinear despite rounding.
int orientation(const Point2& o, const Point2& a, const Point2& b) {
  const double c = cross(o, a, b);
  const double scale = (a - o).norm() * (b - o).norm();
  if (std::abs(c) <= 1e-12 * scale)
    return 0;
  return c > 0.0 ? 1 : -1;
}

/// For x collinear with p, q: true when x lies strictly between them.
bool strictly_between(const Point2& p, const Point2& q, const Point2& x) {
  return (x - p).dot(q - p) > 0.0 && (x - q).dot(p - q) > 0.0;
}

/// True when a segment leaving corner v (edges a -> v -> b, material on the left) towards t
/// starts inside the material.
bool opens_into(const Point2& a, const Point2& v, const Point2& b, const Point2& t) {
  const bool left_of_in = orientation(a, v, t) > 0;
  const bool left_of_out = orientation(v, b, t) > 0;
  if (orientation(a, v, b) > 0)
    return left_of_in && left_of_out; // convex corner: inside both half-planes
  return left_of_in || left_of_out;   // reflex or straight corner
}

/// True when edge (a, b) is in the way of the bridge m -> v: it crosses it, a vertex lies on
/// it, or a bridge end lies inside the edge. Edges merely ending at m or v do not block.
bool blocks(const Point2& m, const Point2& v, const Point2& a, const Point2& b) {
  const int o1 = orientation(m, v, a);
  const int o2 = orientation(m, v, b);
  const int o3 = orientation(a, b, m);
  const int o4 = orientation(a, b, v);
  if (o1 * o2 < 0 && o3 * o4 < 0)
    return true;
  const auto on_bridge = [&](const Point2& p, int o) {
    return o == 0 && p != m && p != v && strictly_between(m, v, p);
  };
  const auto on_edge = [&](const Point2& p, int o) {
    return o == 0 && p != a && p != b && strictly_between(a, b, p);
  };
  return on_bridge(a, o1) || on_bridge(b, o2) || on_edge(m, o3) || on_edge(v, o4);
}

double loop_signed_area(std::span<const Point2> points, const std::vector<int>& loop) {
  std::vector<Point2> coordinates;
  coordinates.reserve(loop.size());
  for (const int i : loop)
    coordinates.push_back(points[static_cast<std::size_t>(i)]);
  return signed_area(coordinates);
}

void check_loop(std::span<const Point2> points, const std::vector<int>& loop, const char* what) {
  require(loop.size() >= 3, std::string(what) + " loop with " + std::to_string(loop.size()) +
                                " points (a polygon needs 3)");
  for (const int i : loop)
    require(i >= 0 && static_cast<std::size_t>(i) < points.size(),
            "point index " + std::to_string(i) + " out of range (" + std::to_string(points.size()) +
                " points)");
}

/// A copy of @p loop turning the requested way (counter-clockwise when @p ccw).
std::vector<int> oriented(std::span<const Point2> points, std::vector<int> loop, bool ccw) {
  if ((loop_signed_area(points, loop) > 0.0) != ccw)
    std::reverse(loop.begin(), loop.end());
  return loop;
}

/// The position in @p loop of a vertex from which the triangle fan covers the counter-
/// clockwise loop exactly (no fan triangle turns clockwise: the vertex is in the kernel of
/// the polygon), or 0 when there is none. ParaView draws polygons as such fans.
std::size_t fan_start(std::span<const Point2> points, const std::vector<int>& loop) {
  const std::size_t n = loop.size();
  const auto at = [&](std::size_t k) -> const Point2& {
    return points[static_cast<std::size_t>(loop[k % n])];
  };
  for (std::size_t s = 0; s < n; ++s) {
    bool covers = true;
    for (std::size_t k = 1; k + 1 < n && covers; ++k)
      covers = orientation(at(s), at(s + k), at(s + k + 1)) >= 0;
    if (covers)
      return s;
  }
  return 0;
}

} // namespace

std::vector<int> keyhole_loop(std::span<const Point2> points, const PolygonCell& cell) {
  check_loop(points, cell.outer, "outer");
  std::vector<int> loop = oriented(points, cell.outer, true);
  if (cell.holes.empty())
    return loop;

  std::vector<std::vector<int>> holes;
  holes.reserve(cell.holes.size());
  for (const std::vector<int>& hole : cell.holes) {
    check_loop(points, hole, "hole");
    holes.push_back(oriented(points, hole, false));
  }
  const auto point = [&](int i) -> const Point2& { return points[static_cast<std::size_t>(i)]; };
  const auto max_x = [&](const std::vector<int>& hole) {
    double x = -std::numeric_limits<double>::infinity();
    for (const int i : hole)
      x = std::max(x, point(i).x());
    return x;
  };
  // Eberly's order, the hole reaching furthest right first: its rightmost vertex then always
  // sees a vertex of the outer loop or of an earlier hole past every hole still waiting.
  std::stable_sort(holes.begin(), holes.end(),
                   [&](const auto& a, const auto& b) { return max_x(a) > max_x(b); });

  for (std::size_t h = 0; h < holes.size(); ++h) {
    const std::vector<int>& hole = holes[h];
    const std::size_t nh = hole.size();
    const auto bridge_is_clear = [&](std::size_t m, std::size_t j) {
      const std::size_t n = loop.size();
      const Point2& pm = point(hole[m]);
      const Point2& pv = point(loop[j]);
      if (!opens_into(point(hole[(m + nh - 1) % nh]), pm, point(hole[(m + 1) % nh]), pv) ||
          !opens_into(point(loop[(j + n - 1) % n]), pv, point(loop[(j + 1) % n]), pm))
        return false;
      const auto crosses_loop = [&](const std::vector<int>& other) {
        for (std::size_t k = 0; k < other.size(); ++k)
          if (blocks(pm, pv, point(other[k]), point(other[(k + 1) % other.size()])))
            return true;
        return false;
      };
      if (crosses_loop(loop))
        return false;
      for (std::size_t g = h; g < holes.size(); ++g)
        if (crosses_loop(holes[g]))
          return false;
      return true;
    };
    // Hole vertices by decreasing x (the first is the classic choice), loop vertices by
    // distance from it: the first clear pair is the bridge.
    std::vector<std::size_t> hole_order(nh);
    std::iota(hole_order.begin(), hole_order.end(), std::size_t{0});
    std::stable_sort(hole_order.begin(), hole_order.end(), [&](std::size_t a, std::size_t b) {
      return point(hole[a]).x() > point(hole[b]).x();
    });
    std::size_t bridge_m = hole_order.front();
    std::size_t bridge_j = loop.size();
    for (const std::size_t m : hole_order) {
      std::vector<std::size_t> loop_order(loop.size());
      std::iota(loop_order.begin(), loop_order.end(), std::size_t{0});
      const Point2& pm = point(hole[m]);
      std::stable_sort(loop_order.begin(), loop_order.end(), [&](std::size_t a, std::size_t b) {
        return (point(loop[a]) - pm).squaredNorm() < (point(loop[b]) - pm).squaredNorm();
      });
      const auto clear = std::find_if(loop_order.begin(), loop_order.end(),
                                      [&](std::size_t j) { return bridge_is_clear(m, j); });
      if (clear != loop_order.end()) {
        bridge_m = m;
        bridge_j = *clear;
        break;
      }
      // Degenerate input (a hole crossing the outer loop) has no clear bridge at all: the
      // nearest vertex still gives the right area, and output must not stop a run.
      if (bridge_j == loop.size())
        bridge_j = loop_order.front();
    }
    std::vector<int> merged;
    merged.reserve(loop.size() + nh + 2);
    merged.insert(merged.end(), loop.begin(),
                  loop.begin() + static_cast<std::ptrdiff_t>(bridge_j) + 1);
    for (std::size_t k = 0; k <= nh; ++k)
      merged.push_back(hole[(bridge_m + k) % nh]);
    merged.insert(merged.end(), loop.begin() + static_cast<std::ptrdiff_t>(bridge_j), loop.end());
    loop = std::move(merged);
  }
  return loop;
}

// ----------------------------------------------------------------------------------------
// Atomic files

namespace {

// ----------------------------------------------------------------------------------------
// VTK conversion

vtkSmartPointer<vtkAbstractArray> to_vtk(const std::vector<std::string>& values, int n_components) {
  auto result = vtkSmartPointer<vtkStringArray>::New();
  result->SetNumberOfComponents(n_components);
  result->SetNumberOfValues(static_cast<vtkIdType>(values.size()));
  for (std::size_t k = 0; k < values.size(); ++k)
    result->SetValue(static_cast<vtkIdType>(k), values[k]);
  return result;
}

template <class Value>
vtkSmartPointer<vtkAbstractArray> to_vtk(const std::vector<Value>& values, int n_components) {
  using VtkArray =
      std::conditional_t<std::is_same_v<Value, double>, vtkDoubleArray, vtkTypeInt32Array>;
  auto result = vtkSmartPointer<VtkArray>::New();
  result->SetNumberOfComponents(n_components);
  result->SetNumberOfTuples(static_cast<vtkIdType>(values.size()) / n_components);
  // -0.0 is written as 0.0. VTK puts each array's range into the file's header and
  // computes it with threads: of an array holding both zeros, which one is the minimum
  // depends on the threads' order, so the same data gave "-0" in one file and "0" in
  // the next (a restarted run's contact forces differed from the straight run's in
  // that header alone, once under load). x + 0.0 is x for every other value.
  std::transform(values.begin(), values.end(), result->GetPointer(0),
                 [](Value v) { return v + Value{0}; });
  return result;
}

vtkSmartPointer<vtkAbstractArray> to_vtk(const DataArray& array) {
  vtkSmartPointer<vtkAbstractArray> result = std::visit(
      [&](const auto& values) { return to_vtk(values, array.n_components); }, array.values);
  result->SetName(array.name.c_str());
  for (std::size_t c = 0; c < array.component_names.size(); ++c)
    result->SetComponentName(static_cast<vtkIdType>(c), array.component_names[c].c_str());
  return result;
}

/// Adds @p arrays to @p target; @p n_tuples is the required tuple count (points or cells),
/// or negative for field data, whose arrays may have any length.
void add_arrays(vtkFieldData* target,
                const DataArrays& arrays,
                std::ptrdiff_t n_tuples,
                const char* kind) {
  for (const DataArray& array : arrays.arrays()) {
    require(n_tuples < 0 || array.n_tuples() == static_cast<std::size_t>(n_tuples),
            std::string(kind) + " array '" + array.name + "' has " +
                std::to_string(array.n_tuples()) + " tuples for " + std::to_string(n_tuples) +
                (std::string(kind) == "point" ? " points" : " cells"));
    target->AddArray(to_vtk(array));
  }
}

vtkNew<vtkPoints> to_vtk_points(const std::vector<Point2>& points) {
  vtkNew<vtkPoints> result;
  result->SetDataTypeToDouble();
  result->SetNumberOfPoints(static_cast<vtkIdType>(points.size()));
  for (std::size_t i = 0; i < points.size(); ++i)
    result->SetPoint(static_cast<vtkIdType>(i), points[i].x(), points[i].y(), 0.0);
  return result;
}

/// A cell array from loops of point indices (offsets + connectivity, VTK 9 layout).
vtkNew<vtkCellArray> to_vtk_cells(const std::vector<std::vector<int>>& loops) {
  vtkNew<vtkIdTypeArray> offsets;
  vtkNew<vtkIdTypeArray> connectivity;
  offsets->SetNumberOfValues(static_cast<vtkIdType>(loops.size() + 1));
  vtkIdType size = 0;
  for (const auto& loop : loops)
    size += static_cast<vtkIdType>(loop.size());
  connectivity->SetNumberOfValues(size);
  vtkIdType next = 0;
  for (std::size_t c = 0; c < loops.size(); ++c) {
    offsets->SetValue(static_cast<vtkIdType>(c), next);
    for (const int i : loops[c])
      connectivity->SetValue(next++, i);
  }
  offsets->SetValue(static_cast<vtkIdType>(loops.size()), next);
  vtkNew<vtkCellArray> cells;
  cells->SetData(offsets, connectivity);
  return cells;
}

/// Where VTK's own messages go instead of the terminal. VTK prints an error as "ERROR: In
/// .../vtkXMLWriter.cxx, line N", then "vtkXMLUnstructuredGridWriter (0x55...): ...", and its
/// logger repeats it with a time stamp, in colour, with the pipeline's request dumped: source
/// lines and addresses that say neither which file failed nor what to do. This window keeps
/// the text for write_xml(), which reports a failed write with the file, the reason and
/// what to do (write_file_atomically()), VTK's words only where the system gave no reason.
class MessageWindow final : public vtkOutputWindow {
public:
  static MessageWindow* New();
  void DisplayText(const char* text) override {
    if (text != nullptr)
      text_ += text;
  }
  /// What VTK said since the last call.
  std::string take() { return std::exchange(text_, std::string()); }

private:
  std::string text_;
};

vtkStandardNewMacro(MessageWindow);

/// The window, made VTK's output window and its logger silenced on stderr at the first call.
MessageWindow& vtk_messages() {
  static MessageWindow* const window = [] {
    MessageWindow* created = MessageWindow::New();
    vtkOutputWindow::SetInstance(created); // VTK holds it until the process ends
    created->Delete();
    vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
    return created;
  }();
  return *window;
}

/// A VTK XML writer that frees its appended-mode position arrays only when it allocated them.
/// VTK 9.1's writers free them whenever a write fails (vtkXMLUnstructuredDataWriter::
/// WriteAPiece on OutOfDiskSpaceError), also in inline mode, which never allocates them: a
/// step file cut short by a full disk or a file-size limit then freed uninitialised pointers
/// and crashed nmm, depending on what the heap held (tests/unit/io/messages_test.cpp).
template <class Base> class GuardedWriter final : public Base {
public:
  static GuardedWriter* New() {
    auto* writer = new GuardedWriter;
    writer->InitializeObjectBase();
    return writer;
  }

protected:
  void AllocatePositionArrays() override {
    Base::AllocatePositionArrays();
    allocated_ = true;
  }
  void DeletePositionArrays() override {
    if (allocated_)
      Base::DeletePositionArrays();
    allocated_ = false;
  }

private:
  bool allocated_ = false;
};

/// VTK's messages as words: without the source line headers ("ERROR: In FILE, line N"), the
/// object names with their addresses, the indented dumps of pipeline requests and the
/// executive's echo of them ("returned failure for request"); "; " between messages.
std::string vtk_words(const std::string& text) {
  static const std::regex header(R"(^(ERROR|Warning|Generic Warning|Debug): In .*, line \d+$)");
  static const std::regex object(R"(^\w+ ?\(0x[0-9a-fA-F]+\): )");
  std::istringstream in(text);
  std::string words;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line.front() == ' ' || std::regex_match(line, header) ||
        line.find("returned failure for request") != std::string::npos)
      continue;
    line = std::regex_replace(line, object, "", std::regex_constants::format_first_only);
    if (!line.empty())
      words += (words.empty() ? "" : "; ") + line;
  }
  return words;
}

/// LZ4-compressed binary data, base64-encoded inside each DataArray element (VTK's "binary"
/// mode). LZ4 against ZLib's default level on a 1e5-element step file: 3x faster to write,
/// 1.4x larger (docs/benchmarks.md "Time step"); ParaView reads both (LZ4 since 5.5). Inline,
/// not appended: the XML readers of VTK before 9.3.1 (ParaView 5.11) fail on any AppendedData
/// element with an expat that defers reparsing (2.6, and Debian 12's 2.5.0 since its update
/// for CVE-2023-52425): "not well-formed (invalid token)" for raw bytes, which are not XML,
/// and for base64 ones too (their parser cuts the document at AppendedData and relies on
/// expat's callbacks coming at once; checked with Debian 12's ParaView 5.11 on 2026-12-01).
/// Inline base64 costs a third more bytes and more write time (docs/benchmarks.md, "Output
/// files").
/// VTK's messages never reach the terminal raw (MessageWindow): a failed write is reported by
/// write_file_atomically() from errno (disk full, file too large, ...), or, when the system
/// gave no reason, by VTK's words with @p file and what to do; messages of a write that
/// succeeded are passed on as words, naming the file.
template <class Writer>
bool write_xml(vtkDataObject* data, const fs::path& tmp, const fs::path& file) {
  MessageWindow& messages = vtk_messages();
  static_cast<void>(messages.take());
  vtkNew<GuardedWriter<Writer>> writer;
  writer->SetInputData(data);
  writer->SetFileName(tmp.c_str());
  writer->SetDataModeToBinary();
  writer->SetCompressorTypeToLZ4();
  writer->SetHeaderTypeToUInt64(); // blocks beyond 4 GiB stay readable
  const bool written = writer->Write() == 1 && writer->GetErrorCode() == 0;
  const int reason = errno; // of the failed write, for write_file_atomically()
  const std::string said = vtk_words(messages.take());
  if (!written && reason == 0 && !said.empty())
    throw OutputWriteError(write_failure_message(file, 0, {}, "VTK's writer says: " + said));
  if (written && !said.empty())
    std::clog << "nmm: VTK, writing " << quoted(file) << ": " << said << '\n';
  errno = reason;
  return written;
}

void check_indices(const std::vector<int>& loop, std::size_t n_points, std::size_t min_size) {
  require(loop.size() >= min_size, "a cell has " + std::to_string(loop.size()) + " points (needs " +
                                       std::to_string(min_size) + ")");
  for (const int i : loop)
    require(i >= 0 && static_cast<std::size_t>(i) < n_points,
            "point index " + std::to_string(i) + " out of range (" + std::to_string(n_points) +
                " points)");
}

} // namespace

void write_vtu(const fs::path& file, const PolygonMeshData& data) {
  std::vector<std::vector<int>> loops;
  loops.reserve(data.cells.size());
  vtkNew<vtkUnsignedCharArray> types;
  types->SetNumberOfValues(static_cast<vtkIdType>(data.cells.size()));
  for (std::size_t c = 0; c < data.cells.size(); ++c) {
    const PolygonCell& cell = data.cells[c];
    std::vector<int> loop = keyhole_loop(data.points, cell);
    if (cell.holes.empty()) {
      const std::size_t start = fan_start(data.points, loop);
      std::rotate(loop.begin(), loop.begin() + static_cast<std::ptrdiff_t>(start), loop.end());
    }
    const bool triangle = loop.size() == 3;
    types->SetValue(static_cast<vtkIdType>(c), triangle ? VTK_TRIANGLE : VTK_POLYGON);
    loops.push_back(std::move(loop));
  }
  vtkNew<vtkUnstructuredGrid> grid;
  grid->SetPoints(to_vtk_points(data.points));
  grid->SetCells(types, to_vtk_cells(loops));
  add_arrays(grid->GetPointData(), data.point_data, static_cast<std::ptrdiff_t>(data.points.size()),
             "point");
  add_arrays(grid->GetCellData(), data.cell_data, static_cast<std::ptrdiff_t>(data.cells.size()),
             "cell");
  add_arrays(grid->GetFieldData(), data.field_data, -1, "field");
  write_file_atomically(file, [&](const fs::path& tmp) {
    return write_xml<vtkXMLUnstructuredGridWriter>(grid, tmp, file);
  });
}

void write_vtp_points(const fs::path& file, const PointCloudData& data) {
  std::vector<std::vector<int>> vertices(data.points.size());
  for (std::size_t i = 0; i < data.points.size(); ++i)
    vertices[i] = {static_cast<int>(i)};
  vtkNew<vtkPolyData> poly;
  poly->SetPoints(to_vtk_points(data.points));
  poly->SetVerts(to_vtk_cells(vertices));
  add_arrays(poly->GetPointData(), data.point_data, static_cast<std::ptrdiff_t>(data.points.size()),
             "point");
  add_arrays(poly->GetFieldData(), data.field_data, -1, "field");
  write_file_atomically(
      file, [&](const fs::path& tmp) { return write_xml<vtkXMLPolyDataWriter>(poly, tmp, file); });
}

void write_vtp_lines(const fs::path& file, const PolylineData& data) {
  for (const auto& line : data.lines)
    check_indices(line, data.points.size(), 2);
  vtkNew<vtkPolyData> poly;
  poly->SetPoints(to_vtk_points(data.points));
  poly->SetLines(to_vtk_cells(data.lines));
  add_arrays(poly->GetPointData(), data.point_data, static_cast<std::ptrdiff_t>(data.points.size()),
             "point");
  add_arrays(poly->GetCellData(), data.cell_data, static_cast<std::ptrdiff_t>(data.lines.size()),
             "cell");
  add_arrays(poly->GetFieldData(), data.field_data, -1, "field");
  write_file_atomically(
      file, [&](const fs::path& tmp) { return write_xml<vtkXMLPolyDataWriter>(poly, tmp, file); });
}

// ----------------------------------------------------------------------------------------
// PvdSeries

namespace {

std::string xml_escape(std::string_view text) {
  std::string result;
  result.reserve(text.size());
  for (const char c : text) {
    switch (c) {
    case '&':
      result += "&amp;";
      break;
    case '<':
      result += "&lt;";
      break;
    case '>':
      result += "&gt;";
      break;
    case '"':
      result += "&quot;";
      break;
    case '\'':
      result += "&apos;";
      break;
    default:
      if (static_cast<unsigned char>(c) < 0x20)
        result += "&#" + std::to_string(static_cast<int>(c)) + ";";
      else
        result += c;
    }
  }
  return result;
}

/// Shortest text that reads back as the same double.
std::string exact_text(double value) {
  char buffer[32];
  const auto [end, error] = std::to_chars(buffer, buffer + sizeof buffer, value);
  return error == std::errc{} ? std::string(buffer, end) : std::to_string(value);
}

} // namespace

PvdSeries::PvdSeries(fs::path pvd_file, std::vector<std::string> part_names)
    : pvd_file_(std::move(pvd_file)), part_names_(std::move(part_names)) {}

void PvdSeries::add(double time, const std::vector<fs::path>& parts) {
  require(!parts.empty(), "an output step without files");
  require(std::isfinite(time), "time " + exact_text(time) + " of " + quoted(parts.front()));
  const fs::path directory = fs::absolute(pvd_file_).parent_path().lexically_normal();
  const std::size_t before = entries_.size();
  for (std::size_t part = 0; part < parts.size(); ++part) {
    const fs::path target = fs::absolute(parts[part]).lexically_normal();
    fs::path relative = target.lexically_relative(directory);
    if (relative.empty())
      relative = target;
    entries_.push_back(Entry{time, static_cast<int>(part), relative.generic_string()});
  }
  try {
    write();
  } catch (...) {
    entries_.resize(before); // keep entries() equal to what the file on disk lists
    throw;
  }
}

void PvdSeries::restore(std::vector<Entry> entries) {
  entries_ = std::move(entries);
  write();
}

void PvdSeries::write() const {
  write_file_atomically(pvd_file_, [&](const fs::path& tmp) {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    out << "<?xml version=\"1.0\"?>\n"
        << "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\""
        << (std::endian::native == std::endian::little ? "LittleEndian" : "BigEndian")
        << "\">\n  <Collection>\n";
    for (const Entry& entry : entries_) {
      out << "    <DataSet timestep=\"" << exact_text(entry.time) << "\" group=\"\" part=\""
          << entry.part << "\"";
      if (entry.part >= 0 && static_cast<std::size_t>(entry.part) < part_names_.size())
        out << " name=\"" << xml_escape(part_names_[static_cast<std::size_t>(entry.part)]) << "\"";
      out << " file=\"" << xml_escape(entry.file) << "\"/>\n";
    }
    out << "  </Collection>\n</VTKFile>\n";
    out.flush();
    return static_cast<bool>(out);
  });
}

} // namespace nmm
