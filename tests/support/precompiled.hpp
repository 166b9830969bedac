// SPDX-License-Identifier: MIT
// tests/support/precompiled.hpp — the headers every test executable parses, compiled once
// for all of them (tests/CMakeLists.txt, target nmm_test_pch): googletest, Eigen's dense and
// sparse cores and the standard library the tests use. Parsing them took more than half of
// each test source's compile time (GCC's -ftime-report: 10.1 of 17.3 s for
// verification/joint_strength_test.cpp, whose preprocessed text is 180k lines). Only
// third-party headers: a change to one of ours must not rebuild every test.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <Eigen/SparseCore>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <numbers>
#include <optional>
#include <random>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>
