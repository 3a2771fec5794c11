// The camera set-up of a G-buffer pass, shared by the CPU renderer (gbuffer.cpp) and its GL
// twin (src/gl/deferred_renderer_scene.cpp): matrices, reconstruction constants, vertex transforms.
#include <cmath>
#include <numbers>

#include "tessera/deferred.h"

namespace tessera::deferred {

GBufferCamera gbuffer_camera(const scene::Camera& camera, int width, int height) {
  GBufferCamera c;
  c.aspect = float(width) / float(height);
  c.tan_half_fov_y = std::tan(camera.fov_y_degrees * std::numbers::pi_v<float> / 360.0f);
  c.view = camera.view();
  c.inv_view = inverse(c.view);
  c.view_projection = camera.projection(c.aspect) * c.view;
  c.eye = camera.eye;
  return c;
}

void transform_gbuffer_vertices(const GBufferCamera& camera, std::span<const Vec3> positions,
                                float* clip, std::size_t clip_stride, float* depth,
                                std::size_t depth_stride, const Parallel& parallel) {
  parallel_for(
      0, std::int64_t(positions.size()), 4096,
      [&](std::int64_t b, std::int64_t e) {
        for (std::int64_t i = b; i < e; ++i) {
          const Vec3& p = positions[std::size_t(i)];
          const Vec4 c = camera.view_projection * Vec4{p.x, p.y, p.z, 1.0f};
          float* o = clip + std::size_t(i) * clip_stride;
          o[0] = c.x;
          o[1] = c.y;
          o[2] = c.z;
          o[3] = c.w;
          const Vec4 v = camera.view * Vec4{p.x, p.y, p.z, 1.0f};
          depth[std::size_t(i) * depth_stride] = -v.z;  // linear view depth
        }
      },
      parallel);
}

}  // namespace tessera::deferred
