// Runs a shell command for the tests of the command line and the report tools: its exit status
// and what it wrote to stdout (redirect stderr in the command to capture it too).
#pragma once

#include <sys/wait.h>

#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <string>

namespace rktsph::test {

struct ShellResult {
  int status;  ///< exit status, -1 if the command could not run or did not exit
  std::string output;
};

inline ShellResult shell(const std::string& command) {
  FILE* pipe = popen(command.c_str(), "r");
  std::string output;
  std::array<char, 4096> buffer;
  while (pipe && fgets(buffer.data(), buffer.size(), pipe))
    output += buffer.data();
  const int raw = pipe ? pclose(pipe) : -1;
  return {WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, output};
}

#ifdef RKTSPH_BINARY
/// The rktsph program with these arguments; output is its stdout and stderr.
inline ShellResult run_rktsph(const std::string& arguments) {
  return shell(std::string(RKTSPH_BINARY) + " " + arguments + " 2>&1");
}
#endif

/// `name` in a scratch folder of this test process (<tmp>/<prefix>_<pid>/, created).
inline std::filesystem::path scratch_file(const std::string& prefix, const std::string& name) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / (prefix + "_" + std::to_string(getpid()));
  std::filesystem::create_directories(dir);
  return dir / name;
}

}  // namespace rktsph::test
