// SPDX-License-Identifier: MIT
// The checkpoint byte stream: every value back bit for bit, and every way a stream can be
// wrong (cut short, another section, a count the model does not have) an InputError.
#include "mesh/error.hpp"
#include "mesh/state_archive.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <vector>

namespace nmm {
namespace {

TEST(StateArchive, EveryValueReadsBackBitForBit) {
  StateWriter out;
  out.section("TEST");
  out.put(std::int64_t{-42});
  const double awkward = std::nextafter(0.1, 1.0); // not a short decimal
  out.put(awkward);
  out.put(std::numeric_limits<double>::denorm_min());
  out.put(true);
  out.put(Point2(1.0 / 3.0, -2.5e-300));
  out.put(std::string_view("a text, with\nnewline"));
  Eigen::VectorXd v(3);
  v << 1.0, -0.0, 1e300;
  out.put(v);
  out.put(Eigen::VectorXd()); // empty: a block without a carried force
  Eigen::Matrix3d m = Eigen::Matrix3d::Random();
  out.put(m);
  out.put(std::vector<int>{3, -1, 7});
  out.put(std::vector<Point2>{Point2(1, 2), Point2(3, 4)});

  StateReader in(out.bytes(), "test");
  in.section("TEST");
  EXPECT_EQ(in.integer(), -42);
  EXPECT_EQ(in.real(), awkward);
  EXPECT_EQ(in.real(), std::numeric_limits<double>::denorm_min());
  EXPECT_TRUE(in.boolean());
  const Point2 p = in.point();
  EXPECT_EQ(p.x(), 1.0 / 3.0);
  EXPECT_EQ(p.y(), -2.5e-300);
  EXPECT_EQ(in.text(), "a text, with\nnewline");
  const Eigen::VectorXd w = in.vector();
  ASSERT_EQ(w.size(), 3);
  EXPECT_EQ(w(1), 0.0);
  EXPECT_TRUE(std::signbit(w(1))) << "-0 stays -0";
  EXPECT_EQ(w(2), 1e300);
  EXPECT_EQ(in.vector().size(), 0);
  EXPECT_EQ(in.matrix3(), m);
  EXPECT_EQ(in.integers(), (std::vector<int>{3, -1, 7}));
  std::vector<Point2> points(2);
  in.points_into(points, "points");
  EXPECT_EQ(points[1], Point2(3, 4));
  EXPECT_TRUE(in.at_end());
}

std::string error_of(const std::function<void()>& read) {
  try {
    read();
  } catch (const InputError& error) {
    return error.what();
  }
  ADD_FAILURE() << "no InputError";
  return {};
}

TEST(StateArchive, AStreamCutShortAWrongSectionOrAnotherCountIsAnInputError) {
  StateWriter out;
  out.section("MODL");
  out.put(std::vector<Point2>{Point2(1, 2), Point2(3, 4)});
  const std::string bytes = out.bytes();

  EXPECT_NE(error_of([&] {
              StateReader in(std::string_view(bytes).substr(0, bytes.size() - 3), "ck.nmm");
              in.section("MODL");
              static_cast<void>(in.points());
            }).find("ck.nmm: the checkpoint ends early"),
            std::string::npos);
  EXPECT_NE(error_of([&] {
              StateReader in(bytes, "ck.nmm");
              in.section("CONT");
            }).find("expected the section \"CONT\" at byte 0, found \"MODL\""),
            std::string::npos);
  EXPECT_NE(error_of([&] {
              StateReader in(bytes, "ck.nmm");
              in.section("MODL");
              std::vector<Point2> three(3);
              in.points_into(three, "loop vertices");
            }).find("it has 2 loop vertices, the case has 3"),
            std::string::npos);
  // A count that would make a huge allocation is refused before it is made.
  StateWriter huge;
  huge.put(std::int64_t{1} << 50);
  EXPECT_NE(error_of([&] {
              StateReader in(huge.bytes(), "ck.nmm");
              static_cast<void>(in.vector());
            }).find("a count of"),
            std::string::npos);
}

} // namespace
} // namespace nmm
