// SPDX-License-Identifier: MIT
// io/gmsh_internal.hpp — what the io/gmsh_*.cpp files behind io/gmsh_reader.hpp share.
// Included only from those files: it brings in gmsh's API.
#pragma once

#include "io/gmsh_reader.hpp"
#include "mesh/geometry.hpp"
#include "mesh/physical_mesh.hpp"

#include <Eigen/Core>
#include <gmsh.h>

#include <array>
#include <cstddef>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

namespace nmm::detail {

// ----------------------------------------------------------------------------------------
// gmsh errors (gmsh_session.cpp). The session sets General.AbortOnError = 0, so gmsh logs
// errors and carries on; we read them back from the logger after each call that can fail on
// user input.

/// Errors gmsh logs from construction on. Restarting the logger empties it, which keeps
/// logger::get() (a full copy) cheap.
class GmshErrorLog {
public:
  GmshErrorLog() {
    gmsh::logger::stop();
    gmsh::logger::start();
  }

  [[nodiscard]] std::vector<std::string> errors() const {
    std::vector<std::string> log;
    gmsh::logger::get(log);
    std::vector<std::string> result;
    const std::string prefix = "Error: ";
    for (const std::string& line : log) {
      if (line.rfind(prefix, 0) == 0)
        result.push_back(line.substr(prefix.size()));
    }
    return result;
  }
};

/// Throws the InputError for the gmsh @p errors (the first one, and how many more) met while
/// @p doing something with @p file; at the file and line gmsh names, when it names one.
[[noreturn]] void throw_gmsh_error(const std::string& file,
                                   const std::string& doing,
                                   const std::vector<std::string>& errors);

/// Runs @p action and turns whatever gmsh reports into an InputError about @p file.
template <class Action>
void run_gmsh(const std::string& file, const std::string& doing, Action&& action) {
  const GmshErrorLog log;
  try {
    action();
  } catch (const std::string& message) {
    // Only when a .geo file turned General.AbortOnError back on: gmsh then throws its
    // message as a std::string.
    throw_gmsh_error(file, doing, {message});
  }
  const std::vector<std::string> errors = log.errors();
  if (!errors.empty())
    throw_gmsh_error(file, doing, errors);
}

// ----------------------------------------------------------------------------------------
// Reading options (gmsh_reader.cpp)

/// @throws InputError about @p file when @p options' curve tolerance is negative or not
/// finite.
void check_tolerance(const std::string& file, const GeometryReadOptions& options);

// ----------------------------------------------------------------------------------------
// Geometry files (gmsh_file.cpp)

enum class GmshFileKind { geo, msh };

/// The kind of geometry @p file, by its extension.
/// @throws InputError when the file is missing, not a regular file, of another extension or
/// unreadable.
GmshFileKind check_geometry_file(const std::filesystem::path& file);

/// Opens @p file (of @p kind, check_geometry_file()) as gmsh's current model, a .geo first
/// checked for `Exit` and read within @p options' limits (read_within_limits()).
/// @throws InputError with what gmsh reports.
void open_model(const std::filesystem::path& file,
                GmshFileKind kind,
                const GeometryReadOptions& options = {});

// ----------------------------------------------------------------------------------------
// Limits on reading a .geo (gmsh_geo_limits.cpp)

/// Reads the .geo @p file in a child process with @p options' time and memory limits, and
/// returns when it was read within them (whatever gmsh reported: the read in this process
/// reports it). The child dies with this process (PR_SET_PDEATHSIG), so a Ctrl-C that stops
/// nmm stops it too.
/// @throws InputError when the child is stopped at the time limit or runs out of memory.
void read_within_limits(const std::filesystem::path& file, const GeometryReadOptions& options);

// ----------------------------------------------------------------------------------------
// The current model (gmsh_model.cpp)

using Point3 = Eigen::Vector3d;

inline Point2 planar(const Point3& p) { return {p.x(), p.y()}; }

/// @p tags as "1, 2, 3", the first 12 and how many in all when there are more.
std::string tag_list(const std::vector<int>& tags);

/// A physical group of the model: its tag, its name and the tags of its entities.
struct PhysicalGroup {
  int tag = 0;
  std::string name;
  std::vector<int> entities;
};

/// The physical groups of dimension @p dim, in gmsh's order; an unnamed one is called
/// @p unnamed_prefix + "_" + its tag.
std::vector<PhysicalGroup> physical_groups(int dim, const std::string& unnamed_prefix);

/// The tags of the model's entities of dimension @p dim.
std::set<int> entity_tags(int dim);

/// Throws the InputError for a model of @p file without Physical Surface: which surfaces
/// and Physical Curves it has, and how to name the materials.
[[noreturn]] void throw_no_physical_surface(const std::string& file);

/// 2D or 1D elements of one entity as lists of corner (primary) nodes.
std::vector<std::vector<std::size_t>> element_corners(int dim, int tag);

/// Coordinates of every mesh node of the current model, by node tag.
class NodeTable {
public:
  /// @throws InputError when the model has no node @p tag.
  const Point3& at(std::size_t tag);

private:
  void load();
  std::unordered_map<std::size_t, Point3> coordinates_;
  bool loaded_ = false;
};

// ----------------------------------------------------------------------------------------
// Chaining edges (curves between end points, or mesh edges between nodes) into paths and
// loops (gmsh_surface_loops.cpp). Shared by the loops of geometric surfaces and of meshed
// (discrete) ones, and by the pieces of a discrete curve.

struct Chain {
  /// Edge index and whether it is walked from its first to its second node.
  std::vector<std::pair<std::size_t, bool>> edges;
  std::size_t first_node = 0;
  std::size_t last_node = 0;
  bool closed = false;
};

/// @p edges (pairs of node numbers) chained: open paths first, from an end, then loops.
std::vector<Chain> chain_edges(const std::vector<std::array<std::size_t, 2>>& edges);

// ----------------------------------------------------------------------------------------
// Reading one model

/// Reads the curves, surfaces and points of gmsh's current model into the plane; @p file
/// names the model in messages. Curved curves are sampled within a tolerance, once per curve
/// (gmsh_curves.cpp); surfaces become polygons of the loops of their outline
/// (gmsh_surface_loops.cpp).
class ModelReader {
public:
  /// @p max_chord: the longest chord of a sampled curve (m), 0 for no bound.
  ModelReader(std::string file, double tolerance, double max_chord, double z_limit)
      : file_(std::move(file)), tolerance_(tolerance), max_chord_(max_chord), z_limit_(z_limit) {}

  /// True when curve @p tag (read already) stands for a curve that its polyline only
  /// approximates: a curved gmsh curve sampled here, or the mesh of a discrete curve.
  [[nodiscard]] bool is_sampled(int tag) const { return sampled_.count(tag) > 0; }
  /// The curves of the outline of geometric surface @p tag (read already).
  [[nodiscard]] const std::vector<int>& outline(int tag) { return outlines_[tag]; }

  /// The polylines of curve @p tag (one, except for a discrete curve whose mesh is in
  /// pieces), in the curve's parametric direction, computed once per curve.
  const std::vector<std::vector<Point2>>& curve(int tag, const std::string& context);

  /// The polygon of surface @p tag of Physical Surface @p group: the loop of largest area
  /// outside, the others its holes.
  Polygon surface(int tag, const std::string& group);

  /// The coordinates of point @p tag in the plane.
  Point2 point(int tag, const std::string& context);

private:
  /// @p p in the plane z = 0. @throws InputError when it lies off the plane.
  Point2 in_plane(const Point3& p, const std::string& context) const;

  /// The points of curve @p tag at @p parameters.
  std::vector<Point3> evaluate(int tag, const std::vector<double>& parameters) const;

  /// The exact coordinates of the gmsh points at the start and end of curve @p tag, matched
  /// to the curve's values at its parameter bounds (empty for a curve without end points).
  std::optional<std::array<Point3, 2>>
  end_points(int tag, const Point3& first, const Point3& last) const;

  /// The polyline of a gmsh curve of @p type with a parametrisation: the end points of a
  /// Line, otherwise chords subdivided until within the tolerance (and the longest chord).
  std::vector<Point3>
  parametric_curve(int tag, const std::string& type, const std::string& context);

  /// The polylines of the line elements of discrete curve @p tag.
  std::vector<std::vector<Point3>> discrete_curve(int tag, const std::string& context);

  /// The loops of geometric surface @p tag from its boundary curves (recorded in outline()).
  std::vector<Loop> curve_loops(int tag, const std::string& context);

  /// The loops of discrete surface @p tag: the boundary edges of its mesh.
  std::vector<Loop> discrete_loops(int tag, const std::string& context);

  std::string file_;
  double tolerance_;
  double max_chord_;
  double z_limit_;
  std::map<int, std::vector<std::vector<Point2>>> curves_;
  std::set<int> sampled_;
  std::map<int, std::vector<int>> outlines_;
  NodeTable nodes_;
};

// ----------------------------------------------------------------------------------------
// Curves coarser than the cover mesh (gmsh_coarse_curves.cpp)

/// One warning per Physical Curve, and per Physical Surface for its outline curves that no
/// Physical Curve names, whose sampled or meshed curves are coarser than the cover mesh.
/// @p reader has read @p physical from the groups @p surface_groups and @p curve_groups of
/// @p file.
std::vector<std::string> coarse_curve_warnings(const std::string& file,
                                               ModelReader& reader,
                                               const PhysicalMesh& physical,
                                               const std::vector<PhysicalGroup>& surface_groups,
                                               const std::vector<PhysicalGroup>& curve_groups,
                                               double cover_size);

} // namespace nmm::detail
