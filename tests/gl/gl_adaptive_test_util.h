// Shared by gl_adaptive_test.cpp and gl_adaptive_budget_test.cpp: textures in and out, the
// DeferredRenderer fixture whose G-buffer and Blinn-Phong feed the component, a synthetic
// G-buffer with an analytic hook.
#pragma once

#include <EGL/egl.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <memory>
#include <numeric>
#include <optional>
#include <string>
#include <vector>

#include "gl/gl_api.h"
#include "gl_test_fixture.h"
#include "tessera/deferred.h"
#include "tessera/gl.h"
#include "tessera/gl_adaptive.h"
#include "tessera/gl_deferred.h"
#include "tessera/scene.h"
#include "test_support.h"

namespace tessera::aa_test {

using namespace gl::api;
namespace d = deferred;

inline PFNGLGETINTEGERI_VPROC get_integeri_v() {
  return reinterpret_cast<PFNGLGETINTEGERI_VPROC>(eglGetProcAddress("glGetIntegeri_v"));
}

/// A GL_TEXTURE_2D of `format` holding `texels` (RGBA floats per texel, w x h).
inline gl::Object make_texture(GLenum format, int w, int h, const std::vector<float>& texels,
                               GLenum upload_format = GL_RGBA) {
  gl::Object t = gl::create_object(gl::ObjectType::texture, GL_TEXTURE_2D);
  glTextureStorage2D(t.get(), 1, format, w, h);
  if (!texels.empty()) {
    glTextureSubImage2D(t.get(), 0, 0, 0, w, h, upload_format, GL_FLOAT, texels.data());
  }
  return t;
}

inline std::vector<float> read_rgba32f(std::uint32_t tex) {
  Result<ImageRGBAF> img = gl::read_texture_rgbaf(tex);
  EXPECT_TRUE(img.ok()) << img.status().message;
  return img ? img->pixels : std::vector<float>{};
}

inline std::vector<std::uint8_t> read_counts(std::uint32_t tex, int w, int h) {
  std::vector<std::uint8_t> c(std::size_t(w) * std::size_t(h));
  glGetTextureSubImage(tex, 0, 0, 0, 0, w, h, 1, GL_RED_INTEGER, GL_UNSIGNED_BYTE,
                       GLsizei(c.size()), c.data());
  return c;
}

/// Rgb of an RGBA image equal bit for bit to gl::DeferredRenderer's (alpha: 1 in both).
inline std::size_t differing_pixels(const std::vector<float>& a, const ImageRGBAF& b) {
  std::size_t n = 0;
  for (std::size_t i = 0; i < b.pixel_count(); ++i) {
    for (int c = 0; c < 4; ++c) {
      if (std::memcmp(&a[i * 4 + std::size_t(c)], &b.pixels[i * 4 + std::size_t(c)], 4) != 0) {
        ++n;
        break;
      }
    }
  }
  return n;
}

class GlAdaptive : public test::GlTest {
 protected:
  void TearDown() override {
    deferred_.reset();
    test::GlTest::TearDown();
  }

  // DeferredRenderer on the built-in scene, its G-buffer at w x h x m, its adaptive image.
  void use_deferred(int w, int h, int m) {
    scene_ = std::make_unique<scene::Scene>(scene::builtin_scene());
    camera_ = scene::orbit_camera(*scene_, 1, 8);
    gl::DeferredRendererOptions o;
    o.glsl_dir = TESSERA_GLSL_DIR;
    Result<std::unique_ptr<gl::DeferredRenderer>> g = gl::DeferredRenderer::create(*scene_, o);
    ASSERT_TRUE(g.ok()) << g.status().message;
    deferred_ = std::move(*g);
    shading_ = d::scene_shading(*scene_, 8, &camera_);
    ASSERT_TRUE(deferred_->render_gbuffer(camera_, w, h, m).ok());
    w_ = w;
    h_ = h;
    m_ = m;
  }
  // After a gl::DeferredRenderer shade call its G-buffer sits on units 0..2 and its texture arrays
  // on units 3..: the component reads the same textures, the hook shades through the same bindings.
  std::array<std::uint32_t, 4> deferred_textures(int* classes) {
    std::array<std::uint32_t, 4> t{};
    GLint active = 0;
    glGetIntegerv(GL_ACTIVE_TEXTURE, &active);
    for (int u = 0; u < 3; ++u) {
      glActiveTexture(GLenum(GL_TEXTURE0 + u));
      GLint name = 0;
      glGetIntegerv(GL_TEXTURE_BINDING_2D, &name);
      t[std::size_t(u)] = std::uint32_t(name);
    }
    *classes = 0;
    for (int u = 3; u < 11; ++u) {
      glActiveTexture(GLenum(GL_TEXTURE0 + u));
      GLint name = 0;
      glGetIntegerv(GL_TEXTURE_BINDING_2D_ARRAY, &name);
      if (name == 0) break;
      ++*classes;
    }
    glActiveTexture(GLenum(active));
    return t;
  }
  // DeferredRenderer's 1 spp (one_) and adaptive (ad_) images of the use_deferred G-buffer,
  // and the frame a component reads it from: frame_.gbuffer the textures the adaptive shade left
  // bound, classes_ its texture arrays.
  void shade_default_and_adaptive() {
    Result<deferred::ShadeResult> one = deferred_->shade_default(shading_);
    ASSERT_TRUE(one.ok()) << one.status().message;
    Result<deferred::ShadeResult> ad = deferred_->shade_adaptive(shading_, AdaptiveThresholds{});
    ASSERT_TRUE(ad.ok()) << ad.status().message;
    one_ = std::move(*one);
    ad_ = std::move(*ad);
    frame_ = {};
    frame_.gbuffer = deferred_textures(&classes_);
  }
  gl::AdaptiveSupersamplerOptions deferred_options(int classes) const {
    gl::AdaptiveSupersamplerOptions o;
    o.width = w_;
    o.height = h_;
    o.m = m_;
    o.output = AdaptiveOutputFormat::rgba32f;
    o.sample_count_texture = true;
    o.glsl_dir = TESSERA_GLSL_DIR;
    o.layout = deferred_gbuffer_layout();
    o.hook.name = "blinn_phong_hook";
    o.hook.source = "#define TESSERA_DEFERRED_CLASSES " + std::to_string(std::max(classes, 1)) +
                    "\n#include \"deferred_shading.glsl\"\n"
                    "vec4 tessera_shade_sample(ivec2 g, float footprint) {\n"
                    "  return vec4(tessera_shade(g, footprint), 1.0);\n}\n";
    return o;
  }

  std::unique_ptr<scene::Scene> scene_;
  scene::Camera camera_;
  std::unique_ptr<gl::DeferredRenderer> deferred_;
  d::ShadingOptions shading_;
  int w_ = 0, h_ = 0, m_ = 0;
  std::optional<deferred::ShadeResult> one_, ad_;
  gl::AdaptiveFrame frame_;
  int classes_ = 0;
};

// A synthetic G-buffer: slot 0 = (depth, normal), slot 1 = (id, 0, 0, 0), RGBA32F.
struct Synthetic {
  gl::Object t0, t1;
  gl::AdaptiveFrame frame;
};
template <class Depth>
Synthetic synthetic(int w, int h, int m, Depth depth) {
  std::vector<float> a, b;
  for (int gy = 0; gy < h * m; ++gy) {
    for (int gx = 0; gx < w * m; ++gx) {
      a.insert(a.end(), {depth(gx, gy), 0.0f, 0.0f, 1.0f});
      b.insert(b.end(), {0.0f, 0.0f, 0.0f, 0.0f});
    }
  }
  Synthetic s;
  s.t0 = make_texture(GL_RGBA32F, w * m, h * m, a);
  s.t1 = make_texture(GL_RGBA32F, w * m, h * m, b);
  s.frame.gbuffer = {s.t0.get(), s.t1.get(), 0, 0};
  return s;
}

inline gl::AdaptiveSupersamplerOptions synthetic_options(int w, int h, int m) {
  gl::AdaptiveSupersamplerOptions o;
  o.width = w;
  o.height = h;
  o.m = m;
  o.output = AdaptiveOutputFormat::rgba32f;
  o.sample_count_texture = true;
  o.glsl_dir = TESSERA_GLSL_DIR;
  o.layout.depth = {0, "r"};
  o.layout.normal = {0, "gba"};
  o.layout.id = {1, "r"};
  o.hook.name = "analytic_hook";
  // A colour per grid texel, HDR values included.
  o.hook.source =
      "vec4 tessera_shade_sample(ivec2 g, float footprint) {\n"
      "  return vec4(float(g.x) * 4.0, float(g.y) * 0.25 + 0.1, float(g.x + g.y) * 2.0, 1.0);\n"
      "}\n";
  return o;
}

inline std::vector<int> extra_of(const std::vector<std::uint8_t>& counts) {
  std::vector<int> k;
  for (std::uint8_t c : counts) k.push_back(int(c) - 1);
  return k;
}

}  // namespace tessera::aa_test
