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
  const std::vector<Vec3> normals = smooth_face_normals(m);
  const float corner_uv[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  r->varyings_.resize(std::size_t(m.face_count()) * 4 * kVaryings);
  r->clip_.resize(std::size_t(m.face_count()) * 4 * 4);
  for (int f = 0; f < m.face_count(); ++f) {
    for (int k = 0; k < 4; ++k) {
      const std::size_t fv = std::size_t(f) * 4 + std::size_t(k);
      float* v = &r->varyings_[fv * kVaryings];
      v[0] = corner_uv[k][0];
      v[1] = corner_uv[k][1];
      v[2] = normals[fv].x;
      v[3] = normals[fv].y;
      v[4] = normals[fv].z;
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
  face_clip_positions(scene_->mesh, camera, frame_window(o), clip_);

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
  FaceRenderOptions o;
  o.sampling.method = SeamMethod::traverse;
  o.sampling.filter = options.filter;
  o.sampling.max_aniso = 16;
  o.msaa = 1;
  o.threads = options.threads;
  return render_reference_tiles(width, height, options,
                                [&](const FrameWindow& w) -> Result<ImageRGBAF> {
                                  set_frame_window(o, w);
                                  Result<FaceFrame> f = render(camera, o);
                                  if (!f) return f.status();
                                  return std::move(f->image);
                                });
}

}  // namespace tessera::faces
