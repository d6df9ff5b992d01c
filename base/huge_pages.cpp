#include "base/huge_pages.h"

#include <sys/auxv.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>

namespace manylight {

namespace {

constexpr const char* kTunable = "glibc.malloc.hugetlb";

// Whether the kernel's transparent huge pages are given only on request ("[madvise]").
bool hugePagesOnRequest() {
  std::ifstream in("/sys/kernel/mm/transparent_hugepage/enabled");
  const std::string mode{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  return mode.find("[madvise]") != std::string::npos;
}

// Whether Valgrind runs us (it preloads its vgpreload libraries): exec would leave it.
bool underValgrind() {
  const char* preload = std::getenv("LD_PRELOAD");
  return preload && std::string(preload).find("vgpreload") != std::string::npos;
}

}  // namespace

void restartWithHugePages(char** argv) {
  const char* own = std::getenv("MANYLIGHT_HUGE_PAGES");
  if (own && std::string(own) == "0") return;
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  const std::string before = tunables ? tunables : "";
  if (before.find(kTunable) != std::string::npos) return;
  if (getauxval(AT_SECURE) != 0 || underValgrind() || !hugePagesOnRequest()) return;
  // Our own path, not /proc/self/exe itself: under a tool that runs the program inside its
  // own process image, that link names the tool.
  char self[4096];
  const ssize_t length = readlink("/proc/self/exe", self, sizeof self - 1);
  if (length <= 0) return;
  self[length] = '\0';
  const std::string after = (before.empty() ? "" : before + ":") + kTunable + "=1";
  if (setenv("GLIBC_TUNABLES", after.c_str(), 1) != 0) return;
  execv(self, argv);
  // exec failed: go on as we are, without the tunable in the environment of children either.
  if (tunables) {
    setenv("GLIBC_TUNABLES", before.c_str(), 1);
  } else {
    unsetenv("GLIBC_TUNABLES");
  }
}

}  // namespace manylight
