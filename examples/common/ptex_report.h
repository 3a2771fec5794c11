// ptex_report.h — what the two Ptex example engines (examples/engine_ptex on OpenGL,
// examples/engine_ptex_vk on Vulkan) share around their frame, so that the twins draw the same
// frame and judge it the same way: the flags both take (MESH.obj FILE.ptx, --size, --orbit,
// --shift-px, --json, -o), the engine's vertex (4 a Ptex face: its corners are not shared, each
// face has its own UVs) and per-frame block (view-projection, light), and the comparison with
// tessera's CPU renderer (faces::FaceRenderer: Discard, trilinear, same camera, resolution and
// lighting; tests/gl/gl_face_renderer_test.cpp measures its frames the same way). Header-only,
// like engine_context.h.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <utility>
#include <vector>

#include "engine_args.h"
#include "tessera/core.h"
#include "tessera/faces.h"
#include "tessera/faces_gpu.h"
#include "tessera/metrics.h"
#include "tessera/ptex.h"

namespace engine {

/// The flags both Ptex engines take.
struct PtexArgs {
  std::string obj, ptx, out;
  int w = 320, h = 240, orbit_k = 1, orbit_n = 8;
  float shift_px = 0.0f;
  bool json = false;
};

/// Adds --size WxH (even, 2..8192), --orbit K/N, --shift-px X, --json and -o FILE.png.
inline void add_ptex_flags(CommandLine& cl, PtexArgs& a) {
  cl.option("--size", [&a](const std::string& v) -> std::string {
    if (!parse_size(v, a.w, a.h) || a.w > 8192 || a.h > 8192 || a.w % 2 || a.h % 2)
      return "--size " + v + ": expected WxH, even, 2..8192 (2x2 derivative quads)";
    return "";
  });
  cl.option("--orbit", [&a](const std::string& v) -> std::string {
    if (std::sscanf(v.c_str(), "%d/%d", &a.orbit_k, &a.orbit_n) != 2 || a.orbit_n <= 0 ||
        a.orbit_k < 0)
      return "--orbit " + v + ": expected K/N";
    return "";
  });
  cl.option("--shift-px", [&a](const std::string& v) -> std::string {
    a.shift_px = std::strtof(v.c_str(), nullptr);
    return "";
  });
  cl.flag("--json", &a.json);
  cl.option("-o", [&a](const std::string& v) -> std::string {
    a.out = v;
    return "";
  });
}

/// Parses the command line of `engine` (its flags in `cl`): the two positional words are the
/// mesh and the Ptex file. "" or the problem.
inline std::string parse_ptex_args(const CommandLine& cl, int argc, char** argv, PtexArgs& a,
                                   const std::string& engine) {
  std::vector<std::string> positional;
  if (std::string why = cl.parse(argc, argv, &positional); !why.empty()) return why;
  if (positional.size() != 2) return "usage: " + engine + " MESH.obj FILE.ptx [options]";
  a.obj = positional[0];
  a.ptx = positional[1];
  return "";
}

/// What both engines draw: the scene (named after the mesh) and its per-face textures.
struct PtexScene {
  tessera::faces::FaceScene scene;
  tessera::faces::FaceTextureSet set;
};

/// tessera, step 1 (pure: no device yet): the mesh's polygons split into the quad faces of the
/// Ptex file, and the file's per-face textures; a bad file is named in the status.
inline tessera::Result<PtexScene> load_ptex_scene(const PtexArgs& a) {
  auto poly = tessera::faces::load_obj_polygons(a.obj);
  if (!poly) return poly.status();
  auto file = tessera::ptex::read_ptex(a.ptx);
  if (!file) return file.status();
  auto mesh = tessera::faces::ptex_quad_mesh(*poly, *file, a.ptx);
  if (!mesh) return mesh.status();
  auto set = tessera::faces::FaceTextureSet::from_ptex(*file, a.ptx);
  if (!set) return set.status();
  PtexScene out;
  out.scene.name = a.obj;
  out.scene.mesh = std::move(*mesh);
  out.set = std::move(*set);
  return out;
}

/// The engine's vertex: position, normal, per-face UV, integer face id (40 bytes).
struct FaceVertex {
  float position[3], normal[3], uv[2];
  std::int32_t face;
};

/// Four vertices (smooth normals: tessera's helper, so the CPU check sees the same geometry)
/// and two triangles per face of `mesh`.
inline void face_vertices(const tessera::faces::QuadMesh& mesh, std::vector<FaceVertex>& verts,
                          std::vector<std::uint32_t>& indices) {
  const std::vector<tessera::Vec3> normals = tessera::faces::smooth_face_normals(mesh);
  const float corner_uv[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  for (int f = 0; f < mesh.face_count(); ++f) {
    for (int c = 0; c < 4; ++c) {
      const tessera::Vec3& p =
          mesh.positions[std::size_t(mesh.quads[std::size_t(f)][std::size_t(c)])];
      const tessera::Vec3& n = normals[std::size_t(f) * 4 + std::size_t(c)];
      verts.push_back({{p.x, p.y, p.z}, {n.x, n.y, n.z}, {corner_uv[c][0], corner_uv[c][1]}, f});
    }
    const auto b = std::uint32_t(f) * 4;
    for (std::uint32_t i : {b, b + 1, b + 2, b, b + 2, b + 3}) indices.push_back(i);
  }
}

/// The engine's per-frame block (std140; GL binding 0, Vulkan set 0 binding 0).
struct ForwardFrameBlock {
  float view_proj[16];
  float light_dir[4];  // xyz, w unused
  float shade[4];      // ambient, diffuse
};

/// The block for a `w` x `h` frame of `camera`, its image moved `shift_px` pixels right.
inline ForwardFrameBlock forward_frame_block(const tessera::scene::Camera& camera, int w, int h,
                                             float shift_px) {
  ForwardFrameBlock frame{};
  const tessera::Mat4 vp = camera.view_projection(float(w) / float(h));
  for (int c = 0; c < 4; ++c) {
    for (int r = 0; r < 4; ++r) frame.view_proj[c * 4 + r] = vp.m[c][r];
    // A shift of X pixels to the right: clip x += (2 X / width) w.
    frame.view_proj[c * 4 + 0] += 2.0f * shift_px / float(w) * vp.m[c][3];
  }
  const float light[3] = {0.42f, 0.82f, 0.39f};
  std::copy(light, light + 3, frame.light_dir);
  frame.shade[0] = 0.35f;
  frame.shade[1] = 0.65f;
  return frame;
}

/// How far an engine's frame is from the CPU renderer's: PSNR of the 8-bit sRGB images
/// (infinite when identical), the fraction of pixels whose linear-RGB 2-norm difference is
/// >= 0.01, the largest such norm, the non-finite ones, and the CPU frame's time.
struct Agreement {
  double psnr = 0, frac_001 = 0, max_norm = 0, cpu_ms = 0;
  int non_finite = 0;
};

/// How far `img` is from `reference` (the Agreement's measures but the CPU time).
inline tessera::Result<Agreement> image_agreement(const tessera::ImageRGBAF& img,
                                                  const tessera::ImageRGBAF& reference) {
  tessera::metrics::CompareOptions co;
  co.compute_ssim = false;
  auto c =
      tessera::metrics::compare_images(tessera::to_srgb8(img), tessera::to_srgb8(reference), co);
  if (!c) return c.status();
  auto norms = tessera::metrics::error_norms(img, reference);
  if (!norms) return norms.status();
  Agreement r;
  r.psnr = c->psnr_rgb;
  int over = 0;
  for (float e : *norms) {
    if (!std::isfinite(e)) {
      ++r.non_finite;
      continue;
    }
    over += e >= 0.01f;
    r.max_norm = std::max(r.max_norm, double(e));
  }
  r.frac_001 = double(over) / double(norms->size());
  return r;
}

/// Renders the frame of `camera` at `img`'s size with tessera's CPU renderer `cpu` (Discard,
/// trilinear, the Clamp fallback) and compares `img` with it.
inline tessera::Result<Agreement> cpu_agreement(tessera::faces::FaceRenderer& cpu,
                                                const tessera::scene::Camera& camera,
                                                const tessera::ImageRGBAF& img) {
  tessera::faces::FaceRenderOptions o;
  o.width = img.width;
  o.height = img.height;
  o.sampling.method = tessera::faces::SeamMethod::discard;
  o.sampling.filter = tessera::texture::TextureFilter::trilinear;
  o.sampling.clamp_fallback = true;
  auto frame = cpu.render(camera, o);
  if (!frame) return frame.status();
  auto r = image_agreement(img, frame->image);
  if (r) r->cpu_ms = frame->ms();
  return r;
}

/// The same with a CPU renderer made for the one frame.
inline tessera::Result<Agreement> cpu_agreement(const tessera::faces::FaceScene& scene,
                                                const tessera::faces::FaceTextureSet& set,
                                                const tessera::scene::Camera& camera,
                                                const tessera::ImageRGBAF& img) {
  auto cpu = tessera::faces::FaceRenderer::create(scene, set);
  if (!cpu) return cpu.status();
  return cpu_agreement(**cpu, camera, img);
}

/// A PSNR as the reports print it ("%.3f"); for JSON, which has no infinity, identical 8-bit
/// images (MSE 0) give null.
inline std::string psnr_text(double psnr, bool json) {
  if (json && !std::isfinite(psnr)) return "null";
  char text[32];
  std::snprintf(text, sizeof text, "%.3f", psnr);
  return text;
}

}  // namespace engine
