#pragma once
// Running the manylight program from a test: its exit code, stderr and stdout. For the
// *_gltest targets, which define MANYLIGHT_BIN.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "tests/test_support.h"

namespace manylight::testing {

namespace fs = std::filesystem;

struct ProcessResult {
  int exitCode;
  std::string err;
  std::string out;
};

inline std::string readFile(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

// Runs the program; its output files live outside the test folder, which some tests count.
inline ProcessResult manylight(const std::string& args) {
  const fs::path errFile = fs::path(testFolder().string() + "-stderr.txt");
  const fs::path outFile = fs::path(testFolder().string() + "-stdout.txt");
  const std::string cmd =
      std::string(MANYLIGHT_BIN) + " " + args + " 2>" + errFile.string() + " >" + outFile.string();
  const int status = std::system(cmd.c_str());
  ProcessResult r{WIFEXITED(status) ? WEXITSTATUS(status) : -1, readFile(errFile),
                  readFile(outFile)};
  fs::remove(errFile);
  fs::remove(outFile);
  return r;
}

inline std::string writeText(const std::string& name, const std::string& text) {
  const fs::path p = testFolder() / name;
  std::ofstream(p) << text;
  return p.string();
}

// Runs `command` with bash (single quotes are not allowed in it); returns its exit code.
inline int shell(const std::string& command) {
  const int status = std::system(("bash -c '" + command + "'").c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// The value after "NAME = " in the fit tool's output.
inline double printed(const std::string& out, const std::string& name) {
  const std::size_t at = out.find("\n" + name + " = ");
  if (at == std::string::npos && out.rfind(name + " = ", 0) != 0) {
    ADD_FAILURE() << "no '" << name << "' in:\n" << out;
    return std::nan("");
  }
  return std::stod(
      out.substr(out.find(name + " = ", at == std::string::npos ? 0 : at) + name.size() + 3));
}

}  // namespace manylight::testing
