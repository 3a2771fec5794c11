// Host set-up shared by the face renderer and its GL twin (gl::FaceRenderer): smooth vertex
// normals, clip-space positions of a frame window, and the tiled, Mitchell-Netravali-downsampled
// reference. Both renderers call these, so their frames start from the same numbers.
#include <algorithm>
#include <cmath>

#include "core/check.h"
#include "tessera/faces.h"

namespace tessera::faces {

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

std::vector<Vec3> smooth_face_normals(const QuadMesh& m) {
  // Area-weighted face normals summed per position.
  std::vector<Vec3> normals(m.positions.size());
  for (int f = 0; f < m.face_count(); ++f) {
    const auto& q = m.quads[std::size_t(f)];
    const Vec3 n = cross(m.positions[std::size_t(q[2])] - m.positions[std::size_t(q[0])],
                         m.positions[std::size_t(q[3])] - m.positions[std::size_t(q[1])]);
    for (int k = 0; k < 4; ++k)
      normals[std::size_t(q[std::size_t(k)])] = normals[std::size_t(q[std::size_t(k)])] + n;
  }
  std::vector<Vec3> out(std::size_t(m.face_count()) * 4);
  for (int f = 0; f < m.face_count(); ++f) {
    for (int k = 0; k < 4; ++k) {
      out[std::size_t(f) * 4 + std::size_t(k)] =
          normalize(normals[std::size_t(m.quads[std::size_t(f)][std::size_t(k)])]);
    }
  }
  return out;
}

void face_clip_positions(const QuadMesh& m, const scene::Camera& camera, const FrameWindow& w,
                         std::span<float> out) {
  TESSERA_DCHECK(out.size() >= std::size_t(m.face_count()) * 16);
  const int fw = w.full_width > 0 ? w.full_width : w.width;
  const int fh = w.full_height > 0 ? w.full_height : w.height;
  const Mat4 vp = camera.view_projection(float(fw) / float(fh));
  const float sx = float(fw) / float(w.width), sy = float(fh) / float(w.height);
  const float left = 2.0f * float(w.x0) / float(fw) - 1.0f;
  const float bottom = 1.0f - 2.0f * float(w.y0 + w.height) / float(fh);
  const float ox = -sx * left - 1.0f, oy = -sy * bottom - 1.0f;
  for (int f = 0; f < m.face_count(); ++f) {
    for (int k = 0; k < 4; ++k) {
      const Vec3& p = m.positions[std::size_t(m.quads[std::size_t(f)][std::size_t(k)])];
      const Vec4 c = vp * Vec4{p.x, p.y, p.z, 1.0f};
      float* o = &out[(std::size_t(f) * 4 + std::size_t(k)) * 4];
      o[0] = sx * c.x + ox * c.w;
      o[1] = sy * c.y + oy * c.w;
      o[2] = c.z;
      o[3] = c.w;
    }
  }
}

Result<ImageRGBAF> downsample_mitchell(const ImageRGBAF& g, int factor, int width, int height,
                                       const Parallel& parallel) {
  constexpr int kMargin = kReferenceMargin;
  if (factor < 1 || width < 1 || height < 1 || g.width != (width + 2 * kMargin) * factor ||
      g.height != (height + 2 * kMargin) * factor) {
    return Status::error(ErrorCode::size_mismatch,
                         "downsample_mitchell: the grid must be (size + 4) x factor per side");
  }
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
  // Horizontal pass: grid rows -> output columns; then vertical.
  ImageRGBAF hpass(width, g.height);
  parallel_for(
      0, g.height, 64,
      [&](std::int64_t b, std::int64_t e) {
        for (std::int64_t y = b; y < e; ++y) {
          for (int x = 0; x < width; ++x) {
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
      parallel);
  ImageRGBAF out(width, height);
  parallel_for(
      0, height, 16,
      [&](std::int64_t b, std::int64_t e) {
        for (std::int64_t y = b; y < e; ++y) {
          for (int x = 0; x < width; ++x) {
            float acc[4] = {0, 0, 0, 0};
            const int g0 = int(y) * factor;
            for (int i = 0; i < taps; ++i) {
              const float* p = hpass.at(x, g0 + i);
              for (int k = 0; k < 4; ++k) acc[k] += w[std::size_t(i)] * p[k];
            }
            float* q = out.at(x, int(y));
            for (int k = 0; k < 4; ++k) q[k] = acc[k];
          }
        }
      },
      parallel);
  return out;
}

Result<ImageRGBAF> render_reference_tiles(int width, int height, const ReferenceOptions& options,
                                          const ReferenceTileFn& render_tile) {
  const int factor = options.factor, tile = options.tile;
  if (width < 1 || height < 1 || factor < 1 || factor > 16 || tile < 1) {
    return Status::error(ErrorCode::invalid_argument, "reference: bad size or factor");
  }
  constexpr int kMargin = kReferenceMargin;
  ImageRGBAF out(width, height);
  FrameWindow window;
  window.full_width = width * factor;
  window.full_height = height * factor;
  for (int ty = 0; ty < height; ty += tile) {
    for (int tx = 0; tx < width; tx += tile) {
      const int tw = std::min(tile, width - tx), th = std::min(tile, height - ty);
      window.width = (tw + 2 * kMargin) * factor;
      window.height = (th + 2 * kMargin) * factor;
      window.x0 = (tx - kMargin) * factor;
      window.y0 = (ty - kMargin) * factor;
      Result<ImageRGBAF> grid = render_tile(window);
      if (!grid) return grid.status();
      Result<ImageRGBAF> d = downsample_mitchell(*grid, factor, tw, th, {options.threads});
      if (!d) return d.status();
      for (int y = 0; y < th; ++y) {
        std::copy(d->at(0, y), d->at(0, y) + std::size_t(tw) * 4, out.at(tx, ty + y));
      }
    }
  }
  return out;
}

}  // namespace tessera::faces
