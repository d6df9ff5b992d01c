#include "base/text_table.h"

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "base/error.h"

namespace manylight {

namespace fs = std::filesystem;

std::string readTextFile(const std::string& path, std::uintmax_t maxBytes) {
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (ec || !fs::exists(status))
    throw SceneError(path + ": cannot open: No such file or directory");
  if (!fs::is_regular_file(status)) throw SceneError(path + ": not a regular file");
  const std::uintmax_t size = fs::file_size(path, ec);
  if (ec) throw SceneError(path + ": " + ec.message());
  if (size > maxBytes) {
    throw SceneError(path + ": " + std::to_string(size) + " bytes exceed the limit of " +
                     std::to_string(maxBytes) + " bytes");
  }
  std::ifstream f(path, std::ios::binary);
  if (!f) throw SceneError(path + ": cannot open: " + std::strerror(errno));
  std::string text(size, '\0');
  if (size > 0 && !f.read(text.data(), std::streamsize(size)))
    throw SceneError(path + ": cannot read");
  return text;
}

namespace {

std::string_view trim(std::string_view s) {
  const char* blanks = " \t\r\n";
  const std::size_t first = s.find_first_not_of(blanks);
  if (first == std::string_view::npos) return {};
  return s.substr(first, s.find_last_not_of(blanks) - first + 1);
}

}  // namespace

std::vector<TextLine> contentLines(std::string_view text) {
  if (text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);
  std::vector<TextLine> lines;
  int number = 0;
  while (!text.empty()) {
    ++number;
    const std::size_t end = text.find('\n');
    const std::string_view line = trim(text.substr(0, end));
    text = end == std::string_view::npos ? std::string_view() : text.substr(end + 1);
    if (!line.empty() && line[0] != '#') lines.push_back({number, line});
  }
  return lines;
}

std::vector<std::string_view> splitFields(std::string_view line) {
  std::vector<std::string_view> fields;
  while (true) {
    const std::size_t comma = line.find(',');
    fields.push_back(trim(line.substr(0, comma)));
    if (comma == std::string_view::npos) return fields;
    line.remove_prefix(comma + 1);
  }
}

bool parseNumber(std::string_view field, double& value) {
  const char* begin = field.data();
  const char* end = field.data() + field.size();
  if (begin != end && *begin == '+') ++begin;
  const auto [stop, ec] = std::from_chars(begin, end, value);  // no locale, no hexadecimal
  return begin != end && ec == std::errc() && stop == end && std::isfinite(value);
}

}  // namespace manylight
