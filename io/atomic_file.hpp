// SPDX-License-Identifier: MIT
// io/atomic_file.hpp — files replaced whole: a reader sees the old file or the new one; and
// the error of an output file that cannot be written (disk full, file-size limit).
#pragma once

#include "mesh/error.hpp"

#include <filesystem>
#include <functional>
#include <string>

namespace nmm {

/// An output file could not be written: the disk is full, the process's file-size limit
/// (`ulimit -f`) is reached, or the system refused the write. An InputError (the exit code
/// is the one of a folder that cannot be written); a run that stops by it says
/// "failed: " and the message in summary.json's status.
class OutputWriteError : public InputError {
public:
  explicit OutputWriteError(const std::string& message) : InputError(message) {}
};

/// The message for a failed write of @p file with errno @p error: "disk full: cannot write
/// 'FILE' (reason); what to do" for ENOSPC and EDQUOT, "file too large: ..." with the limit
/// for EFBIG (SIGXFSZ is ignored by `nmm`, so a file-size limit makes writes fail with it),
/// else "cannot write 'FILE': reason; ...". When @p error is 0 or another code the file
/// system is examined: a disk with no free block left is reported as full. @p what, when
/// given, says what was written: "cannot write WHAT to 'FILE'". @p writer_reason, when given,
/// is the writer's own account, said when errno gives none ("cannot write 'FILE': REASON").
[[nodiscard]] std::string write_failure_message(const std::filesystem::path& file,
                                                int error,
                                                const std::string& what = {},
                                                const std::string& writer_reason = {});

/// Writes @p file through @p write_to(temporary path), which returns whether it wrote
/// everything, and renames the temporary file into place, so a reader (ParaView, a script
/// following summary.json) sees either the old file or the complete new one, never a
/// partial file. @throws InputError naming the file and what to do when the directory is
/// missing or not writable or the file cannot be replaced; OutputWriteError when the
/// writing fails part way.
void write_file_atomically(const std::filesystem::path& file,
                           const std::function<bool(const std::filesystem::path&)>& write_to);

} // namespace nmm
