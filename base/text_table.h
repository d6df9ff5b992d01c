#pragma once
// Small text inputs given on the command line (light lists, fit pairs): read whole, split
// into numbered lines and comma-separated fields, numbers parsed strictly. Callers turn a
// problem into "FILE:LINE: problem".
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace manylight {

// Reads a regular file of at most maxBytes. Throws SceneError "PATH: problem" (missing,
// not a regular file — a FIFO would block —, too large, unreadable).
std::string readTextFile(const std::string& path, std::uintmax_t maxBytes);

struct TextLine {
  int number;             // 1-based
  std::string_view text;  // without the line break and surrounding blanks
};

// The lines that say something: blank lines and lines starting with '#' are left out. A
// UTF-8 byte order mark before the first line is ignored.
std::vector<TextLine> contentLines(std::string_view text);

// Comma-separated fields, each without surrounding blanks.
std::vector<std::string_view> splitFields(std::string_view line);

// The whole of `field` as a finite number; false for anything else ("", "1x", "nan").
bool parseNumber(std::string_view field, double& value);

}  // namespace manylight
