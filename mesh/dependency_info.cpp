// SPDX-License-Identifier: MIT
#include "mesh/dependency_info.hpp"

#include <CGAL/version_macros.h>

namespace nmm {

std::string cgal_version() { return CGAL_VERSION_STR; }

} // namespace nmm
