// SPDX-License-Identifier: MIT
// io/atomic_file.hpp — files replaced whole: a reader sees the old file or the new one.
#pragma once

#include <filesystem>
#include <functional>

namespace nmm {

/// Writes @p file through @p write_to(temporary path), which returns whether it wrote
/// everything, and renames the temporary file into place, so a reader (ParaView, a script
/// following summary.json) sees either the old file or the complete new one, never a
/// partial file. @throws InputError naming the file and what to do when the directory is
/// missing or not writable, the writing fails part way, or the file cannot be replaced.
void write_file_atomically(const std::filesystem::path& file,
                           const std::function<bool(const std::filesystem::path&)>& write_to);

} // namespace nmm
