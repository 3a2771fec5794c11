// SceneRenderer: transform, rasterise with an unlit textured material, resolve.
#include <chrono>

#include "tessera/render.h"

namespace tessera::render {

raster::DrawCall mesh_draw(const scene::Mesh& mesh, const float* clip, const float* varyings,
                           int varying_count, std::uint32_t primitive_id_base) {
  raster::DrawCall d;
  d.positions = clip;
  d.varyings = varyings;
  d.varying_count = varying_count;
  d.vertex_count = mesh.positions.size();
  d.indices = mesh.indices.data();
  d.index_count = mesh.indices.size();
  d.cull = raster::CullMode::none;
  d.primitive_id_base = primitive_id_base;
  return d;
}

Result<std::vector<texture::Texture>> build_scene_textures(const scene::Scene& scene,
                                                           const Parallel& parallel) {
  std::vector<texture::Texture> textures;
  textures.reserve(scene.textures.size());
  for (const scene::Texture& t : scene.textures) {
    texture::TextureOptions o;
    o.srgb = t.srgb;
    o.threads = parallel.threads;
    Result<texture::Texture> tex = texture::Texture::from_rgba8(t.image, o);
    if (!tex) return tex.status();
    textures.push_back(std::move(*tex));
  }
  return textures;
}

SceneRenderer::~SceneRenderer() = default;

Result<std::unique_ptr<SceneRenderer>> SceneRenderer::create(const scene::Scene& scene,
                                                             const Parallel& parallel) {
  std::unique_ptr<SceneRenderer> r(new SceneRenderer());
  r->scene_ = &scene;
  Result<std::vector<texture::Texture>> textures = build_scene_textures(scene, parallel);
  if (!textures) return textures.status();
  r->textures_ = std::move(*textures);
  // UVs do not change between frames.
  for (const scene::Mesh& m : scene.meshes) {
    std::vector<float> uv(m.uvs.size() * 2);
    for (std::size_t i = 0; i < m.uvs.size(); ++i) {
      uv[2 * i] = m.uvs[i].x;
      uv[2 * i + 1] = m.uvs[i].y;
    }
    r->varyings_.push_back(std::move(uv));
    r->clip_.emplace_back(m.positions.size() * 4);
  }
  return r;
}

Result<Frame> SceneRenderer::render(const scene::Camera& camera, const FrameOptions& options) {
  const scene::Scene& sc = *scene_;
  if (fb_.width() != options.width || fb_.height() != options.height ||
      fb_.msaa() != options.msaa || fb_.ssaa() != options.ssaa) {
    raster::FrameBufferDesc desc;
    desc.width = options.width;
    desc.height = options.height;
    desc.msaa = options.msaa;
    desc.ssaa = options.ssaa;
    desc.channels = 4;
    Result<raster::FrameBuffer> fb = raster::FrameBuffer::create(desc);
    if (!fb) return fb.status();
    fb_ = std::move(*fb);
  }
  raster::RasterOptions ro;
  ro.threads = options.threads;
  rasteriser_.set_options(ro);

  Frame frame;
  auto t0 = std::chrono::steady_clock::now();
  const Mat4 vp = camera.view_projection(float(options.width) / float(options.height));
  for (std::size_t mi = 0; mi < sc.meshes.size(); ++mi) {
    const scene::Mesh& m = sc.meshes[mi];
    std::vector<float>& clip = clip_[mi];
    parallel_for(0, std::int64_t(m.positions.size()), 4096,
                 [&](std::int64_t b, std::int64_t e) {
                   for (std::int64_t i = b; i < e; ++i) {
                     const Vec3& p = m.positions[std::size_t(i)];
                     const Vec4 c = vp * Vec4{p.x, p.y, p.z, 1.0f};
                     float* o = &clip[std::size_t(i) * 4];
                     o[0] = c.x;
                     o[1] = c.y;
                     o[2] = c.z;
                     o[3] = c.w;
                   }
                 },
                 {options.threads});
  }
  frame.ms_transform = ms_since(t0);

  texture::SamplerState sampler;
  sampler.filter = options.filter == Filter::aniso16 ? texture::TextureFilter::anisotropic
                                                     : texture::TextureFilter::trilinear;
  sampler.max_aniso = 16;
  std::vector<raster::DrawCall> draws;
  draws.reserve(sc.meshes.size());
  std::uint32_t prim_base = 0;
  for (std::size_t mi = 0; mi < sc.meshes.size(); ++mi) {
    const scene::Mesh& m = sc.meshes[mi];
    const scene::Material& mat = sc.materials[std::size_t(m.material)];
    raster::DrawCall d = mesh_draw(m, clip_[mi].data(), varyings_[mi].data(), 2, prim_base);
    prim_base += std::uint32_t(m.triangle_count());
    const texture::Texture* tex =
        (options.shading == Shading::textured && mat.base_color_texture >= 0)
            ? &textures_[std::size_t(mat.base_color_texture)]
            : nullptr;
    const std::array<float, 4> base =
        options.shading == Shading::flat
            ? std::array<float, 4>{1, 1, 1, 1}
            : std::array<float, 4>{mat.base_color[0], mat.base_color[1], mat.base_color[2], 1};
    // One call per 2x2 quad; each active lane is shaded exactly as a per-pixel shader would
    // (Texture::sample4 is bit-identical to a `sample` per lane).
    d.quad_shader = [tex, base, sampler](const raster::ShadeInput* lanes, std::uint32_t active,
                                         float* out) {
      std::array<std::array<float, 4>, 4> texel;
      if (tex) {
        std::array<texture::Uv, 4> uv{};
        std::array<texture::UvGradients, 4> g{};
        for (int lane = 0; lane < 4; ++lane) {
          if (!(active >> lane & 1u)) continue;
          const raster::ShadeInput& in = lanes[lane];
          uv[std::size_t(lane)] = {in.varyings[0], in.varyings[1]};
          g[std::size_t(lane)] = {in.ddx[0], in.ddx[1], in.ddy[0], in.ddy[1]};
        }
        tex->sample4(sampler, uv, g, active, texel);
      }
      for (int lane = 0; lane < 4; ++lane) {
        if (!(active >> lane & 1u)) continue;
        float* o = out + lane * raster::kMaxChannels;
        std::array<float, 4> c = base;
        if (tex) {
          for (int k = 0; k < 3; ++k) c[std::size_t(k)] *= texel[std::size_t(lane)][std::size_t(k)];
        }
        o[0] = c[0];
        o[1] = c[1];
        o[2] = c[2];
        o[3] = 1.0f;
      }
    };
    draws.push_back(std::move(d));
  }
  raster::ClearValues clear;
  for (int k = 0; k < 4; ++k) clear.value[std::size_t(k)] = kBackground[std::size_t(k)];
  t0 = std::chrono::steady_clock::now();
  Result<raster::RasterStats> stats = rasteriser_.render(fb_, draws, &clear);
  if (!stats) return stats.status();
  frame.ms_raster = ms_since(t0);
  frame.stats = *stats;
  t0 = std::chrono::steady_clock::now();
  frame.image = raster::resolve_srgb8(fb_, {options.threads});
  frame.ms_resolve = ms_since(t0);
  return frame;
}

}  // namespace tessera::render
