// SPDX-License-Identifier: MIT
#include "io/dependency_info.hpp"

#include "mesh/dependency_info.hpp"
#include "solver/cholmod_solver.hpp"
#include "solver/threads.hpp"

#include <CLI/Version.hpp>
#include <Eigen/Core>
#include <gmsh.h>
#include <toml++/toml.h>
#include <vtkVersion.h>

#include <sstream>

namespace nmm {

std::string dependency_report() {
  std::ostringstream out;
  out << "  CGAL      " << cgal_version() << '\n'
      << "  " << cholmod_version() << '\n'
      << "  BLAS      " << blas_description() << '\n'
      << "  gmsh      " << GMSH_API_VERSION << '\n'
      << "  VTK       " << vtkVersion::GetVTKVersion() << '\n'
      << "  toml++    " << TOML_LIB_MAJOR << '.' << TOML_LIB_MINOR << '.' << TOML_LIB_PATCH << '\n'
      << "  CLI11     " << CLI11_VERSION << '\n'
      << "  Eigen     " << EIGEN_WORLD_VERSION << '.' << EIGEN_MAJOR_VERSION << '.'
      << EIGEN_MINOR_VERSION << '\n';
  return out.str();
}

} // namespace nmm
