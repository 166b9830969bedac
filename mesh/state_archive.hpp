// SPDX-License-Identifier: MIT
// mesh/state_archive.hpp — the byte stream of a restart checkpoint: each module writes the
// state it carries from step to step (model geometry and stresses, contact states, the
// stepper's velocities and counters) and reads it back bit for bit. Reals are stored as
// their 8 bytes, so a restarted run continues from exactly the numbers the interrupted one
// had. Sections start with a four-letter tag and every count read is checked against the
// model being restored, so a checkpoint of another model is refused, never half applied.
#pragma once

#include "mesh/geometry.hpp"

#include <Eigen/Core>

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace nmm {

/// Appends values to a byte string (little-endian as the machine writes it: a checkpoint is
/// for restarting on the machine kind that wrote it; the header records the byte order).
class StateWriter {
public:
  /// A section tag: four characters, checked by StateReader::section().
  void section(std::string_view tag);
  void put(std::int64_t value);
  void put(double value);
  void put(bool value);
  void put(const Point2& point);
  void put(std::string_view text);
  void put(const Eigen::VectorXd& values);
  void put(const Eigen::Matrix3d& values);
  void put(const std::vector<int>& values);
  void put(const std::vector<Point2>& points);
  /// A count, read back by StateReader::count().
  void put_count(std::size_t n) { put(static_cast<std::int64_t>(n)); }

  [[nodiscard]] const std::string& bytes() const noexcept { return bytes_; }

private:
  void raw(const void* data, std::size_t size);
  std::string bytes_;
};

/// Reads what a StateWriter wrote, in the same order.
/// Every read past the end, a wrong section tag or a count that does not match throws
/// InputError("<what>: ..."), with @p what naming the checkpoint file.
class StateReader {
public:
  StateReader(std::string_view bytes, std::string what);

  /// Reads a section tag and checks it is @p tag.
  void section(std::string_view tag);
  std::int64_t integer();
  double real();
  bool boolean();
  Point2 point();
  std::string text();
  Eigen::VectorXd vector();
  Eigen::Matrix3d matrix3();
  std::vector<int> integers();
  std::vector<Point2> points();
  /// A count in [0, 2^40).
  std::size_t count();
  /// A count that must equal @p expected; @p what names it in the message ("elements").
  void expect_count(std::size_t expected, std::string_view what);
  /// Points read into @p points, whose size must equal the stored count.
  void points_into(std::vector<Point2>& points, std::string_view what);

  [[nodiscard]] bool at_end() const noexcept { return position_ == bytes_.size(); }
  /// Throws InputError("<what>: " + message + ...).
  [[noreturn]] void fail(const std::string& message) const;

private:
  void raw(void* data, std::size_t size);
  /// A count of items of @p bytes_each bytes that the rest of the stream must hold.
  std::size_t count_of(std::size_t bytes_each);
  [[noreturn]] void fail_short() const;
  std::string_view bytes_;
  std::size_t position_ = 0;
  std::string what_;
};

} // namespace nmm
