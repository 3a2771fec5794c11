// DeferredRenderer: textures, and the geometry pass into the enlarged G-buffer.
#include <cmath>

#include "deferred_internal.h"
#include "tessera/render.h"

namespace tessera::deferred {

DeferredRenderer::~DeferredRenderer() = default;

Result<std::unique_ptr<DeferredRenderer>> DeferredRenderer::create(const scene::Scene& scene,
                                                                   const Parallel& parallel) {
  std::unique_ptr<DeferredRenderer> r(new DeferredRenderer());
  r->scene_ = &scene;
  r->threads_ = parallel.threads;
  Result<std::vector<texture::Texture>> textures = render::build_scene_textures(scene, parallel);
  if (!textures) return textures.status();
  r->textures_ = std::move(*textures);
  for (const scene::Material& m : scene.materials) {
    MaterialInfo mi;
    mi.base = {m.base_color[0], m.base_color[1], m.base_color[2]};
    if (m.base_color_texture >= 0 && std::size_t(m.base_color_texture) < r->textures_.size()) {
      mi.texture = &r->textures_[std::size_t(m.base_color_texture)];
    }
    r->materials_.push_back(mi);
  }
  for (const scene::Mesh& m : scene.meshes) {
    r->clip_.emplace_back(m.positions.size() * 4);
    std::vector<float> v(m.positions.size() * 6);
    for (std::size_t i = 0; i < m.positions.size(); ++i) {
      float* o = &v[i * 6];
      o[1] = m.normals[i].x;
      o[2] = m.normals[i].y;
      o[3] = m.normals[i].z;
      o[4] = m.uvs[i].x;
      o[5] = m.uvs[i].y;
    }
    r->varyings_.push_back(std::move(v));
  }
  return r;
}

Status DeferredRenderer::render_gbuffer(const scene::Camera& camera, int width, int height, int m,
                                        GBuffer& out, raster::RasterStats* stats) {
  if (m < 1 || m > 8) {
    return Status::error(ErrorCode::invalid_argument,
                         "deferred: window size m must be in [1, 8], got " + std::to_string(m));
  }
  if (out.fb.width() != width || out.fb.height() != height || out.fb.ssaa() != m ||
      out.fb.channels() != kGBufferChannels) {
    raster::FrameBufferDesc desc;
    desc.width = width;
    desc.height = height;
    desc.ssaa = m;
    desc.msaa = 1;
    desc.channels = kGBufferChannels;
    Result<raster::FrameBuffer> fb = raster::FrameBuffer::create(desc);
    if (!fb) return fb.status();
    out.fb = std::move(*fb);
  }
  out.m = m;
  const GBufferCamera cam = gbuffer_camera(camera, width, height);
  out.aspect = cam.aspect;
  out.tan_half_fov_y = cam.tan_half_fov_y;
  out.inv_view = cam.inv_view;
  out.eye = cam.eye;

  const scene::Scene& sc = *scene_;
  for (std::size_t mi = 0; mi < sc.meshes.size(); ++mi) {
    transform_gbuffer_vertices(cam, sc.meshes[mi].positions, clip_[mi].data(), 4,
                               varyings_[mi].data(), 6, {threads_});
  }

  std::vector<raster::DrawCall> draws;
  draws.reserve(sc.meshes.size());
  std::uint32_t prim_base = 0;
  for (std::size_t mi = 0; mi < sc.meshes.size(); ++mi) {
    const scene::Mesh& mesh = sc.meshes[mi];
    raster::DrawCall d =
        render::mesh_draw(mesh, clip_[mi].data(), varyings_[mi].data(), 6, prim_base);
    prim_base += std::uint32_t(mesh.triangle_count());
    const float material = float(mesh.material);
    d.shader = [material](const raster::ShadeInput& in, float* o) {
      const float* v = in.varyings;
      o[kChDepth] = v[0];
      o[kChNormal] = v[1];
      o[kChNormal + 1] = v[2];
      o[kChNormal + 2] = v[3];
      o[kChMaterial] = material;
      o[kChUv] = v[4];
      o[kChUv + 1] = v[5];
      o[kChDuvDx] = in.ddx[4];
      o[kChDuvDx + 1] = in.ddx[5];
      o[kChDuvDy] = in.ddy[4];
      o[kChDuvDy + 1] = in.ddy[5];
    };
    draws.push_back(std::move(d));
  }
  raster::ClearValues clear;
  clear.value[kChDepth] = camera.far_z;
  clear.value[kChMaterial] = -1.0f;
  raster::RasterOptions ro;
  ro.threads = threads_;
  rasteriser_.set_options(ro);
  Result<raster::RasterStats> st = rasteriser_.render(out.fb, draws, &clear);
  if (!st) return st.status();
  if (stats) *stats = *st;
  return Status::success();
}

}  // namespace tessera::deferred
