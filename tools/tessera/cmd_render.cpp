// tessera render SCENE ...: one frame (or a timed sequence) of a scene with the software
// rasteriser, unlit textured shading.
#include <algorithm>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "cli.h"
#include "tessera/io.h"
#include "tessera/render.h"

namespace tessera::cli {

namespace {
struct RenderArgs {
  std::string scene, out, camera, orbit, filter = "trilinear", shading = "textured";
  int width = 1024, height = 768, msaa = 1, ssaa = 1, frames = 1;
  bool json = false;
  bool quiet = false;
};

int run_render(const RenderArgs& args, const GlobalOptions& global) {
  if (Result<io::ImageFormat> f = io::image_format_for_output(args.out); !f) {
    return usage_error("-o: " + f.status().message);
  }
  if (int rc = refuse_binary_to_terminal(args.out, "an image")) return rc;
  Result<scene::Scene> sc = args.scene == "builtin" ? Result<scene::Scene>(scene::builtin_scene())
                                                    : scene::load_scene(args.scene);
  if (!sc) return fail(sc.status());
  Result<scene::Camera> camera = scene::camera_from_text(*sc, args.camera, args.orbit);
  if (!camera) return usage_error(camera.status().message);
  Result<std::unique_ptr<render::SceneRenderer>> renderer =
      render::SceneRenderer::create(*sc, {global.threads});
  if (!renderer) return fail(renderer.status());
  render::FrameOptions fo;
  fo.width = args.width;
  fo.height = args.height;
  fo.msaa = args.msaa;
  fo.ssaa = args.ssaa;
  fo.filter = args.filter == "aniso16" ? render::Filter::aniso16 : render::Filter::trilinear;
  fo.shading = args.shading == "flat" ? render::Shading::flat : render::Shading::textured;
  fo.threads = global.threads;
  std::vector<double> times;
  render::Frame last;
  for (int f = 0; f < args.frames; ++f) {
    Result<render::Frame> frame = (*renderer)->render(*camera, fo);
    if (!frame) return fail(frame.status());
    times.push_back(frame->ms_total());
    last = std::move(*frame);
  }
  if (Status s = io::write_image(args.out, last.image); !s.ok()) return fail(s);
  const double median_ms = median(times);
  std::FILE* out = text_stream(args.out == "-");
  const std::uint64_t samples = std::uint64_t(args.width) * std::uint64_t(args.height) *
                                std::uint64_t(args.msaa) * std::uint64_t(args.ssaa * args.ssaa);
  if (args.json) {
    nlohmann::json j = {{"scene", args.scene},
                        {"width", args.width},
                        {"height", args.height},
                        {"msaa", args.msaa},
                        {"ssaa", args.ssaa},
                        {"filter", args.filter},
                        {"threads", global.threads > 0 ? global.threads : default_thread_count()},
                        {"triangles", sc->triangle_count()},
                        {"triangles_rasterised", last.stats.triangles_setup},
                        {"samples", samples},
                        {"shader_invocations", last.stats.lanes_shaded},
                        {"frames", args.frames},
                        {"frame_ms", times},
                        {"median_ms", median_ms},
                        {"ms_transform", last.ms_transform},
                        {"ms_raster", last.ms_raster},
                        {"ms_resolve", last.ms_resolve},
                        {"output", io::io_name(args.out, true)}};
    std::fprintf(out, "%s\n", j.dump(2).c_str());
  } else if (!args.quiet) {
    std::fprintf(out,
                 "%s: %zu triangles, %dx%d, msaa %d, ssaa %d, %.2f ms/frame (median of %d) -> %s\n",
                 args.scene.c_str(), sc->triangle_count(), args.width, args.height, args.msaa,
                 args.ssaa, median_ms, args.frames, io::io_name(args.out, true).c_str());
  }
  return kExitOk;
}
}  // namespace

Command add_render_command(CLI::App& app, const GlobalOptions& global) {
  auto args = std::make_shared<RenderArgs>();
  CLI::App* sub = app.add_subcommand(
      "render", "Render a scene (OBJ, glTF or 'builtin') with the software rasteriser");
  sub->add_option("SCENE", args->scene, "Scene file (.obj, .gltf, .glb) or 'builtin'")->required();
  sub->add_option("--width", args->width)->check(CLI::Range(1, 16384))->capture_default_str();
  sub->add_option("--height", args->height)->check(CLI::Range(1, 16384))->capture_default_str();
  auto* cam = sub->add_option("--camera", args->camera,
                              "Camera eye,target,up,fov: 10 comma-separated numbers");
  sub->add_option("--orbit", args->orbit, "FRAME/N: camera on the scene's orbit")->excludes(cam);
  auto* msaa = sub->add_option("--msaa", args->msaa, "MSAA samples (D3D standard positions)")
                   ->check(CLI::IsMember({1, 2, 4, 8, 16}));
  sub->add_option("--ssaa", args->ssaa, "Supersampling: M x M shaded samples per pixel")
      ->check(CLI::Range(1, 8))
      ->excludes(msaa);
  sub->add_option("--filter", args->filter, "Texture filter")
      ->check(CLI::IsMember({"trilinear", "aniso16"}))
      ->capture_default_str();
  sub->add_option("--shading", args->shading, "textured, or flat white (coverage only)")
      ->check(CLI::IsMember({"textured", "flat"}))
      ->capture_default_str();
  sub->add_option("--frames", args->frames, "Frames to render and time (median reported)")
      ->check(CLI::Range(1, 100000));
  sub->add_option("-o,--output,--out", args->out,
                  "Output image: .png, .bmp, .tga or .jpg by extension ('-' = PNG on stdout)")
      ->required();
  sub->add_flag("--json", args->json, "Print timings, triangles and samples as JSON");
  sub->add_flag("-q,--quiet", args->quiet, "Print nothing on success");
  return {sub, [args, &global] { return run_render(*args, global); }};
}

}  // namespace tessera::cli
