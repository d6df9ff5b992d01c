// Writes the generated room scene (scene/scene_builder.h) with a chosen light count: the
// bundled sample (scenes/sample.gltf) and the benchmarks' inputs come from here.
#include <cstdio>
#include <cstdlib>
#include <string>

#include "scene/error.h"
#include "scene/scene_builder.h"

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr,
                 "usage: manylight_make_scene OUT.gltf|OUT.glb LIGHTS [SEED] [--point-only] "
                 "[--specular] [--untextured]\n");
    return 2;
  }
  manylight::RoomOptions o;
  o.lightCount = std::atoi(argv[2]);
  if (argc > 3 && argv[3][0] != '-') o.seed = std::uint32_t(std::strtoul(argv[3], nullptr, 10));
  for (int i = 3; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--point-only") o.mix = false;
    if (a == "--specular") o.specular = true;
    if (a == "--untextured") o.textured = false;
  }
  try {
    manylight::writeRoomScene(argv[1], o);
  } catch (const manylight::Error& e) {
    std::fprintf(stderr, "manylight_make_scene: %s\n", e.what());
    return 1;
  }
  return 0;
}
