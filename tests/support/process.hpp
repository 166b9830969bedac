// SPDX-License-Identifier: MIT
// tests/support/process.hpp — run the `nmm` program as a child process (fork + execv) with
// its output captured, for end-to-end tests of the command line; and a temporary folder.
#pragma once

#include "temp_dir.hpp"
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

namespace nmm::testing {

namespace fs = std::filesystem;

inline std::string read_text(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

inline void write_text(const fs::path& file, const std::string& text) {
  std::ofstream out(file, std::ios::binary);
  out << text;
}

/// A started child process; its stdout and stderr go to files.
struct ChildProcess {
  pid_t pid = -1;
  fs::path out_file;
  fs::path err_file;
};

/// Starts @p args[0] with arguments @p args in folder @p cwd (the current one when empty).
inline ChildProcess start_process(const std::vector<std::string>& args,
                                  const fs::path& output_prefix,
                                  const fs::path& cwd = {}) {
  ChildProcess child;
  child.out_file = output_prefix.string() + ".stdout";
  child.err_file = output_prefix.string() + ".stderr";
  // Everything the child needs is prepared before fork: after it, only async-signal-safe
  // calls (open, dup2, chdir, execv).
  std::vector<std::string> storage = args;
  std::vector<char*> argv;
  for (std::string& a : storage)
    argv.push_back(a.data());
  argv.push_back(nullptr);
  const std::string out = child.out_file.string();
  const std::string err = child.err_file.string();
  const std::string dir = cwd.string();
  child.pid = ::fork();
  if (child.pid == 0) {
    const int out_fd = ::open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int err_fd = ::open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (out_fd < 0 || err_fd < 0 || ::dup2(out_fd, STDOUT_FILENO) < 0 ||
        ::dup2(err_fd, STDERR_FILENO) < 0 || (!dir.empty() && ::chdir(dir.c_str()) != 0))
      ::_exit(127);
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
  return child;
}

/// Waits for @p child; returns its exit code, or 128 + the signal that killed it, or -1
/// (after killing it) when it takes longer than @p timeout.
inline int wait_process(const ChildProcess& child,
                        std::chrono::seconds timeout = std::chrono::seconds(300)) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  for (;;) {
    int status = 0;
    const pid_t done = ::waitpid(child.pid, &status, WNOHANG);
    if (done == child.pid) {
      if (WIFEXITED(status))
        return WEXITSTATUS(status);
      if (WIFSIGNALED(status))
        return 128 + WTERMSIG(status);
      return -1;
    }
    if (done < 0)
      return -1;
    if (std::chrono::steady_clock::now() > deadline) {
      ::kill(child.pid, SIGKILL);
      ::waitpid(child.pid, &status, 0);
      return -1;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
}

/// The outcome of a finished process.
struct ProcessResult {
  int exit_code = -1;
  std::string out;
  std::string err;
};

/// Runs @p args to completion (see start_process()).
inline ProcessResult run_process(const std::vector<std::string>& args,
                                 const fs::path& output_prefix,
                                 const fs::path& cwd = {}) {
  const ChildProcess child = start_process(args, output_prefix, cwd);
  ProcessResult result;
  result.exit_code = wait_process(child);
  result.out = read_text(child.out_file);
  result.err = read_text(child.err_file);
  return result;
}

/// A test fixture that runs the `nmm` program at @p program, each run's stdout and stderr
/// kept in files of the test's temporary folder (also the place for its inputs).
class NmmTest : public ::testing::Test {
protected:
  NmmTest(fs::path program, const std::string& prefix)
      : program_(std::move(program)), dir_(prefix) {}
  /// Runs nmm with @p args in folder @p cwd (the current one when empty).
  ProcessResult nmm(const std::vector<std::string>& args, const fs::path& cwd = {}) {
    std::vector<std::string> argv{program_.string()};
    argv.insert(argv.end(), args.begin(), args.end());
    return run_process(argv, dir_.path() / ("nmm_" + std::to_string(++calls_)), cwd);
  }
  [[nodiscard]] const fs::path& dir() const { return dir_.path(); }

private:
  fs::path program_;
  TempDir dir_;
  int calls_ = 0;
};

} // namespace nmm::testing
