#include "test_support.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include "tessera/image_ops.h"
#include "tessera/metrics.h"

namespace tessera::test {

namespace fs = std::filesystem;

std::optional<fs::path> shared_data_dir() {
  fs::path p;
  if (const char* env = std::getenv("TESSERA_SHARED")) {
    p = fs::path(env) / "data";
  } else {
    p = fs::path(TESSERA_SOURCE_DIR) / ".." / "shared" / "data";
  }
  std::error_code ec;
  if (fs::is_directory(p, ec)) return fs::weakly_canonical(p);
  return std::nullopt;
}

std::optional<fs::path> pvrtextool() {
  fs::path p = TESSERA_PVRTEXTOOL_PATH;
  if (const char* env = std::getenv("TESSERA_PVRTEXTOOL")) p = env;
  std::error_code ec;
  if (!p.empty() && fs::is_regular_file(p, ec)) return p;
  return std::nullopt;
}

fs::path temp_dir(const std::string& name) {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::string leaf = name;
  if (info) leaf = std::string(info->test_suite_name()) + "." + info->name() + "." + name;
  fs::path p = fs::path(TESSERA_BINARY_DIR) / "test-tmp" / leaf;
  std::error_code ec;
  fs::remove_all(p, ec);
  fs::create_directories(p);
  return p;
}

fs::path artifacts_dir() {
  fs::path p = fs::path(TESSERA_BINARY_DIR) / "test-artifacts";
  fs::create_directories(p);
  return p;
}

Result<faces::FaceTextureSet> baked_texture_set(const faces::FaceScene& scene) {
  Result<std::vector<faces::FaceAdjacency>> adj = faces::build_adjacency(scene.mesh);
  if (!adj) return adj.status();
  return faces::FaceTextureSet::create(faces::bake_faces(scene), std::move(*adj));
}

faces::FaceTextureSet figure1_texture_set(int ground, int character) {
  faces::Figure1Options o;
  o.ground = ground;
  o.character = character;
  Result<faces::FaceTextureSet> set = baked_texture_set(faces::figure1_scene(o));
  if (!set) {
    ADD_FAILURE() << "figure1_texture_set(" << ground << ", " << character
                  << "): " << set.status().message;
    return {};
  }
  return std::move(*set);
}

double psnr_srgb8(const ImageRGBAF& a, const ImageRGBAF& b) {
  metrics::CompareOptions o;
  o.compute_ssim = false;
  Result<metrics::ImageComparison> c = metrics::compare_images(to_srgb8(a), to_srgb8(b), o);
  EXPECT_TRUE(c) << c.status().message;
  return c ? c->psnr_rgb : 0.0;
}

}  // namespace tessera::test
