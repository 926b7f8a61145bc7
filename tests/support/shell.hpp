// Runs a shell command for the tests of the command line and the report tools: its exit status
// and what it wrote to stdout (redirect stderr in the command to capture it too).
#pragma once

#include <sys/wait.h>

#include <array>
#include <cstdio>
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

}  // namespace rktsph::test
