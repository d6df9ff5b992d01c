#include "scene/light_list.h"

#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "base/error.h"
#include "base/text_table.h"
#include "scene/srgb.h"

namespace manylight {
namespace {

// A problem with one light; the caller adds the file and line.
class ListError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct ListedLight {
  glm::dvec3 position{0.0};
  double rgb[3] = {0, 0, 0};
  double brightness = 0.0;
  double radius = 0.0;  // 0: absent
  std::string falloff = "inverse-square";
};

Light toLight(const ListedLight& l) {
  for (int c = 0; c < 3; ++c) {
    const double v = l.rgb[c];
    if (v != std::floor(v) || v < 0.0 || v > 255.0) {
      throw ListError(std::string("colour ") + "RGB"[c] + " must be an integer code 0..255, got " +
                      std::to_string(v));
    }
  }
  if (!(l.brightness >= 0.0) || !std::isfinite(float(l.brightness))) {
    throw ListError("brightness must be a finite number >= 0, got " + std::to_string(l.brightness));
  }
  if (l.radius < 0.0 || !std::isfinite(float(l.radius))) {
    throw ListError("radius must be a finite number > 0, got " + std::to_string(l.radius));
  }
  if (l.falloff != "inverse-square") {
    throw ListError("falloff '" + l.falloff + "' is not modelled; only inverse-square (glTF's) is");
  }
  Light light;
  light.type = LightType::Point;
  light.position = glm::vec3(l.position);
  if (!std::isfinite(light.position.x) || !std::isfinite(light.position.y) ||
      !std::isfinite(light.position.z)) {
    throw ListError("position is not finite in single precision");
  }
  light.colour = glm::vec3(float(decodeSrgb8(std::uint8_t(l.rgb[0]))),
                           float(decodeSrgb8(std::uint8_t(l.rgb[1]))),
                           float(decodeSrgb8(std::uint8_t(l.rgb[2]))));
  light.intensity = float(l.brightness);
  light.range = float(l.radius);
  return light;
}

// --- CSV -------------------------------------------------------------------------------

const char* const kCsvColumns[] = {"x", "y", "z", "r", "g", "b", "brightness", "radius", "falloff"};
constexpr int kCsvRequired = 7;  // the first seven

std::vector<ListedLight> parseCsv(const std::vector<TextLine>& lines,
                                  std::vector<int>& lineNumbers) {
  if (lines.empty()) return {};
  // column[k]: which field holds kCsvColumns[k], or −1.
  int column[9];
  std::fill(std::begin(column), std::end(column), -1);
  const std::vector<std::string_view> header = splitFields(lines[0].text);
  for (std::size_t f = 0; f < header.size(); ++f) {
    int k = 0;
    while (k < 9 && header[f] != kCsvColumns[k]) ++k;
    if (k == 9) {
      throw ListError(std::to_string(lines[0].number) + ": unknown column '" +
                      std::string(header[f]) +
                      "'; expected x,y,z,r,g,b,brightness[,radius][,falloff]");
    }
    if (column[k] >= 0)
      throw ListError(std::to_string(lines[0].number) + ": column '" + kCsvColumns[k] + "' twice");
    column[k] = int(f);
  }
  for (int k = 0; k < kCsvRequired; ++k) {
    if (column[k] < 0) {
      throw ListError(std::to_string(lines[0].number) + ": the header has no column '" +
                      kCsvColumns[k] + "'; expected x,y,z,r,g,b,brightness[,radius][,falloff]");
    }
  }
  std::vector<ListedLight> lights;
  lights.reserve(lines.size() - 1);
  for (std::size_t i = 1; i < lines.size(); ++i) {
    const std::string where = std::to_string(lines[i].number) + ": ";
    const std::vector<std::string_view> fields = splitFields(lines[i].text);
    if (fields.size() != header.size()) {
      throw ListError(where + "expected " + std::to_string(header.size()) + " fields, got " +
                      std::to_string(fields.size()));
    }
    double v[8] = {0, 0, 0, 0, 0, 0, 0, 0};
    for (int k = 0; k < 8; ++k) {
      if (column[k] < 0) continue;
      if (!parseNumber(fields[column[k]], v[k])) {
        throw ListError(where + kCsvColumns[k] + ": expected a number, got '" +
                        std::string(fields[column[k]]) + "'");
      }
    }
    ListedLight l;
    l.position = {v[0], v[1], v[2]};
    l.rgb[0] = v[3], l.rgb[1] = v[4], l.rgb[2] = v[5];
    l.brightness = v[6];
    l.radius = v[7];
    if (column[7] >= 0 && !(l.radius > 0.0)) throw ListError(where + "radius must be > 0");
    if (column[8] >= 0) l.falloff = std::string(fields[column[8]]);
    lights.push_back(l);
    lineNumbers.push_back(lines[i].number);
  }
  return lights;
}

// --- The UE4 text dump --------------------------------------------------------------------

// Reads one dump line left to right; each step names what it expected.
class DumpLine {
 public:
  explicit DumpLine(std::string_view s) : s_(s) {}

  void expect(std::string_view word) {
    skipBlanks();
    if (s_.substr(0, word.size()) != word) fail("'" + std::string(word) + "'");
    s_.remove_prefix(word.size());
  }
  void hexWord() {
    skipBlanks();
    std::size_t n = 0;
    while (n < s_.size() && std::isxdigit(static_cast<unsigned char>(s_[n]))) ++n;
    if (n == 0) fail("a hexadecimal GUID");
    s_.remove_prefix(n);
  }
  double number(const char* what) {
    skipBlanks();
    double v = 0.0;
    const char* begin = s_.data();
    if (!s_.empty() && s_[0] == '+') ++begin;
    const auto [end, ec] = std::from_chars(begin, s_.data() + s_.size(), v);
    if (ec != std::errc() || !std::isfinite(v)) fail(std::string("a number for ") + what);
    s_.remove_prefix(std::size_t(end - s_.data()));
    return v;
  }
  bool startsWith(std::string_view word) {
    skipBlanks();
    return s_.substr(0, word.size()) == word;
  }
  void end() {
    skipBlanks();
    if (!s_.empty()) fail("the end of the line");
  }

 private:
  void skipBlanks() {
    while (!s_.empty() && (s_[0] == ' ' || s_[0] == '\t')) s_.remove_prefix(1);
  }
  [[noreturn]] void fail(const std::string& expected) {
    const std::string got =
        s_.empty() ? "the end of the line" : "'" + std::string(s_.substr(0, 16)) + "'";
    throw ListError("expected " + expected + ", got " + got);
  }
  std::string_view s_;
};

ListedLight parseDumpLine(std::string_view text) {
  DumpLine d(text);
  ListedLight l;
  d.expect("GUID");
  d.hexWord();
  d.expect("-");
  d.expect("Position");
  d.expect("X=");
  l.position.x = d.number("X");
  d.expect("Y=");
  l.position.y = d.number("Y");
  d.expect("Z=");
  l.position.z = d.number("Z");
  if (d.startsWith("W=")) {
    d.expect("W=");
    d.number("W");
  }
  d.expect("-");
  d.expect("Radius");
  l.radius = d.number("Radius");
  if (!(l.radius > 0.0)) throw ListError("radius must be > 0");
  d.expect("-");
  d.expect("Color");
  d.expect("(");
  d.expect("R=");
  l.rgb[0] = d.number("R");
  d.expect(",");
  d.expect("G=");
  l.rgb[1] = d.number("G");
  d.expect(",");
  d.expect("B=");
  l.rgb[2] = d.number("B");
  if (d.startsWith(",")) {
    d.expect(",");
    d.expect("A=");
    d.number("A");
  }
  d.expect(")");
  d.expect("-");
  d.expect("Brightness");
  d.expect("=");
  l.brightness = d.number("Brightness");
  d.end();
  return l;
}

// --- JSON --------------------------------------------------------------------------------

double jsonNumber(const nlohmann::json& v, const char* what) {
  if (!v.is_number()) throw ListError(std::string(what) + ": expected a number, got " + v.dump());
  return v.get<double>();
}

ListedLight parseJsonLight(const nlohmann::json& j) {
  if (!j.is_object()) throw ListError("expected an object, got " + j.dump().substr(0, 40));
  ListedLight l;
  bool hasPosition = false, hasColour = false, hasBrightness = false;
  for (const auto& [key, v] : j.items()) {
    if (key == "position" || key == "color") {
      if (!v.is_array() || v.size() != 3) throw ListError(key + ": expected an array of 3 numbers");
      for (int c = 0; c < 3; ++c) {
        const double x = jsonNumber(v[c], key.c_str());
        key == "position" ? l.position[c] = x : l.rgb[c] = x;
      }
      (key == "position" ? hasPosition : hasColour) = true;
    } else if (key == "brightness") {
      l.brightness = jsonNumber(v, "brightness");
      hasBrightness = true;
    } else if (key == "radius") {
      l.radius = jsonNumber(v, "radius");
      if (!(l.radius > 0.0)) throw ListError("radius must be > 0");
    } else if (key == "falloff") {
      if (!v.is_string()) throw ListError("falloff: expected a string");
      l.falloff = v.get<std::string>();
    } else {
      throw ListError("unknown key '" + key +
                      "'; expected position, color, brightness, radius, falloff");
    }
  }
  if (!hasPosition) throw ListError("no position");
  if (!hasColour) throw ListError("no color");
  if (!hasBrightness) throw ListError("no brightness");
  return l;
}

void checkBudget(const std::string& path, std::size_t listed, const Scene& scene,
                 const LoadOptions& options) {
  if (scene.lights.size() + listed > options.lightBudget) {
    throw SceneError(path + ": " + std::to_string(listed) + " lights and the scene's " +
                     std::to_string(scene.lights.size()) + " exceed the light budget of " +
                     std::to_string(options.lightBudget) + " (--light-budget)");
  }
}

}  // namespace

void appendLightList(const std::string& path, Scene& scene, const LoadOptions& options) {
  const std::string text = readTextFile(path, options.maxFileBytes);
  const std::string ext = std::filesystem::path(path).extension().string();
  std::vector<Light> lights;
  if (ext == ".json" || ext == ".JSON") {
    const nlohmann::json j = nlohmann::json::parse(text, nullptr, false);
    if (j.is_discarded()) {
      // Parse again with exceptions for the message, which names the line and column.
      try {
        const nlohmann::json again = nlohmann::json::parse(text);
        (void)again;
      } catch (const nlohmann::json::exception& e) {
        std::string what = e.what();
        const std::size_t at = what.find("] ");
        throw SceneError(path + ": " + (at == std::string::npos ? what : what.substr(at + 2)));
      }
    }
    const nlohmann::json* array = &j;
    if (j.is_object()) {
      const auto it = j.find("lights");
      if (it == j.end() || j.size() != 1)
        throw SceneError(path + ": expected an array of lights or {\"lights\": [...]}");
      array = &*it;
    }
    if (!array->is_array())
      throw SceneError(path + ": expected an array of lights or {\"lights\": [...]}");
    checkBudget(path, array->size(), scene, options);
    lights.reserve(array->size());
    for (std::size_t i = 0; i < array->size(); ++i) {
      try {
        lights.push_back(toLight(parseJsonLight((*array)[i])));
      } catch (const ListError& e) {
        throw SceneError(path + ": light " + std::to_string(i) + ": " + e.what());
      }
    }
  } else {
    const std::vector<TextLine> lines = contentLines(text);
    const bool csv = ext == ".csv" || ext == ".CSV";
    checkBudget(path, csv && !lines.empty() ? lines.size() - 1 : lines.size(), scene, options);
    if (csv) {
      std::vector<int> numbers;
      std::vector<ListedLight> listed;
      try {
        listed = parseCsv(lines, numbers);
      } catch (const ListError& e) {
        throw SceneError(path + ":" + e.what());
      }
      lights.reserve(listed.size());
      for (std::size_t i = 0; i < listed.size(); ++i) {
        try {
          lights.push_back(toLight(listed[i]));
        } catch (const ListError& e) {
          throw SceneError(path + ":" + std::to_string(numbers[i]) + ": " + e.what());
        }
      }
    } else {
      lights.reserve(lines.size());
      for (const TextLine& line : lines) {
        try {
          lights.push_back(toLight(parseDumpLine(line.text)));
        } catch (const ListError& e) {
          throw SceneError(path + ":" + std::to_string(line.number) + ": " + e.what());
        }
      }
    }
  }
  scene.lights.insert(scene.lights.end(), lights.begin(), lights.end());
}

}  // namespace manylight
