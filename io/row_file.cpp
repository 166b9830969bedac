// SPDX-License-Identifier: MIT
#include "io/row_file.hpp"

#include "io/atomic_file.hpp"
#include "mesh/error.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <string_view>
#include <system_error>

namespace nmm {

namespace {

std::string system_reason(int error) { return std::generic_category().message(error); }

} // namespace

RowFile::RowFile(std::filesystem::path file, const std::string& header, bool header_with_first_rows)
    : file_(std::move(file)) {
  descriptor_ = ::open(file_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_APPEND | O_CLOEXEC, 0644);
  if (descriptor_ < 0) {
    throw InputError("cannot write " + file_.string() + ": " + system_reason(errno) +
                     "; choose a writable output folder with -o DIR or [output] dir");
  }
  if (header_with_first_rows) {
    pending_header_ = header;
    return;
  }
  try {
    append(header, "its header");
  } catch (...) {
    static_cast<void>(::close(descriptor_)); // no destructor runs for a failed constructor
    throw;
  }
}

RowFile::RowFile(std::filesystem::path file,
                 const std::string& header,
                 const std::string& header_meaning,
                 std::uintmax_t keep_bytes)
    : file_(std::move(file)), bytes_(keep_bytes) {
  const auto fail = [&](const std::string& what) {
    throw InputError("cannot continue " + file_.string() + " after the checkpoint: " + what +
                     "; run the case from the start without --restart");
  };
  std::error_code error;
  const std::uintmax_t size = std::filesystem::file_size(file_, error);
  if (error)
    fail(error.message());
  if (size < keep_bytes || keep_bytes < header.size())
    fail("it has " + std::to_string(size) + " bytes, the checkpoint's step ends at byte " +
         std::to_string(keep_bytes));
  {
    std::FILE* in = std::fopen(file_.c_str(), "rb");
    if (in == nullptr)
      fail(system_reason(errno));
    std::string head(header.size(), '\0');
    const bool read = std::fread(head.data(), 1, head.size(), in) == head.size();
    char last = 0;
    const bool end = std::fseek(in, static_cast<long>(keep_bytes) - 1, SEEK_SET) == 0 &&
                     std::fread(&last, 1, 1, in) == 1;
    static_cast<void>(std::fclose(in));
    if (!read || head != header)
      fail("its header is not " + header_meaning);
    if (!end || last != '\n')
      fail("no row ends at byte " + std::to_string(keep_bytes));
  }
  std::filesystem::resize_file(file_, keep_bytes, error);
  if (error)
    fail(error.message());
  descriptor_ = ::open(file_.c_str(), O_WRONLY | O_APPEND | O_CLOEXEC);
  if (descriptor_ < 0)
    fail(system_reason(errno));
}

RowFile::~RowFile() {
  if (descriptor_ >= 0)
    static_cast<void>(::close(descriptor_));
}

void RowFile::append(const std::string& rows, const std::string& what) {
  if (!pending_header_.empty()) {
    const std::string header = std::move(pending_header_);
    pending_header_.clear();
    try {
      append(header + rows, what);
    } catch (...) {
      pending_header_ = header; // the file is empty again
      throw;
    }
    return;
  }
  const std::string& text = rows;
  // One write(2) puts the text on disk (no buffer to flush); a write cut short by a full
  // disk or a file-size limit is taken back, so the file always ends with a whole row.
  std::string_view rest = text;
  while (!rest.empty()) {
    const ssize_t written = ::write(descriptor_, rest.data(), rest.size());
    if (written < 0 && errno == EINTR)
      continue;
    if (written <= 0) {
      const int error = written < 0 ? errno : ENOSPC;
      if (::ftruncate(descriptor_, static_cast<off_t>(bytes_)) != 0) {
        // The row stays cut; the message below is still the one to give.
      }
      throw OutputWriteError(write_failure_message(file_, error, what));
    }
    rest.remove_prefix(static_cast<std::size_t>(written));
  }
  bytes_ += text.size();
}

} // namespace nmm
