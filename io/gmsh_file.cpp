// SPDX-License-Identifier: MIT
// Checking a geometry file (.geo or .msh) and opening it as gmsh's current model.
#include "io/gmsh_internal.hpp"
#include "mesh/error.hpp"

#include <gmsh.h>

#include <algorithm>
#include <cctype>
#include <fstream>
#include <regex>
#include <string>
#include <system_error>

namespace nmm::detail {

namespace {

/// gmsh 4.8 runs a .geo's `Exit;` as exit(0) of the whole process, which would end nmm
/// silently with success. Refuse such files before gmsh sees them (files they Include are not
/// checked).
void check_no_exit_command(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::string line;
  bool in_block_comment = false;
  static const std::regex exit_command(R"((^|[^A-Za-z0-9_])Exit\s*;)");
  for (int number = 1; std::getline(in, line); ++number) {
    std::string code;
    for (std::size_t i = 0; i < line.size(); ++i) {
      if (in_block_comment) {
        if (line.compare(i, 2, "*/") == 0) {
          in_block_comment = false;
          ++i;
        }
      } else if (line.compare(i, 2, "/*") == 0) {
        in_block_comment = true;
        ++i;
      } else if (line.compare(i, 2, "//") == 0) {
        break;
      } else {
        code += line[i];
      }
    }
    if (std::regex_search(code, exit_command)) {
      throw InputError(file.string(), number, 0,
                       "the .geo file calls Exit, which would end nmm as well as gmsh; remove "
                       "this line (nmm reads the geometry without running gmsh's batch steps)");
    }
  }
}

} // namespace

GmshFileKind check_geometry_file(const std::filesystem::path& file) {
  const std::string name = file.string();
  std::error_code error;
  const auto status = std::filesystem::status(file, error);
  if (!std::filesystem::exists(status)) {
    throw InputError(name + ": geometry file not found (looked for " +
                     std::filesystem::absolute(file, error).string() +
                     "); check the file name and the directory it is given relative to");
  }
  if (!std::filesystem::is_regular_file(status)) {
    throw InputError(name + ": not a regular file (a directory?); give a gmsh .geo or .msh "
                            "file");
  }
  std::string extension = file.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (extension != ".geo" && extension != ".msh") {
    throw InputError(name + ": unknown geometry file type \"" + extension +
                     "\"; give a gmsh .geo file (built-in or OpenCASCADE kernel) or a .msh "
                     "file (format 2 or 4)");
  }
  if (!std::ifstream(file)) {
    throw InputError(name + ": the file exists but cannot be read; check its permissions");
  }
  return extension == ".geo" ? GmshFileKind::geo : GmshFileKind::msh;
}

void open_model(const std::filesystem::path& file,
                GmshFileKind kind,
                const GeometryReadOptions& options) {
  const std::string name = file.string();
  if (kind == GmshFileKind::geo) {
    check_no_exit_command(file);
    read_within_limits(file, options);
  }
  run_gmsh(name, "read the file", [&] {
    gmsh::clear();
    gmsh::open(name);
  });
}

} // namespace nmm::detail
