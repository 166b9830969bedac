// SPDX-License-Identifier: MIT
// io/row_file.hpp — a text file of rows under a header line (history.csv, blocks.csv), written
// so that a run that stops at any moment leaves it readable and a restart continues it.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

namespace nmm {

/// A file of rows under a header, each append one write(2) (no buffer), so that a run that
/// stops at any moment leaves every completed row on disk; an append that the disk or a
/// file-size limit cuts short is taken back, so the file always ends with a whole row.
class RowFile {
public:
  /// Creates (truncates) @p file and writes @p header (with its newline), or, with
  /// @p header_with_first_rows, leaves the file empty and writes the header in the same write
  /// as the first append (a file of outputs that come later takes no disk space before).
  /// @throws InputError naming the file when it cannot be written.
  RowFile(std::filesystem::path file,
          const std::string& header,
          bool header_with_first_rows = false);
  /// Continues @p file after a restart: keeps its first @p keep_bytes bytes (the header and
  /// the rows up to the checkpoint's step), drops the rest and appends after them.
  /// @param header_meaning  what a differing header means, for the message ("that of the
  ///                        case's monitors").
  /// @throws InputError naming the file when it is missing, shorter than @p keep_bytes, does
  ///         not end a row there, or does not start with @p header.
  RowFile(std::filesystem::path file,
          const std::string& header,
          const std::string& header_meaning,
          std::uintmax_t keep_bytes);
  ~RowFile();
  RowFile(const RowFile&) = delete;
  RowFile& operator=(const RowFile&) = delete;
  RowFile(RowFile&&) = delete;
  RowFile& operator=(RowFile&&) = delete;

  /// Writes @p rows at the end (after the header when it waits for them), whole, or truncates
  /// the file back to bytes() and throws OutputWriteError naming the file and the reason
  /// (@p what names the text).
  void append(const std::string& rows, const std::string& what);

  [[nodiscard]] const std::filesystem::path& file() const noexcept { return file_; }
  /// Size of the file so far: header and every row written, bytes.
  [[nodiscard]] std::uintmax_t bytes() const noexcept { return bytes_; }

private:
  std::filesystem::path file_;
  std::uintmax_t bytes_ = 0;
  int descriptor_ = -1;
  std::string pending_header_; ///< written with the first append
};

} // namespace nmm
