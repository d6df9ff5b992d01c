// glsl/spatial_hash.glsl against bake/spatial_hash.h: a fragment shader computes
// spatialHashSlot for every key of a built table, from an offset table that starts past
// other texels (offsetBase), and each slot must equal hashSlot's.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "bake/spatial_hash.h"
#include "gl/objects.h"
#include "tests/gl_support.h"

namespace manylight::testing {
namespace {

using namespace gl::api;

constexpr int kWidth = 64;  // keys per row of the render target

const char* const kVertex = R"glsl(#version 330 core
void main() {
  vec2 p = vec2(gl_VertexID == 1 ? 3.0 : -1.0, gl_VertexID == 2 ? 3.0 : -1.0);
  gl_Position = vec4(p, 0.0, 1.0);
}
)glsl";

// Follows the #version line and glsl/spatial_hash.glsl.
const char* const kFragment = R"glsl(
uniform usamplerBuffer uKeys;
uniform usamplerBuffer uOffsets;
uniform ivec3 uDims;
uniform int uOffsetCount;
uniform int uOffsetBase;
uniform int uKeyCount;
out uint oSlot;
void main() {
  int i = int(gl_FragCoord.y) * 64 + int(gl_FragCoord.x);
  oSlot = i < uKeyCount ? spatialHashSlot(texelFetch(uKeys, i).xyz, uDims, uOffsetCount,
                                          uOffsets, uOffsetBase)
                        : 0xffffffffu;
}
)glsl";

std::string hashSource() {
  std::ifstream in(std::string(MANYLIGHT_SOURCE_DIR) + "/glsl/spatial_hash.glsl");
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

gl::Shader compile(GLenum kind, const std::string& text) {
  gl::Shader shader(kind);
  const char* src = text.c_str();
  glShaderSource(shader.id(), 1, &src, nullptr);
  glCompileShader(shader.id());
  GLint ok = 0;
  glGetShaderiv(shader.id(), GL_COMPILE_STATUS, &ok);
  char log[4096] = {};
  glGetShaderInfoLog(shader.id(), sizeof log, nullptr, log);
  EXPECT_TRUE(ok) << log;
  return shader;
}

gl::Handle<gl::ProgramTraits> linkProgram() {
  const std::string fragment = "#version 330 core\n" + hashSource() + kFragment;
  gl::Shader vs = compile(GL_VERTEX_SHADER, kVertex), fs = compile(GL_FRAGMENT_SHADER, fragment);
  gl::Handle<gl::ProgramTraits> program;
  glAttachShader(program.id(), vs.id());
  glAttachShader(program.id(), fs.id());
  glBindFragDataLocation(program.id(), 0, "oSlot");
  glLinkProgram(program.id());
  GLint ok = 0;
  glGetProgramiv(program.id(), GL_LINK_STATUS, &ok);
  char log[4096] = {};
  glGetProgramInfoLog(program.id(), sizeof log, nullptr, log);
  EXPECT_TRUE(ok) << log;
  return program;
}

// A buffer texture of `format` holding `bytes` bytes from `data`.
struct BufferTexture {
  gl::Buffer buffer;
  gl::Texture texture;
  BufferTexture(const void* data, std::size_t bytes, GLenum format) {
    glBindBuffer(GL_TEXTURE_BUFFER, buffer.id());
    glBufferData(GL_TEXTURE_BUFFER, GLsizeiptr(bytes), data, GL_STATIC_DRAW);
    glBindTexture(GL_TEXTURE_BUFFER, texture.id());
    glTexBuffer(GL_TEXTURE_BUFFER, format, buffer.id());
    glBindBuffer(GL_TEXTURE_BUFFER, 0);
  }
};

void setUniforms(GLuint program, const SpatialHash& h, int base, int keyCount) {
  glUseProgram(program);
  glUniform1i(glGetUniformLocation(program, "uKeys"), 0);
  glUniform1i(glGetUniformLocation(program, "uOffsets"), 1);
  glUniform3i(glGetUniformLocation(program, "uDims"), h.dims.x, h.dims.y, h.dims.z);
  glUniform1i(glGetUniformLocation(program, "uOffsetCount"), h.offsetCount);
  glUniform1i(glGetUniformLocation(program, "uOffsetBase"), base);
  glUniform1i(glGetUniformLocation(program, "uKeyCount"), keyCount);
}

// The slots the shader computes for `keys` (one per pixel, row by row).
std::vector<std::uint32_t> shaderSlots(const SpatialHash& h, const std::vector<glm::uvec3>& keys) {
  const int rows = int(keys.size() + kWidth - 1) / kWidth, base = 5;
  std::vector<std::uint32_t> keyTexels;
  for (glm::uvec3 k : keys) keyTexels.insert(keyTexels.end(), {k.x, k.y, k.z, 0u});
  std::vector<std::uint16_t> offsetTexels(4 * base, 0xffff);  // another table's texels
  const std::vector<std::uint16_t> own = spatialHashTexels(h);
  offsetTexels.insert(offsetTexels.end(), own.begin(), own.end());
  BufferTexture keyBuffer(keyTexels.data(), 4 * keyTexels.size(), GL_RGBA32UI);
  BufferTexture offsetBuffer(offsetTexels.data(), 2 * offsetTexels.size(), GL_RGBA16UI);
  gl::Texture target;
  glBindTexture(GL_TEXTURE_2D, target.id());
  glTexImage2D(GL_TEXTURE_2D, 0, GL_R32UI, kWidth, rows, 0, GL_RED_INTEGER, GL_UNSIGNED_INT,
               nullptr);
  gl::Framebuffer fbo;
  glBindFramebuffer(GL_FRAMEBUFFER, fbo.id());
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, target.id(), 0);
  EXPECT_EQ(glCheckFramebufferStatus(GL_FRAMEBUFFER), GLenum(GL_FRAMEBUFFER_COMPLETE));
  const gl::Handle<gl::ProgramTraits> program = linkProgram();
  setUniforms(program.id(), h, base, int(keys.size()));
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_BUFFER, keyBuffer.texture.id());
  glActiveTexture(GL_TEXTURE1);
  glBindTexture(GL_TEXTURE_BUFFER, offsetBuffer.texture.id());
  gl::VertexArray vao;
  glBindVertexArray(vao.id());
  glViewport(0, 0, kWidth, rows);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  std::vector<std::uint32_t> slots(std::size_t(kWidth * rows));
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glReadPixels(0, 0, kWidth, rows, GL_RED_INTEGER, GL_UNSIGNED_INT, slots.data());
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glActiveTexture(GL_TEXTURE0);
  slots.resize(keys.size());
  return slots;
}

void expectShaderMatches(const std::vector<glm::uvec3>& keys, bool salted) {
  context();
  const SpatialHash h = buildSpatialHash(keys);
  ASSERT_EQ(h.salt != 0, salted) << "salt " << h.salt;
  const std::vector<std::uint32_t> slots = shaderSlots(h, keys);
  ASSERT_EQ(slots.size(), keys.size());
  for (std::size_t i = 0; i < keys.size(); ++i) {
    ASSERT_EQ(slots[i], hashSlot(h, keys[i])) << "key " << i;
  }
}

TEST(SpatialHashShader, SlotsMatchTheCpuHash) {
  std::vector<glm::uvec3> keys;
  for (std::uint32_t i = 0; i < 3000; ++i) {  // four slabs 30x25 cells, then a corner of the domain
    keys.push_back({100 + i % 30, 200 + (i / 30) % 25, 50 * (i / 750) + (i / 30) / 25 % 4});
  }
  const std::uint32_t top = kSpatialHashKeyLimit - 1;
  for (std::uint32_t i = 0; i < 64; ++i)
    keys.push_back({top - i % 4, top - i / 4 % 4, top - i / 16});
  expectShaderMatches(keys, false);
}

// Pairs of keys in a 10x10x10 table with the same residue and linear quotient term
// (quotients (0, 1, 0) and (61, 0, 0)) need the salted term.
TEST(SpatialHashShader, SaltedSlotsMatchTheCpuHash) {
  std::vector<glm::uvec3> keys;
  for (std::uint32_t i = 0; i < 500; ++i) {
    const glm::uvec3 k(i % 10, 10 + i / 10 % 10, i / 100);
    keys.push_back(k);
    keys.push_back({k.x + 610, k.y - 10, k.z});
  }
  expectShaderMatches(keys, true);
}

}  // namespace
}  // namespace manylight::testing
