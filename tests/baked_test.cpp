// Baked scenes (bake/baked_file.h): a bake reads back as the scene it was made from, trees
// included, and anything that is not an intact baked file of this version is refused with a
// message naming the file and the problem.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "bake/baked_file.h"
#include "bake/light_tree_layout.h"
#include "scene/gltf_loader.h"
#include "tests/test_support.h"

namespace manylight {
namespace {

using testing::testFolder;

std::string readBytes(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

void writeBytes(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

Scene roomWithLights(int lights, bool specular = false) {
  RoomOptions o;
  o.lightCount = lights;
  o.specular = specular;
  return loadGltf(testing::roomScene(o, "baked-room-" + std::to_string(lights) + ".gltf"));
}

TEST(Baked, ReadsBackWhatWasBaked) {
  TreeOptions trees;
  trees.split = Split::LongestAxis;
  trees.nodeColour = NodeColourCoding::Fitted;
  const BakedScene baked = bakeScene(roomWithLights(300, true), trees);
  const std::string path = (testFolder() / "room.mlbake").string();
  writeBakedScene(path, baked);
  const BakedScene b = readBakedScene(path);
  const Scene &s = baked.scene, &r = b.scene;
  EXPECT_EQ(r.name, s.name);
  ASSERT_EQ(r.meshes.size(), s.meshes.size());
  for (std::size_t m = 0; m < s.meshes.size(); ++m) {
    ASSERT_EQ(r.meshes[m].primitives.size(), s.meshes[m].primitives.size());
    for (std::size_t p = 0; p < s.meshes[m].primitives.size(); ++p) {
      const Primitive &a = s.meshes[m].primitives[p], &c = r.meshes[m].primitives[p];
      EXPECT_EQ(c.positions, a.positions);
      EXPECT_EQ(c.normals, a.normals);
      EXPECT_EQ(c.texcoords, a.texcoords);
      EXPECT_EQ(c.texcoords1, a.texcoords1);
      EXPECT_EQ(c.tangents, a.tangents);
      EXPECT_EQ(c.mode, a.mode);
      EXPECT_EQ(c.colours, a.colours);
      EXPECT_EQ(c.indices, a.indices);
      EXPECT_EQ(c.material, a.material);
    }
  }
  ASSERT_EQ(r.instances.size(), s.instances.size());
  for (std::size_t i = 0; i < s.instances.size(); ++i) {
    EXPECT_EQ(r.instances[i].mesh, s.instances[i].mesh);
    EXPECT_EQ(r.instances[i].world, s.instances[i].world);
  }
  ASSERT_EQ(r.materials.size(), s.materials.size());
  for (std::size_t i = 0; i < s.materials.size(); ++i) {
    EXPECT_EQ(r.materials[i].baseColorFactor, s.materials[i].baseColorFactor);
    EXPECT_EQ(r.materials[i].baseColorTexture, s.materials[i].baseColorTexture);
    EXPECT_EQ(r.materials[i].roughness, s.materials[i].roughness);
    EXPECT_EQ(r.materials[i].metallic, s.materials[i].metallic);
    for (int k = 0; k < Material::kTextureSlots; ++k)
      EXPECT_EQ(r.materials[i].slot(k), s.materials[i].slot(k));
    EXPECT_EQ(r.materials[i].alphaMode, s.materials[i].alphaMode);
    EXPECT_EQ(r.materials[i].unlit, s.materials[i].unlit);
  }
  ASSERT_EQ(r.textures.size(), s.textures.size());
  ASSERT_FALSE(s.textures.empty());
  EXPECT_EQ(r.textures[0].rgba, s.textures[0].rgba);
  EXPECT_EQ(r.textures[0].width, s.textures[0].width);
  ASSERT_EQ(r.lights.size(), 300u);
  for (std::size_t i = 0; i < s.lights.size(); ++i) {
    EXPECT_EQ(r.lights[i].type, s.lights[i].type);
    EXPECT_EQ(r.lights[i].position, s.lights[i].position);
    EXPECT_EQ(r.lights[i].colour, s.lights[i].colour);
    EXPECT_EQ(r.lights[i].range, s.lights[i].range);
    EXPECT_EQ(r.lights[i].outerConeAngle, s.lights[i].outerConeAngle);
  }
  ASSERT_EQ(r.cameras.size(), s.cameras.size());
  EXPECT_EQ(r.cameras[0].world, s.cameras[0].world);
  EXPECT_EQ(r.cameras[0].yfov, s.cameras[0].yfov);
  // The trees as packed, with the coding's constants and error figures.
  EXPECT_TRUE(b.hasTrees);
  EXPECT_EQ(b.trees.split, Split::LongestAxis);
  EXPECT_EQ(b.packed.words, baked.packed.words);
  for (int t = 0; t < 3; ++t) {
    EXPECT_EQ(b.packed.base[t], baked.packed.base[t]);
    EXPECT_EQ(b.packed.leaves[t], baked.packed.leaves[t]);
  }
  const NodeColourCoder &c = b.packed.colour, &o = baked.packed.colour;
  EXPECT_EQ(c.coding(), NodeColourCoding::Fitted);
  EXPECT_EQ(c.fit().gamma, o.fit().gamma);
  EXPECT_EQ(c.fit().a, o.fit().a);
  EXPECT_EQ(c.fit().worstRelative, o.fit().worstRelative);
  EXPECT_EQ(c.slack, o.slack);
  EXPECT_EQ(c.maxError[1], o.maxError[1]);
  EXPECT_EQ(c.decode(baked.packed.words[8]), o.decode(baked.packed.words[8]));
  // Baking again gives the same bytes.
  const std::string again = (testFolder() / "again.mlbake").string();
  writeBakedScene(again, bakeScene(roomWithLights(300, true), trees));
  EXPECT_EQ(readBytes(again), readBytes(path));
}

TEST(Baked, TheOctreeReadsBackAsBaked) {
  const BakedScene baked = bakeScene(roomWithLights(300), {});
  ASSERT_TRUE(baked.hasOctree);  // every other point and spot light has a range
  const std::string path = (testFolder() / "octree.mlbake").string();
  writeBakedScene(path, baked);
  const BakedScene b = readBakedScene(path);
  ASSERT_TRUE(b.hasOctree);
  const LinklessOctree &o = baked.octree, &r = b.octree;
  EXPECT_EQ(r.levels, o.levels);
  EXPECT_EQ(r.origin, o.origin);
  EXPECT_EQ(r.leafEdge, o.leafEdge);
  EXPECT_EQ(r.nodes, o.nodes);
  EXPECT_EQ(r.offsets, o.offsets);
  EXPECT_EQ(r.indices, o.indices);
  EXPECT_EQ(r.globalCount, o.globalCount);
  EXPECT_GT(r.globalCount, 0u);
  for (std::size_t l = 0; l < o.level.size(); ++l) {
    EXPECT_EQ(r.level[l].dims, o.level[l].dims);
    EXPECT_EQ(r.level[l].offsetCount, o.level[l].offsetCount);
  }
}

TEST(Baked, TheLightAnimationReadsBackAndPlaysTheSame) {
  const std::filesystem::path file = std::filesystem::path(MANYLIGHT_SHARED_SCENES) /
                                     "AnimateAllTheThings/24_animation_pointer.gltf";
  if (!std::filesystem::exists(file))
    GTEST_SKIP() << "no " << file << " (the shared scenes are absent)";
  const BakedScene baked = bakeScene(loadGltf(file.string()), {});
  ASSERT_TRUE(baked.scene.lightAnimation.animated());
  const std::string path = (testFolder() / "animated.mlbake").string();
  writeBakedScene(path, baked);
  const BakedScene b = readBakedScene(path);
  ASSERT_EQ(b.scene.lightAnimation.lights.size(), baked.scene.lightAnimation.lights.size());
  EXPECT_EQ(b.scene.lightAnimation.duration(), baked.scene.lightAnimation.duration());
  for (float t : {0.0f, 2.5f, 5.0f, 9.0f}) {
    std::vector<Light> a, c;
    baked.scene.lightAnimation.sampleLights(baked.scene, t, a);
    b.scene.lightAnimation.sampleLights(b.scene, t, c);
    ASSERT_EQ(a.size(), c.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
      EXPECT_EQ(a[i].position, c[i].position) << t;
      EXPECT_EQ(a[i].colour, c[i].colour) << t;
      EXPECT_EQ(a[i].intensity, c[i].intensity) << t;
      EXPECT_EQ(a[i].range, c[i].range) << t;
      EXPECT_EQ(a[i].outerConeAngle, c[i].outerConeAngle) << t;
    }
  }
}

TEST(Baked, ASceneWithoutLightsHasNoTrees) {
  const std::string path = (testFolder() / "dark.mlbake").string();
  Scene dark = roomWithLights(1);
  dark.lights.clear();
  writeBakedScene(path, bakeScene(dark, {}));
  const BakedScene b = readBakedScene(path);
  EXPECT_FALSE(b.hasTrees);
  EXPECT_FALSE(b.hasOctree);
  EXPECT_TRUE(b.scene.lights.empty());
}

// Rewrites the header's size and checksum, as a careful forger would.
void reseal(std::string& file) {
  const std::uint64_t size = file.size();
  std::memcpy(&file[16], &size, 8);
  const std::uint64_t sum = bakedChecksum(std::string_view(file).substr(kBakedHeaderBytes));
  std::memcpy(&file[24], &sum, 8);
}

// Where a section's bytes start (docs/baked-format.md: the table follows the header).
std::size_t sectionOffset(const std::string& file, const char (&tag)[5]) {
  std::uint32_t count;
  std::memcpy(&count, &file[kBakedHeaderBytes], 4);
  for (std::uint32_t i = 0; i < count; ++i) {
    const std::size_t entry = kBakedHeaderBytes + 4 + 24 * i;
    if (std::memcmp(&file[entry], tag, 4) == 0) {
      std::uint64_t offset;
      std::memcpy(&offset, &file[entry + 8], 8);
      return std::size_t(offset);
    }
  }
  ADD_FAILURE() << "no section " << tag;
  return 0;
}

struct DamageCase {
  const char* name;
  std::string content;
  std::string message;  // after "PATH: "
};

void expectRefused(const std::vector<DamageCase>& cases) {
  for (const DamageCase& c : cases) {
    const std::string path = (testFolder() / (std::string(c.name) + ".mlbake")).string();
    writeBytes(path, c.content);
    try {
      readBakedScene(path);
      ADD_FAILURE() << c.name << ": accepted";
    } catch (const BakeError& e) {
      EXPECT_EQ(std::string(e.what()), path + ": " + c.message) << c.name;
    }
  }
}

TEST(Baked, ADamagedOctreeIsRefused) {
  const std::string good = (testFolder() / "good-octree.mlbake").string();
  writeBakedScene(good, bakeScene(roomWithLights(40), {}));
  const std::string bytes = readBytes(good);
  std::vector<DamageCase> octreeCases;
  // The octree section: origin, leaf edge, levels, 32 bytes a level, then the node texels.
  const std::size_t octree = sectionOffset(bytes, "OCTR");
  std::uint32_t levels;
  std::memcpy(&levels, &bytes[octree + 16], 4);
  std::uint64_t nodeWords;
  const std::size_t nodes = octree + 20 + 32 * std::size_t(levels);
  std::memcpy(&nodeWords, &bytes[nodes], 8);
  std::string badLeaf = bytes;
  for (std::uint64_t w = 1; w < nodeWords; w += 2) {  // the first leaf's list: far past the end
    std::uint32_t word;
    std::memcpy(&word, &bytes[nodes + 8 + 4 * w], 4);
    if (!(word & kOctreeLeafBit)) continue;
    const std::uint32_t first = 1u << 30;
    std::memcpy(&badLeaf[nodes + 8 + 4 * (w - 1)], &first, 4);
    break;
  }
  reseal(badLeaf);
  octreeCases.push_back(
      {"octree-leaf", badLeaf, "light octree: a leaf's list runs past the index list"});
  std::string badLevels = bytes;
  badLevels[octree + 16] = 40;
  reseal(badLevels);
  octreeCases.push_back(
      {"octree-levels", badLevels, "light octree: octree levels: 40 is more than 16"});
  expectRefused(octreeCases);
}

// Resealed damage to the light trees of `bytes`, a baked file of roomWithLights(40).
std::vector<DamageCase> damagedTrees(const std::string& bytes) {
  std::vector<DamageCase> cases;
  std::string rep = bytes;
  const std::size_t trees = sectionOffset(bytes, "TREE");
  // base[3], leaves[3], coding, fit (5 doubles, a count), fittedToSrgb, scale, 8 doubles, word
  // count.
  const std::size_t words = trees + 24 + 1 + 48 + 1 + 4 + 64 + 8;
  const std::int32_t farLight = 99999;
  std::memcpy(&rep[words + 4 * (layout::kNodeWords + 3)], &farLight,
              4);  // the first tree (directional), node 1
  reseal(rep);
  cases.push_back({"representative", rep,
                   "light trees: tree 0: node 1 names light 99999, not one of its type"});
  std::string twice = bytes;  // the first tree's second leaf holds its first leaf's light
  std::int32_t leaves0;
  std::memcpy(&leaves0, &bytes[trees + 12], 4);
  const std::size_t firstLeaf = words + 4 * layout::kNodeWords * std::size_t(leaves0 - 1);
  std::memcpy(&twice[firstLeaf + 4 * (layout::kNodeWords + 3)], &bytes[firstLeaf + 4 * 3], 4);
  std::int32_t light;
  std::memcpy(&light, &bytes[firstLeaf + 4 * 3], 4);
  reseal(twice);
  cases.push_back({"leaf-twice", twice,
                   "light trees: tree 0: leaves " + std::to_string(leaves0 - 1) + " and " +
                       std::to_string(leaves0) + " both hold light " + std::to_string(light)});
  return cases;
}

TEST(Baked, DamagedAndForeignFilesAreRefused) {
  const std::string good = (testFolder() / "good.mlbake").string();
  writeBakedScene(good, bakeScene(roomWithLights(40), {}));
  const std::string bytes = readBytes(good);
  std::vector<DamageCase> cases;
  cases.push_back({"truncated", bytes.substr(0, bytes.size() - 1),
                   "truncated or extended: " + std::to_string(bytes.size() - 1) +
                       " bytes, the header says " + std::to_string(bytes.size())});
  cases.push_back({"header-only", bytes.substr(0, 20), "truncated: 20 bytes"});
  cases.push_back({"extended", bytes + "x",
                   "truncated or extended: " + std::to_string(bytes.size() + 1) +
                       " bytes, the header says " + std::to_string(bytes.size())});
  std::string flipped = bytes;
  flipped[bytes.size() / 2] ^= 0x10;
  cases.push_back({"bit-flip", flipped, "checksum mismatch: the file is damaged"});
  std::string lastByte = bytes;
  lastByte.back() ^= 0x01;
  cases.push_back({"last-bit", lastByte, "checksum mismatch: the file is damaged"});
  std::string version = bytes;
  version[9] ^= 0x01;  // the version + 256
  cases.push_back({"version", version,
                   "baked format version " + std::to_string(kBakedFormatVersion + 256) +
                       ", expected " + std::to_string(kBakedFormatVersion) +
                       "; bake the scene again"});
  std::string magic = bytes;
  magic[0] = 'X';
  cases.push_back({"magic", magic, "not a manylight baked file (no MLBAKE magic)"});
  cases.push_back({"png", std::string("\x89PNG\r\n\x1a\n", 8) + std::string(100, '\0'),
                   "not a manylight baked file (no MLBAKE magic)"});
  cases.push_back(
      {"gltf", R"({"asset": {"version": "2.0"}})", "not a manylight baked file (no MLBAKE magic)"});
  cases.push_back({"empty", "", "not a manylight baked file (no MLBAKE magic)"});
  std::string flags = bytes;
  flags[12] = 1;
  cases.push_back({"flags", flags, "unknown flags 1"});
  // Resealed, so only the format's own checks can catch them.
  std::string lightType = bytes;
  lightType[sectionOffset(bytes, "LGHT") + 4] = 7;
  reseal(lightType);
  cases.push_back({"light-type", lightType, "lights: unknown light type 7"});
  for (DamageCase& c : damagedTrees(bytes)) cases.push_back(std::move(c));
  std::string index = bytes;
  index[sectionOffset(bytes, "INST") + 4] = 100;  // instance 0's mesh
  reseal(index);
  cases.push_back({"mesh-index", index, "instances: mesh index out of range"});
  std::string table = bytes;
  const std::uint64_t past = bytes.size() + 10;
  std::memcpy(&table[kBakedHeaderBytes + 4 + 8], &past, 8);
  reseal(table);
  cases.push_back({"table", table, "section table: a section lies outside the file"});

  expectRefused(cases);
  const std::string missing = (testFolder() / "missing.mlbake").string();
  try {
    readBakedScene(missing);
    ADD_FAILURE() << "missing: accepted";
  } catch (const BakeError& e) {
    EXPECT_EQ(std::string(e.what()), missing + ": cannot open: No such file or directory");
  }
  try {
    readBakedScene(testFolder().string());
    ADD_FAILURE() << "folder: accepted";
  } catch (const BakeError& e) {
    EXPECT_EQ(std::string(e.what()), testFolder().string() + ": not a regular file");
  }
}

}  // namespace
}  // namespace manylight
