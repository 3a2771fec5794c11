// Helpers shared by the test programs: where the shared data and the oracle are, temporary
// folders, and writing diff images on failure; the skip-or-fail rule is test_require.h.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "tessera/core.h"
#include "tessera/faces.h"
#include "test_require.h"  // required(), TESSERA_SKIP_OR_FAIL, TESSERA_SKIP_WITHOUT_AVX2

namespace tessera::test {

/// ../shared/data next to the source tree (or $TESSERA_SHARED/data); nullopt when absent.
std::optional<std::filesystem::path> shared_data_dir();
/// Path of PVRTexToolCLI configured at build time (or $TESSERA_PVRTEXTOOL); nullopt if missing.
std::optional<std::filesystem::path> pvrtextool();

/// A fresh, empty folder under the build tree for this test (removed at the next run).
std::filesystem::path temp_dir(const std::string& name);
/// Folder in the build tree where tests write diff images when they fail.
std::filesystem::path artifacts_dir();

/// The per-face texture set of `scene`: its faces baked (faces::bake_faces) with their
/// adjacency; the status says which step failed.
Result<faces::FaceTextureSet> baked_texture_set(const faces::FaceScene& scene);
/// The baked texture set of faces::figure1_scene with a `ground` x `ground` ground plane and a
/// 6 x `character` x `character` character (the GL tests' small scenes). When baking fails it
/// records a test failure with the status and returns an empty set.
faces::FaceTextureSet figure1_texture_set(int ground, int character);

/// The RGB PSNR (dB) of two linear-RGB frames as 8-bit sRGB (to_srgb8, metrics::compare_images
/// without SSIM), the measure the GPU-vs-CPU tests bound; a failed comparison (different sizes)
/// is a gtest failure and returns 0.
double psnr_srgb8(const ImageRGBAF& a, const ImageRGBAF& b);

/// A w x h `Image` (ImageRGBA8 or ImageRGBAF) of one colour.
template <class Image, class T>
Image solid_image(int w, int h, T r, T g, T b, T a) {
  Image img(w, h);
  for (std::size_t i = 0; i < img.pixel_count(); ++i) {
    img.pixels[i * 4 + 0] = r;
    img.pixels[i * 4 + 1] = g;
    img.pixels[i * 4 + 2] = b;
    img.pixels[i * 4 + 3] = a;
  }
  return img;
}

/// A w x h 8-bit image of one colour.
inline ImageRGBA8 solid_rgba8(int w, int h, std::uint8_t r, std::uint8_t g, std::uint8_t b,
                              std::uint8_t a = 255) {
  return solid_image<ImageRGBA8>(w, h, r, g, b, a);
}

/// True for an OpenGL renderer that filters textures in float (Mesa's software rasterisers),
/// where GL lookups match tessera's sampler to float rounding. Hardware texture units weight
/// texels in fixed point (Direct3D requires 8 bits of sub-texel precision), so the GL tests use
/// looser, stated bounds there.
inline bool float_texture_filtering(const std::string& gl_renderer) {
  return gl_renderer.find("llvmpipe") != std::string::npos ||
         gl_renderer.find("softpipe") != std::string::npos;
}

}  // namespace tessera::test

/// Skips the current test with a message when the shared data folder is absent (fails it when
/// the run requires "shared").
#define TESSERA_REQUIRE_SHARED_DATA(var)                                                  \
  auto var##_opt = ::tessera::test::shared_data_dir();                                    \
  if (!var##_opt) TESSERA_SKIP_OR_FAIL("shared", "../shared/data not present; skipping"); \
  const std::filesystem::path var = *var##_opt
