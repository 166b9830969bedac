// SPDX-License-Identifier: MIT
// The one source of nmm_test_pch (tests/CMakeLists.txt): CMake builds the precompiled header
// of support/precompiled.hpp with it, and every test executable reuses that header.
