// For huge_pages_test.cpp: runs restartWithHugePages as main does, then prints GLIBC_TUNABLES
// as the program (run again or not) sees it, or "(unset)".
#include <cstdio>
#include <cstdlib>

#include "base/huge_pages.h"

int main(int, char** argv) {
  manylight::restartWithHugePages(argv);
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  std::printf("%s\n", tunables ? tunables : "(unset)");
  return 0;
}
