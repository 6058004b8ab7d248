// Runs the bssrdf binary from tests and captures its exit status, stdout and stderr.
#pragma once

#include <sys/wait.h>
#include <unistd.h>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace bssrdf::test_cli {

struct Run {
  int status;
  std::string out, err;
};

inline std::string slurp(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// This process's scratch directory, removed with everything in it when the process exits (ctest
// runs every test case in a process of its own, so cases never share or leak files).
struct ScratchDirectory {
  std::filesystem::path path = std::filesystem::temp_directory_path() / ("bssrdf-test-" + std::to_string(::getpid()));
  ScratchDirectory() { std::filesystem::create_directories(path); }
  ~ScratchDirectory() {
    std::error_code ignored;
    std::filesystem::remove_all(path, ignored);
  }
};
inline const std::filesystem::path& scratch() {
  static const ScratchDirectory directory;
  return directory.path;
}

// `arguments` is appended to the binary's path as shell words.
inline Run run(const std::string& arguments) {
  static int counter = 0;
  const auto out = scratch() / ("cli-out" + std::to_string(counter));
  const auto err = scratch() / ("cli-err" + std::to_string(counter++));
  const std::string command =
      std::string(BSSRDF_CLI) + " " + arguments + " >" + out.string() + " 2>" + err.string() + " </dev/null";
  const int raw = std::system(command.c_str());
  return {WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, slurp(out), slurp(err)};
}

// A path in this process's scratch directory.
inline std::filesystem::path temp(const std::string& name) { return scratch() / name; }

inline int count_lines(const std::string& text) {
  int n = 0;
  for (char c : text) n += c == '\n';
  return n;
}

}  // namespace bssrdf::test_cli
