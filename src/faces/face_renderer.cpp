// Driver: rasterising a per-face-textured quad mesh (texture lookup + a light Lambert term),
// and the Mitchell-Netravali-downsampled supersampled reference, rendered in tiles.
#include <algorithm>
#include <chrono>
#include <cmath>

#include "tessera/faces.h"

namespace tessera::faces {

namespace {
constexpr int kVaryings = 5;  // u, v, normal
}  // namespace

float mitchell_netravali(float x, float b, float c) {
  x = std::fabs(x);
  if (x < 1.0f) {
    return ((12 - 9 * b - 6 * c) * x * x * x + (-18 + 12 * b + 6 * c) * x * x + (6 - 2 * b)) / 6.0f;
  }
  if (x < 2.0f) {
    return ((-b - 6 * c) * x * x * x + (6 * b + 30 * c) * x * x + (-12 * b - 48 * c) * x +
            (8 * b + 24 * c)) /
           6.0f;
  }
  return 0.0f;
}

FaceRenderer::~FaceRenderer() = default;

Result<std::unique_ptr<FaceRenderer>> FaceRenderer::create(const FaceScene& scene,
                                                           const FaceTextureSet& textures) {
  if (scene.mesh.face_count() != textures.face_count()) {
    return Status::error(ErrorCode::size_mismatch,
                         scene.name + ": " + std::to_string(scene.mesh.face_count()) +
                             " faces but " + std::to_string(textures.face_count()) +
                             " face textures");
  }
  std::unique_ptr<FaceRenderer> r(new FaceRenderer());
  r->scene_ = &scene;
  r->textures_ = &textures;
  const QuadMesh& m = scene.mesh;
  // Smooth normals: area-weighted face normals summed per position.
  std::vector<Vec3> normals(m.positions.size());
  for (int f = 0; f < m.face_count(); ++f) {
    const auto& q = m.quads[std::size_t(f)];
    const Vec3 n = cross(m.positions[std::size_t(q[2])] - m.positions[std::size_t(q[0])],
                         m.positions[std::size_t(q[3])] - m.positions[std::size_t(q[1])]);
    for (int k = 0; k < 4; ++k)
      normals[std::size_t(q[std::size_t(k)])] = normals[std::size_t(q[std::size_t(k)])] + n;
  }
  const float corner_uv[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  r->varyings_.resize(std::size_t(m.face_count()) * 4 * kVaryings);
  r->clip_.resize(std::size_t(m.face_count()) * 4 * 4);
  for (int f = 0; f < m.face_count(); ++f) {
    for (int k = 0; k < 4; ++k) {
      float* v = &r->varyings_[(std::size_t(f) * 4 + std::size_t(k)) * kVaryings];
      const Vec3 n = normalize(normals[std::size_t(m.quads[std::size_t(f)][std::size_t(k)])]);
      v[0] = corner_uv[k][0];
      v[1] = corner_uv[k][1];
      v[2] = n.x;
      v[3] = n.y;
      v[4] = n.z;
    }
    const std::uint32_t b = std::uint32_t(f) * 4;
    for (std::uint32_t i : {b, b + 1, b + 2, b, b + 2, b + 3}) r->indices_.push_back(i);
  }
  return r;
}

Result<FaceFrame> FaceRenderer::render(const scene::Camera& camera, const FaceRenderOptions& o) {
  // The buffer is kept between frames; a new pattern (or a return to the standard one) needs a
  // new buffer as much as a new size or rate does.
  if (fb_.width() != o.width || fb_.height() != o.height || fb_.msaa() != o.msaa ||
      fb_.desc().sample_pattern != o.sample_pattern) {
    raster::FrameBufferDesc desc;
    desc.width = o.width;
    desc.height = o.height;
    desc.msaa = o.msaa;
    desc.channels = 4;
    desc.sample_pattern = o.sample_pattern;
    Result<raster::FrameBuffer> fb = raster::FrameBuffer::create(desc);
    if (!fb) return fb.status();
    fb_ = std::move(*fb);
  }
  raster::RasterOptions ro;
  ro.threads = o.threads;
  rasteriser_.set_options(ro);

  // Clip-space positions, optionally remapped to a sub-rectangle of a larger virtual image.
  const int fw = o.full_width > 0 ? o.full_width : o.width;
  const int fh = o.full_height > 0 ? o.full_height : o.height;
  const Mat4 vp = camera.view_projection(float(fw) / float(fh));
  const float sx = float(fw) / float(o.width), sy = float(fh) / float(o.height);
  const float left = 2.0f * float(o.x0) / float(fw) - 1.0f;
  const float bottom = 1.0f - 2.0f * float(o.y0 + o.height) / float(fh);
  const float ox = -sx * left - 1.0f, oy = -sy * bottom - 1.0f;
  const QuadMesh& m = scene_->mesh;
  for (int f = 0; f < m.face_count(); ++f) {
    for (int k = 0; k < 4; ++k) {
      const Vec3& p = m.positions[std::size_t(m.quads[std::size_t(f)][std::size_t(k)])];
      const Vec4 c = vp * Vec4{p.x, p.y, p.z, 1.0f};
      float* out = &clip_[(std::size_t(f) * 4 + std::size_t(k)) * 4];
      out[0] = sx * c.x + ox * c.w;
      out[1] = sy * c.y + oy * c.w;
      out[2] = c.z;
      out[3] = c.w;
    }
  }

  raster::DrawCall d;
  d.positions = clip_.data();
  d.varyings = varyings_.data();
  d.varying_count = kVaryings;
  d.vertex_count = clip_.size() / 4;
  d.indices = indices_.data();
  d.index_count = indices_.size();
  d.cull = raster::CullMode::back;
  const FaceTextureSet* set = textures_;
  const SampleOptions so = o.sampling;
  const bool shading_only = o.shading_only;
  const int mask_from = o.mask_faces_from;
  const bool face_ids = o.face_ids;
  d.shader = [set, so, shading_only, mask_from, face_ids](const raster::ShadeInput& in,
                                                          float* out) {
    const float* v = in.varyings;
    if (face_ids) {
      out[0] = out[1] = out[2] = float((in.primitive_id >> 1) + 1);
      out[3] = 1.0f;
      return;
    }
    if (shading_only && mask_from >= 0) {
      const float flag = int(in.primitive_id >> 1) >= mask_from ? 1.0f : 0.0f;
      out[0] = out[1] = out[2] = flag;
      out[3] = 1.0f;
      return;
    }
    std::array<float, 4> c = {0.8f, 0.8f, 0.8f, 1.0f};
    if (!shading_only) {
      const int face = int(in.primitive_id >> 1);
      const texture::UvGradients g{in.ddx[0], in.ddx[1], in.ddy[0], in.ddy[1]};
      c = sample_face(*set, face, {v[0], v[1]}, g, so);
    }
    // Very light lighting: ambient + Lambert with one directional light.
    const float nl = (v[2] * 0.42f + v[3] * 0.82f + v[4] * 0.39f) /
                     std::sqrt(v[2] * v[2] + v[3] * v[3] + v[4] * v[4] + 1e-20f);
    const float shade = 0.35f + 0.65f * std::max(nl, 0.0f);
    out[0] = c[0] * shade;
    out[1] = c[1] * shade;
    out[2] = c[2] * shade;
    out[3] = 1.0f;
  };
  raster::ClearValues clear;
  clear.value = {kFaceBackground[0], kFaceBackground[1], kFaceBackground[2], 0.0f};
  FaceFrame frame;
  auto t0 = std::chrono::steady_clock::now();
  Result<raster::RasterStats> stats = rasteriser_.render(fb_, d, &clear);
  if (!stats) return stats.status();
  frame.ms_raster = ms_since(t0);
  frame.stats = *stats;
  t0 = std::chrono::steady_clock::now();
  frame.image = raster::resolve(fb_, {o.threads});
  frame.ms_resolve = ms_since(t0);
  return frame;
}

Result<ImageRGBAF> FaceRenderer::render_reference(const scene::Camera& camera, int width,
                                                  int height, const ReferenceOptions& options) {
  const int factor = options.factor, threads = options.threads, tile = options.tile;
  if (width < 1 || height < 1 || factor < 1 || factor > 16 || tile < 1) {
    return Status::error(ErrorCode::invalid_argument, "reference: bad size or factor");
  }
  ImageRGBAF out(width, height);
  constexpr int kMargin = 2;  // Mitchell-Netravali support, in output pixels
  const int taps = 2 * kMargin * factor;
  // Weights of grid pixel offsets relative to an output pixel's first grid pixel - margin.
  std::vector<float> w(static_cast<std::size_t>(taps));
  float wsum = 0;
  for (int i = 0; i < taps; ++i) {
    const float x = (float(i) + 0.5f) / float(factor) - float(kMargin);
    w[std::size_t(i)] = mitchell_netravali(x);
    wsum += w[std::size_t(i)];
  }
  for (float& x : w) x /= wsum;
  FaceRenderOptions o;
  o.sampling.method = Method::traverse;
  o.sampling.filter = options.filter;
  o.sampling.max_aniso = 16;
  o.msaa = 1;
  o.threads = threads;
  o.full_width = width * factor;
  o.full_height = height * factor;
  for (int ty = 0; ty < height; ty += tile) {
    for (int tx = 0; tx < width; tx += tile) {
      const int tw = std::min(tile, width - tx), th = std::min(tile, height - ty);
      o.width = (tw + 2 * kMargin) * factor;
      o.height = (th + 2 * kMargin) * factor;
      o.x0 = (tx - kMargin) * factor;
      o.y0 = (ty - kMargin) * factor;
      Result<FaceFrame> f = render(camera, o);
      if (!f) return f.status();
      const ImageRGBAF& g = f->image;
      // Horizontal pass: grid rows -> output columns.
      ImageRGBAF hpass(tw, g.height);
      parallel_for(
          0, g.height, 64,
          [&](std::int64_t b, std::int64_t e) {
            for (std::int64_t y = b; y < e; ++y) {
              for (int x = 0; x < tw; ++x) {
                float acc[4] = {0, 0, 0, 0};
                const int g0 = x * factor;  // = (x + margin) * factor - margin * factor
                for (int i = 0; i < taps; ++i) {
                  const float* p = g.at(g0 + i, int(y));
                  for (int k = 0; k < 4; ++k) acc[k] += w[std::size_t(i)] * p[k];
                }
                float* q = hpass.at(x, int(y));
                for (int k = 0; k < 4; ++k) q[k] = acc[k];
              }
            }
          },
          {threads});
      parallel_for(
          0, th, 16,
          [&](std::int64_t b, std::int64_t e) {
            for (std::int64_t y = b; y < e; ++y) {
              for (int x = 0; x < tw; ++x) {
                float acc[4] = {0, 0, 0, 0};
                const int g0 = int(y) * factor;
                for (int i = 0; i < taps; ++i) {
                  const float* p = hpass.at(x, g0 + i);
                  for (int k = 0; k < 4; ++k) acc[k] += w[std::size_t(i)] * p[k];
                }
                float* q = out.at(tx + x, ty + int(y));
                for (int k = 0; k < 4; ++k) q[k] = acc[k];
              }
            }
          },
          {threads});
    }
  }
  return out;
}

}  // namespace tessera::faces
