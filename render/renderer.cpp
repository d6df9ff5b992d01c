#include "render/renderer.h"

#include <algorithm>
#include <cassert>
#include <chrono>
#include <cstdio>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "gl/context.h"

namespace manylight {

using namespace gl::api;

namespace {

// Waits for the indirect light's thread (IndirectLight::wait) as a frame ends, however it ends.
struct WaitIndirect {
  const IndirectLight* indirect;
  ~WaitIndirect() {
    if (indirect) indirect->wait();
  }
};

// The radiance target of `gbuffer` read back, rows top-down. Throws gl::GlError on a driver
// error the frame left.
Image readRadiance(const GBuffer& gbuffer) {
  Image image;
  image.width = gbuffer.width();
  image.height = gbuffer.height();
  std::vector<float> rows(std::size_t(image.width) * image.height * 4);
  glBindFramebuffer(GL_FRAMEBUFFER, gbuffer.lightingFramebuffer().id());
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glReadPixels(0, 0, image.width, image.height, GL_RGBA, GL_FLOAT, rows.data());
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  const GLenum error = glGetError();
  if (error != GL_NO_ERROR) {
    char message[64];
    std::snprintf(message, sizeof message, "OpenGL error 0x%04X while rendering", unsigned(error));
    throw gl::GlError(message);
  }
  // GL's rows run bottom-up; images run top-down.
  image.rgba.resize(rows.size());
  const std::size_t stride = std::size_t(image.width) * 4;
  for (int y = 0; y < image.height; ++y) {
    std::copy_n(&rows[std::size_t(image.height - 1 - y) * stride], stride, &image.rgba[y * stride]);
  }
  return image;
}

}  // namespace

Method parseMethod(const std::string& name) {
  if (name == "reference") return Method::Reference;
  if (name == "lightcuts") return Method::Lightcuts;
  if (name == "lightcuts-distance") return Method::LightcutsDistance;
  if (name == "octree") return Method::Octree;
  if (name == "auto") return Method::Auto;
  throw Error("unknown method '" + name +
              "', expected reference, lightcuts, lightcuts-distance, octree or auto");
}

const char* methodName(Method m) {
  switch (m) {
    case Method::Lightcuts:
      return "lightcuts";
    case Method::LightcutsDistance:
      return "lightcuts-distance";
    case Method::Octree:
      return "octree";
    case Method::Auto:
      return "auto";
    default:
      return "reference";
  }
}

Renderer::Renderer(const Scene& scene, const std::vector<Light>& lights, int width, int height,
                   Method method, BakedLights baked)
    : scene_(scene), gpu_(scene, lights), gbuffer_(width, height) {
  if (method == Method::Auto) throw Error("auto is resolved before a renderer is made");
  if (method != Method::Reference) {
    glFinish();
    const auto start = std::chrono::steady_clock::now();
    if (method == Method::Octree) {
      if (!baked.octree) throw Error("octree needs the lights' baked octree");
      octree_ = std::make_unique<OctreeMethod>(*baked.octree, lights);
    } else {
      PackedTrees waited;
      if (!baked.trees && baked.pendingTrees) {
        waited = baked.pendingTrees->get();
        baked.trees = &waited;
      }
      if (!baked.trees)
        throw Error(std::string(methodName(method)) + " needs the lights' baked trees");
      // A renderer takes the trees it is given: a second one given the same has none left.
      const PackedTrees& t = *baked.trees;
      if (t.words.empty() && (t.leaves[0] > 0 || t.leaves[1] > 0 || t.leaves[2] > 0))
        throw Error("the lights' baked trees were already taken by another renderer");
      distance_ = method == Method::LightcutsDistance;
      lightcuts_ =
          std::make_unique<LightcutsMethod>(std::move(*baked.trees), lights, gbuffer_, distance_);
    }
    glFinish();
    uploadMs_ =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  }
}

void warmUpGeometryPass(Aov aov) {
  Scene scene;
  Primitive triangle;
  triangle.positions = {{-1, -1, 0}, {1, -1, 0}, {0, 1, 0}};
  triangle.normals.assign(3, {0, 0, 1});
  triangle.texcoords = {{0, 0}, {1, 0}, {0.5f, 1}};
  triangle.indices = {0, 1, 2};
  scene.meshes.push_back({{triangle}});
  scene.instances.push_back({0, glm::mat4(1.0f)});
  Camera camera;
  camera.world = glm::translate(glm::mat4(1.0f), glm::vec3(0, 0, 3));
  const int size = 8;
  FrameSettings settings;
  settings.aov = aov;
  Renderer(scene, {}, size, size, Method::Reference).render(makeView(camera, size, size), settings);
}

void Renderer::replaceLights(const std::vector<Light>& lights) {
  assert(!lightcuts_ && !octree_ &&
         "trees and octrees are built from the lights given at construction");
  gpu_.replaceLights(lights);
}

void Renderer::moveLights(const std::vector<Light>& lights, const std::vector<int>& changed,
                          const BakeOptions& options) {
  gpu_.replaceLights(lights);
  if (!indirectLights_.empty()) indirectLights_ = lights;
  if (octree_) {
    if (!dynamic_ || !dynamic_->update(lights, changed))
      dynamic_ = std::make_unique<DynamicOctree>(lights, scene_, options.octree);
    octree_->replace(dynamic_->packed(), lights);
  } else if (lightcuts_) {
    if (!trees_ || !trees_->update(lights, changed))
      trees_ = std::make_unique<DynamicTrees>(lights, options.trees);
    // A new method: the trees uploaded anew, and no cut kept from before the move.
    lightcuts_ = std::make_unique<LightcutsMethod>(trees_->packed(), lights, gbuffer_, distance_);
  }
}

const GeometryPass& Renderer::aovPass(Aov aov) {
  if (!aovGeometry_ || aovGeometry_->aov() != aov)
    aovGeometry_ = std::make_unique<GeometryPass>(aov);
  return *aovGeometry_;
}

std::vector<bool> rowsLit(int height, int rowBandStride) {
  std::vector<bool> rows(std::size_t(std::max(height, 0)));
  // Bands count from the bottom row, as GL's scissor does; images run top-down.
  for (int y = 0; y < height; ++y)
    rows[std::size_t(height - 1 - y)] = (y / kRowBand) % std::max(rowBandStride, 1) == 0;
  return rows;
}

int Renderer::lightReference(const View& view, const FrameSettings& settings) {
  if (settings.rowBandStride <= 1)
    return reference_.light(gpu_, gbuffer_, view, settings.lightsPerPass);
  const int bandRows = kRowBand * settings.rowBandStride;
  // As many lights per pass as the lit pixels allow.
  const int litPixels =
      gbuffer_.width() * ((gbuffer_.height() + bandRows - 1) / bandRows) * kRowBand;
  const int perPass = settings.lightsPerPass > 0 ? settings.lightsPerPass
                                                 : ReferenceMethod::lightsPerPass(litPixels);
  glEnable(GL_SCISSOR_TEST);
  int passes = 0;
  for (int y = 0; y < gbuffer_.height(); y += bandRows) {
    glScissor(0, y, gbuffer_.width(), kRowBand);
    passes += reference_.light(gpu_, gbuffer_, view, perPass);
  }
  glDisable(GL_SCISSOR_TEST);
  return passes;
}

void Renderer::beginIndirect(const View& view, const IndirectSettings& settings) {
  if (!indirect_ || indirect_->rsmSize() != settings.rsmSize)
    indirect_ = std::make_unique<IndirectLight>(settings.rsmSize);
  indirect_->begin(gbuffer_, scene_.bounds(), view, indirectLights_, settings);
}

void Renderer::lightIndirect(const View& view, const IndirectSettings& settings,
                             FrameStats* stats) {
  const IndirectStats indirect =
      indirect_->light(scene_, gpu_, geometry_, gbuffer_, view, indirectLights_, settings);
  if (stats) stats->indirect = indirect;
  glBindVertexArray(emptyVao_.id());
}

Image Renderer::render(const View& view, const FrameSettings& settings, FrameStats* stats) {
  glFinish();
  const auto start = std::chrono::steady_clock::now();
  int passes = 0;
  double statsMs = 0.0;
  if (settings.aov != Aov::None) {
    aovPass(settings.aov).draw(scene_, gpu_, gbuffer_, view, settings.ambient, GeometryPass::kAll);
  } else {
    geometry_.draw(scene_, gpu_, gbuffer_, view, settings.ambient);
    // The indirect light's CPU work runs beside the direct light's; should the frame end
    // early, its thread ends before the frame does (it reads indirectLights_).
    const bool indirect = settings.indirect.mode != Indirect::None;
    if (indirect) beginIndirect(view, settings.indirect);
    const WaitIndirect waitIndirect{indirect ? indirect_.get() : nullptr};
    glBindVertexArray(emptyVao_.id());
    auto light = [&] {
      if (lightcuts_) {
        lightcuts_->light(gpu_, gbuffer_, view, settings.lightcuts);
        ++passes;
      } else if (octree_) {
        passes += octree_->light(gpu_, gbuffer_, view, settings.lightsPerPass);
      } else {
        passes += lightReference(view, settings);
      }
    };
    light();
    if (indirect) lightIndirect(view, settings.indirect, stats);
    // The opaque frame's cut statistics, before blended layers light the G-buffer again.
    if (stats && lightcuts_ && settings.readCutStats) stats->cuts = lightcuts_->cutStats();
    if (stats && octree_ && settings.octreeStats) {
      // On the CPU: not part of the frame's time.
      glFinish();
      const auto statsStart = std::chrono::steady_clock::now();
      stats->octree = octree_->frameStats(gbuffer_);
      statsMs =
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - statsStart)
              .count();
    }
    if (gpu_.hasBlended()) {
      if (!blend_) blend_ = std::make_unique<BlendPass>(gbuffer_.width(), gbuffer_.height());
      blend_->draw(scene_, gpu_, gbuffer_, view, settings.ambient, geometry_, [&] {
        glBindVertexArray(emptyVao_.id());
        light();
      });
    }
    glBindVertexArray(0);
  }
  glFinish();
  const auto end = std::chrono::steady_clock::now();

  Image image = readRadiance(gbuffer_);
  if (settings.aov != Aov::None) image.values = aovChannel(settings.aov).values;
  if (stats) {
    // An AOV frame ran no lightcuts pass: it has no cut figures.
    const LightcutsMethod* cuts = settings.aov == Aov::None ? lightcuts_.get() : nullptr;
    stats->renderMs = std::chrono::duration<double, std::milli>(end - start).count() - statsMs;
    stats->lightingPasses = passes;
    stats->cutMs = cuts ? cuts->cutMs() : 0.0;
    stats->cutsMade = cuts ? cuts->cutsMade() : 0;
    stats->cutsKept = cuts ? cuts->cutsKept() : 0;
  }
  return image;
}

}  // namespace manylight
