// SPDX-License-Identifier: MIT
#include "io/atomic_file.hpp"

#include "io/text.hpp"
#include "mesh/error.hpp"

#include <cerrno>
#include <fstream>
#include <string>
#include <system_error>

namespace nmm {

namespace fs = std::filesystem;

namespace {

fs::path temporary_path(const fs::path& file) {
  fs::path tmp = file;
  tmp += ".tmp";
  return tmp;
}

} // namespace

void write_file_atomically(const fs::path& file,
                           const std::function<bool(const fs::path&)>& write_to) {
  const fs::path directory = file.has_parent_path() ? file.parent_path() : fs::path(".");
  std::error_code error;
  const fs::file_status status = fs::status(directory, error);
  if (!fs::exists(status))
    throw InputError("cannot write " + quoted(file) + ": the directory " + quoted(directory) +
                     " does not exist; create it or choose another output directory");
  if (!fs::is_directory(status))
    throw InputError("cannot write " + quoted(file) + ": " + quoted(directory) +
                     " is not a directory; choose another output directory");
  const fs::path tmp = temporary_path(file);
  {
    // Probe first: VTK would report the failure on stderr in its own words only.
    std::ofstream probe(tmp, std::ios::binary | std::ios::trunc);
    if (!probe) {
      const std::string reason = std::error_code(errno, std::generic_category()).message();
      throw InputError("cannot write " + quoted(file) + " in directory " + quoted(directory) +
                       ": " + reason +
                       "; make the directory writable or choose another output directory");
    }
  }
  bool written = false;
  try {
    written = write_to(tmp);
  } catch (...) {
    fs::remove(tmp, error);
    throw;
  }
  if (!written) {
    fs::remove(tmp, error);
    throw InputError("writing " + quoted(file) +
                     " failed part way; check the free space of the output directory " +
                     quoted(directory));
  }
  fs::rename(tmp, file, error);
  if (error) {
    const std::string reason = error.message();
    fs::remove(tmp, error);
    throw InputError("cannot replace " + quoted(file) + ": " + reason +
                     "; remove it or choose another output directory");
  }
}

} // namespace nmm
