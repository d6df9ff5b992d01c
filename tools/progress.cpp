#include "tools/progress.h"

#include <unistd.h>

#include <cstdio>

namespace manylight {

Progress::Progress(int total) : total_(total), terminal_(::isatty(STDERR_FILENO) == 1) {}

void Progress::step(const std::string& what) {
  ++done_;
  if (!terminal_) return;
  constexpr int kWidth = 30;
  const int filled = total_ > 0 ? kWidth * (done_ - 1) / total_ : 0;
  std::string bar(std::size_t(filled), '#');
  bar.resize(kWidth, '.');
  // Only the end of a long name fits the line.
  const std::string name = what.size() > 40 ? "..." + what.substr(what.size() - 37) : what;
  if (total_ > 0) {
    std::fprintf(stderr, "\r\033[K[%s] %d/%d %s", bar.c_str(), done_, total_, name.c_str());
  } else {  // an unknown total: a count
    std::fprintf(stderr, "\r\033[K%d %s", done_, name.c_str());
  }
  std::fflush(stderr);
  drawn_ = true;
}

void Progress::clear() {
  if (!drawn_) return;
  std::fprintf(stderr, "\r\033[K");
  std::fflush(stderr);
  drawn_ = false;
}

}  // namespace manylight
