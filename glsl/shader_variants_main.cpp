// Build-time generator: writes, into the folder given, layout.glsl (glsl::layoutPrelude) and
// one <stage>.variants file per stage of glsl::programs(): a variant per line, its #defines
// separated by spaces, "NONE" for none. cmake/BuildShader.cmake validates each line.
#include <fstream>
#include <iostream>
#include <map>
#include <set>
#include <string>

#include "glsl/variants.h"

namespace {

// Writes `text` to `path` unless the file already holds it, so unchanged lists rebuild nothing.
bool writeIfChanged(const std::string& path, const std::string& text) {
  std::ifstream in(path, std::ios::binary);
  const std::string old((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in && old == text) return true;
  std::ofstream out(path, std::ios::binary);
  out << text;
  return bool(out);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: manylight_shader_variants OUTPUT_DIR\n";
    return 2;
  }
  const std::string dir = argv[1];
  std::map<std::string, std::set<std::string>> stages;
  for (const manylight::glsl::ProgramVariants& p : manylight::glsl::programs()) {
    stages[p.vertex].insert("NONE");  // the vertex stages read no variant's define
    for (const std::vector<std::string>& defines : p.variants) {
      std::string line;
      for (const std::string& d : defines) line += (line.empty() ? "" : " ") + d;
      stages[p.fragment].insert(line.empty() ? "NONE" : line);
    }
  }
  bool ok = writeIfChanged(dir + "/layout.glsl", manylight::glsl::layoutPrelude());
  for (const auto& [stage, variants] : stages) {
    std::string text;
    for (const std::string& v : variants) text += v + "\n";
    ok = writeIfChanged(dir + "/" + stage + ".variants", text) && ok;
  }
  if (!ok) std::cerr << "manylight_shader_variants: cannot write into " << dir << "\n";
  return ok ? 0 : 1;
}
