// SPDX-License-Identifier: MIT
#include "mesh/state_archive.hpp"

#include "mesh/error.hpp"

#include <cstring>
#include <utility>

namespace nmm {

void StateWriter::raw(const void* data, std::size_t size) {
  if (size > 0) // an empty Eigen vector's data() is null
    bytes_.append(static_cast<const char*>(data), size);
}

void StateWriter::section(std::string_view tag) {
  NMM_ASSERT(tag.size() == 4, "a section tag has four characters");
  bytes_.append(tag);
}

void StateWriter::put(std::int64_t value) { raw(&value, sizeof value); }

void StateWriter::put(double value) { raw(&value, sizeof value); }

void StateWriter::put(bool value) {
  const char c = value ? 1 : 0;
  raw(&c, 1);
}

void StateWriter::put(const Point2& point) {
  put(point.x());
  put(point.y());
}

void StateWriter::put(std::string_view text) {
  put_count(text.size());
  bytes_.append(text);
}

void StateWriter::put(const Eigen::VectorXd& values) {
  put_count(static_cast<std::size_t>(values.size()));
  raw(values.data(), sizeof(double) * static_cast<std::size_t>(values.size()));
}

void StateWriter::put(const Eigen::Matrix3d& values) { raw(values.data(), sizeof(double) * 9); }

void StateWriter::put(const std::vector<int>& values) {
  put_count(values.size());
  for (const int v : values)
    put(static_cast<std::int64_t>(v));
}

void StateWriter::put(const std::vector<Point2>& points) {
  put_count(points.size());
  for (const Point2& p : points)
    put(p);
}

StateReader::StateReader(std::string_view bytes, std::string what)
    : bytes_(bytes), what_(std::move(what)) {}

void StateReader::fail(const std::string& message) const {
  throw InputError(what_ + ": " + message +
                   "; the checkpoint does not belong to this case or is damaged: run the case "
                   "from the start without --restart");
}

void StateReader::raw(void* data, std::size_t size) {
  if (bytes_.size() - position_ < size)
    fail_short();
  if (size == 0)
    return; // an empty Eigen vector's data() is null, which memcpy must not get
  std::memcpy(data, bytes_.data() + position_, size);
  position_ += size;
}

void StateReader::section(std::string_view tag) {
  char found[4] = {};
  raw(found, 4);
  if (std::string_view(found, 4) != tag)
    fail("expected the section \"" + std::string(tag) + "\" at byte " +
         std::to_string(position_ - 4) + ", found \"" + std::string(found, 4) + "\"");
}

std::int64_t StateReader::integer() {
  std::int64_t value = 0;
  raw(&value, sizeof value);
  return value;
}

double StateReader::real() {
  double value = 0.0;
  raw(&value, sizeof value);
  return value;
}

bool StateReader::boolean() {
  char c = 0;
  raw(&c, 1);
  if (c != 0 && c != 1)
    fail("a flag is neither 0 nor 1 at byte " + std::to_string(position_ - 1));
  return c == 1;
}

Point2 StateReader::point() {
  const double x = real();
  return {x, real()};
}

void StateReader::fail_short() const {
  fail("the checkpoint ends early (" + std::to_string(bytes_.size()) + " bytes)");
}

std::size_t StateReader::count_of(std::size_t bytes_each) {
  const std::size_t n = count();
  if (n > (bytes_.size() - position_) / bytes_each)
    fail_short(); // before allocating for them
  return n;
}

std::size_t StateReader::count() {
  const std::int64_t n = integer();
  if (n < 0 || n >= (std::int64_t{1} << 40))
    fail("a count of " + std::to_string(n) + " at byte " + std::to_string(position_ - 8));
  return static_cast<std::size_t>(n);
}

std::string StateReader::text() {
  const std::size_t n = count_of(1);
  std::string text(n, '\0');
  raw(text.data(), n);
  return text;
}

Eigen::VectorXd StateReader::vector() {
  const std::size_t n = count_of(sizeof(double));
  Eigen::VectorXd values(static_cast<Eigen::Index>(n));
  raw(values.data(), sizeof(double) * n);
  return values;
}

Eigen::Matrix3d StateReader::matrix3() {
  Eigen::Matrix3d values;
  raw(values.data(), sizeof(double) * 9);
  return values;
}

std::vector<int> StateReader::integers() {
  const std::size_t n = count_of(sizeof(std::int64_t));
  std::vector<int> values(n);
  for (int& v : values)
    v = static_cast<int>(integer());
  return values;
}

std::vector<Point2> StateReader::points() {
  const std::size_t n = count_of(2 * sizeof(double));
  std::vector<Point2> points(n);
  for (Point2& p : points)
    p = point();
  return points;
}

void StateReader::expect_count(std::size_t expected, std::string_view what) {
  const std::size_t n = count();
  if (n != expected)
    fail("it has " + std::to_string(n) + " " + std::string(what) + ", the case has " +
         std::to_string(expected));
}

void StateReader::points_into(std::vector<Point2>& points, std::string_view what) {
  expect_count(points.size(), what);
  for (Point2& p : points)
    p = point();
}

} // namespace nmm
