// SPDX-License-Identifier: MIT
// io/gmsh_internal.hpp — what the io/gmsh_*.cpp files behind io/gmsh_reader.hpp share.
// Included only from those files: it brings in gmsh's API.
#pragma once

#include "io/gmsh_reader.hpp"
#include "mesh/geometry.hpp"

#include <Eigen/Core>
#include <gmsh.h>

#include <cstddef>
#include <filesystem>
#include <set>
#include <string>
#include <unordered_map>
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

} // namespace nmm::detail
