// SPDX-License-Identifier: MIT
// tests/support/case_fixtures.hpp — small geometries and case files for the tests of the
// run pipeline, written into a test's temporary folder (the text is next to the tests that
// depend on it, so that a reader sees the whole input).
#pragma once

#include "process.hpp"

#include <filesystem>
#include <string>

namespace nmm::testing {

/// A 2 m x 1 m plate "rock"; curves "base" (y = 0), "right" (x = 2) and "outside" (a line
/// away from the plate); points "anchor" (1, 0.5) inside and "far" (5, 5) outside; a second
/// surface "clay" (x from 2 to 3) only in plate_and_clay.geo.
inline constexpr const char* plate_geo = R"(// 2 m x 1 m plate
Point(1) = {0, 0, 0};
Point(2) = {2, 0, 0};
Point(3) = {2, 1, 0};
Point(4) = {0, 1, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Point(5) = {1, 0.5, 0};
Point(6) = {5, 5, 0};
Point(7) = {3, 3, 0};
Point(8) = {4, 3, 0};
Line(5) = {7, 8};
Physical Surface("rock") = {1};
Physical Curve("base") = {1};
Physical Curve("right") = {2};
Physical Curve("outside") = {5};
Physical Point("anchor") = {5};
Physical Point("far") = {6};
)";

inline constexpr const char* plate_and_clay_geo = R"(// "rock" [0,2]x[0,1] and "clay" [2,3]x[0,1]
Point(1) = {0, 0, 0};
Point(2) = {2, 0, 0};
Point(3) = {2, 1, 0};
Point(4) = {0, 1, 0};
Point(5) = {3, 0, 0};
Point(6) = {3, 1, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Line(5) = {2, 5};
Line(6) = {5, 6};
Line(7) = {6, 3};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Curve Loop(2) = {5, 6, 7, -2};
Plane Surface(2) = {2};
Physical Surface("rock") = {1};
Physical Surface("clay") = {2};
Physical Curve("base") = {1, 5};
)";

/// A static case on plate.geo: base fixed, a traction on the right edge, 3 steps, a monitor
/// at the top right corner, output every 2 steps. Line numbers matter to the tests:
/// [materials.rock] is line 6, [[boundary]] line 10, [[load]] line 13, [[monitor]] line 19.
inline constexpr const char* plate_case = R"(geometry = "plate.geo"
title = "plate"
[cover_mesh]
size = 0.3
order = 0
[materials.rock]
density = 2000.0
young = 1.0e9
poisson = 0.25
[[boundary]]
curve = "base"
fix = "xy"
[[load]]
curve = "right"
traction = [1.0e5, 0.0]
[analysis]
kind = "static"
steps = 3
[[monitor]]
name = "corner"
point = [2.0, 1.0]
[output]
dir = "out"
every = 2
)";

/// plate.geo with a joint "cut" that cuts a corner of 1 cm x 1 cm (5e-5 m²) off the plate at
/// (2, 0), where the curves "base" and "right" meet: at plate_case's cover size 0.3 m every
/// cover of that piece is below 1e-3 of its star (a block too small for the cover mesh).
inline std::string corner_geo() {
  return std::string(plate_geo) + "Point(9) = {1.98, -0.01, 0};\nPoint(10) = {2.01, 0.02, 0};\n"
                                  "Line(6) = {9, 10};\nPhysical Curve(\"cut\") = {6};\n";
}

/// Writes plate.geo, plate_and_clay.geo and case.toml (@p case_text) into @p dir; returns
/// the case file.
inline std::filesystem::path write_case(const std::filesystem::path& dir,
                                        const std::string& case_text) {
  write_text(dir / "plate.geo", plate_geo);
  write_text(dir / "plate_and_clay.geo", plate_and_clay_geo);
  write_text(dir / "case.toml", case_text);
  return dir / "case.toml";
}

/// @p text with the first @p from replaced by @p to (the test fails when @p from is absent).
inline std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << "fixture has no \"" << from << "\"";
  if (at != std::string::npos)
    text.replace(at, from.size(), to);
  return text;
}

} // namespace nmm::testing
