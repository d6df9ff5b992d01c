// restartWithHugePages (base/huge_pages.h), through tests/huge_pages_probe.cpp: which
// GLIBC_TUNABLES the program ends up with, run from a shell with a given environment.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <iterator>
#include <string>

namespace {

// The probe's line, run with `env` (assignments and -u NAME for `env`).
std::string probe(const std::string& env) {
  const std::string command =
      "env -u GLIBC_TUNABLES -u MANYLIGHT_HUGE_PAGES " + env + " " + MANYLIGHT_PROBE_BIN;
  FILE* out = popen(command.c_str(), "r");
  if (!out) return "(popen failed)";
  char line[256] = {};
  const bool read = std::fgets(line, sizeof line, out) != nullptr;
  pclose(out);
  std::string s = read ? line : "(no output)";
  if (!s.empty() && s.back() == '\n') s.pop_back();
  return s;
}

bool onRequest() {
  std::ifstream in("/sys/kernel/mm/transparent_hugepage/enabled");
  const std::string mode{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  return mode.find("[madvise]") != std::string::npos;
}

}  // namespace

// Where the kernel gives huge pages on request, the program runs again once with the tunable
// added to those set before; else, and where it is set already or turned off, nothing changes.
TEST(HugePages, TheProgramRunsAgainOnceWithTheTunable) {
  const bool again = onRequest();
  EXPECT_EQ(probe(""), again ? "glibc.malloc.hugetlb=1" : "(unset)");
  EXPECT_EQ(probe("GLIBC_TUNABLES=glibc.malloc.check=0"),
            again ? "glibc.malloc.check=0:glibc.malloc.hugetlb=1" : "glibc.malloc.check=0");
  EXPECT_EQ(probe("GLIBC_TUNABLES=glibc.malloc.hugetlb=0"), "glibc.malloc.hugetlb=0");
  EXPECT_EQ(probe("MANYLIGHT_HUGE_PAGES=0"), "(unset)");
}
