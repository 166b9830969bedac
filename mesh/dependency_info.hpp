// SPDX-License-Identifier: MIT
// mesh/dependency_info.hpp — versions of the libraries mesh/ hides behind its .cpp files.
#pragma once

#include <string>

namespace nmm {

/// The CGAL version compiled into mesh/, e.g. "5.5.1".
[[nodiscard]] std::string cgal_version();

} // namespace nmm
