// SPDX-License-Identifier: MIT
#include "io/atomic_file.hpp"

#include "io/text.hpp"
#include "mesh/error.hpp"

#include <sys/resource.h>
#include <sys/statvfs.h>

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

/// True when the file system holding @p directory has no block left for an ordinary user.
bool is_full(const fs::path& directory) {
  struct statvfs info {};
  return ::statvfs(directory.c_str(), &info) == 0 && info.f_bavail == 0;
}

} // namespace

std::string write_failure_message(const fs::path& file,
                                  int error,
                                  const std::string& what,
                                  const std::string& writer_reason) {
  const fs::path directory = file.has_parent_path() ? file.parent_path() : fs::path(".");
  const std::string reason =
      error != 0 ? " (" + std::generic_category().message(error) + ")" : std::string();
  const std::string target = what.empty() ? quoted(file) : what + " to " + quoted(file);
  if (error == ENOSPC || error == EDQUOT || (error != EFBIG && is_full(directory)))
    return "disk full: cannot write " + target + reason + "; free space on the disk of " +
           quoted(directory) +
           " or choose another output folder with -o DIR, then run the case again";
  if (error == EFBIG) {
    struct rlimit limit {};
    std::string size;
    if (::getrlimit(RLIMIT_FSIZE, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY)
      size = " of " + std::to_string(limit.rlim_cur) + " bytes";
    return "file too large: cannot write " + target + reason +
           ": it reached this process's file-size limit" + size +
           " (ulimit -f); raise the limit (ulimit -f unlimited) or write smaller files (a "
           "larger [output] every, fewer steps)";
  }
  return "cannot write " + target + ": " +
         (error != 0               ? std::generic_category().message(error)
          : !writer_reason.empty() ? writer_reason
                                   : std::string("the writer gave no reason")) +
         "; check the output folder " + quoted(directory) + " and its free space";
}

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
      const int reason = errno;
      if (reason == ENOSPC || reason == EDQUOT || reason == EFBIG)
        throw OutputWriteError(write_failure_message(file, reason));
      throw InputError("cannot write " + quoted(file) + " in directory " + quoted(directory) +
                       ": " + std::generic_category().message(reason) +
                       "; make the directory writable or choose another output directory");
    }
  }
  bool written = false;
  errno = 0;
  try {
    written = write_to(tmp);
  } catch (...) {
    fs::remove(tmp, error);
    throw;
  }
  if (!written) {
    // The writer's last failed call set errno (VTK and iostreams keep no reason of their own).
    const int reason = errno;
    fs::remove(tmp, error);
    throw OutputWriteError(write_failure_message(file, reason));
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
