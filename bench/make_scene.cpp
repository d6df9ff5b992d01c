// Writes the generated room scene (generators/scene_builder.h) with a chosen light count: the
// bundled sample (scenes/sample.gltf) and the benchmarks' inputs come from here. With
// --cornell it writes the Cornell-like room of docs/indirect.md instead. With
// --layout NAME the lights are those of the sweep's layout (generators/light_layouts.h), so peers
// (bench/peers.sh) render exactly what `manylight bench` renders.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "base/error.h"
#include "generators/light_layouts.h"
#include "generators/scene_builder.h"

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr,
                 "usage: manylight_make_scene OUT.gltf|OUT.glb LIGHTS [SEED] [--point-only] "
                 "[--specular] [--untextured] [--layout NAME] [--cornell [--block]]\n");
    return 2;
  }
  manylight::RoomOptions o;
  o.lightCount = std::atoi(argv[2]);
  if (argc > 3 && argv[3][0] != '-') o.seed = std::uint32_t(std::strtoul(argv[3], nullptr, 10));
  try {
    for (int i = 3; i < argc; ++i) {
      const std::string a = argv[i];
      if (a == "--point-only") o.mix = false;
      if (a == "--specular") o.specular = true;
      if (a == "--untextured") o.textured = false;
      if (a == "--layout" && i + 1 < argc) {
        // The sweep's seed (tools/sweep.h) unless one is given.
        const std::uint32_t seed = argc > 3 && argv[3][0] != '-' ? o.seed : 7;
        o.lights =
            manylight::layoutLights(manylight::parseLightLayout(argv[++i]), o.lightCount, seed);
      }
    }
    bool cornell = false;
    for (int i = 3; i < argc; ++i) cornell = cornell || std::string(argv[i]) == "--cornell";
    if (cornell) {
      // The Cornell-like room's spot, and LIGHTS − 1 more lights.
      manylight::CornellOptions c;
      c.extraLights = std::max(o.lightCount - 1, 0);
      c.seed = o.seed;
      for (int i = 3; i < argc; ++i) c.block = c.block || std::string(argv[i]) == "--block";
      manylight::writeCornellScene(argv[1], c);
    } else {
      manylight::writeRoomScene(argv[1], o);
    }
  } catch (const manylight::Error& e) {
    std::fprintf(stderr, "manylight_make_scene: %s\n", e.what());
    return 1;
  }
  return 0;
}
