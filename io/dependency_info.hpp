// SPDX-License-Identifier: MIT
// io/dependency_info.hpp — one line per library nmm was built with, for `nmm --version`.
#pragma once

#include <string>

namespace nmm {

/// Multi-line report: nmm, CGAL, CHOLMOD, BLAS, gmsh, VTK, toml++, CLI11, Eigen versions.
[[nodiscard]] std::string dependency_report();

} // namespace nmm
