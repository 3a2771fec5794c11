// tessera compare A B [--json] [--premultiplied] [--normal]: full-reference image quality.
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "cli.h"
#include "tessera/io.h"
#include "tessera/metrics.h"

namespace tessera::cli {

namespace {
struct CompareArgs {
  std::string a, b;
  bool json = false;
  bool quiet = false;
  bool premultiplied = false;
  bool normal = false;
  std::string heatmap;
};

int run_compare(const CompareArgs& args, const GlobalOptions& global) {
  if (args.b == "-") {
    return usage_error("compare: only the first image can be '-' (standard input)");
  }
  if (int rc = refuse_binary_to_terminal(args.heatmap, "a PNG heatmap")) return rc;
  if (!args.heatmap.empty()) {
    if (Result<io::ImageFormat> f = io::image_format_for_output(args.heatmap); !f) {
      return usage_error("--heatmap: " + f.status().message);
    }
  }
  Result<ImageRGBA8> a = io::read_image(args.a);
  if (!a) return fail(a.status());
  Result<ImageRGBA8> b = io::read_image(args.b);
  if (!b) return fail(b.status());
  if (a->width != b->width || a->height != b->height) {
    return fail(Status::error(ErrorCode::size_mismatch,
                              args.b + ": size " + std::to_string(b->width) + "x" +
                                  std::to_string(b->height) + " differs from " +
                                  io::io_name(args.a) + " (" + std::to_string(a->width) + "x" +
                                  std::to_string(a->height) + ")"));
  }
  // -q: both images read and have one size (the exit status says so); no metrics to print,
  // so none are computed, but the heatmap is still written.
  const bool print = args.json || !args.quiet;
  Result<metrics::ImageComparison> r = metrics::ImageComparison{};
  if (print) {
    metrics::CompareOptions options;
    options.threads = global.threads;
    options.premultiplied = args.premultiplied;
    options.normal = args.normal;
    r = metrics::compare_images(*a, *b, options);
    if (!r) return fail(r.status());
  }
  if (!args.heatmap.empty()) {
    Result<ImageRGBA8> map = metrics::difference_heatmap(*a, *b);
    if (!map) return fail(map.status());
    if (Status s = io::write_image(args.heatmap, *map); !s.ok()) return fail(s);
  }
  if (!print) return kExitOk;
  // With the heatmap on stdout, the results go to stderr.
  std::FILE* out = text_stream(args.heatmap == "-");
  if (args.json) {
    nlohmann::json j = {
        {"a", io::io_name(args.a)},
        {"b", args.b},
        {"width", a->width},
        {"height", a->height},
        {"psnr_rgb", db_or_null(r->psnr_rgb)},
        {"identical_rgb", !std::isfinite(r->psnr_rgb)},
        {"mse", r->mse_rgb},
        {"ssim_gray", r->ssim_gray},
        {"max_abs", r->max_abs},
        {"has_alpha", r->has_alpha},
    };
    if (r->has_alpha) {
      j["psnr_alpha"] = db_or_null(r->psnr_alpha);
      j["mse_alpha"] = r->mse_alpha;
    }
    if (r->has_premultiplied) {
      j["psnr_premultiplied"] = db_or_null(r->psnr_premultiplied);
      j["mse_premultiplied"] = r->mse_premultiplied;
    }
    if (r->has_normal) {
      j["angular_error_mean_deg"] = r->angular_error_mean_deg;
      j["angular_error_p99_deg"] = r->angular_error_p99_deg;
      j["angular_error_max_deg"] = r->angular_error_max_deg;
    }
    std::fprintf(out, "%s\n", j.dump(2).c_str());
    return kExitOk;
  }
  std::fprintf(out, "%s vs %s (%dx%d)\n", io::io_name(args.a).c_str(), args.b.c_str(), a->width,
               a->height);
  if (std::isfinite(r->psnr_rgb)) {
    std::fprintf(out, "PSNR RGB   : %.4f dB\n", r->psnr_rgb);
  } else {
    std::fprintf(out, "PSNR RGB   : inf (identical RGB)\n");
  }
  if (r->has_alpha) {
    if (std::isfinite(r->psnr_alpha)) {
      std::fprintf(out, "PSNR alpha : %.4f dB\n", r->psnr_alpha);
    } else {
      std::fprintf(out, "PSNR alpha : inf (identical alpha)\n");
    }
  }
  std::fprintf(out, "SSIM grey  : %.6f\n", r->ssim_gray);
  std::fprintf(out, "MSE RGB    : %.6f\n", r->mse_rgb);
  std::fprintf(out, "max abs    : %d\n", r->max_abs);
  if (r->has_premultiplied) {
    if (std::isfinite(r->psnr_premultiplied)) {
      std::fprintf(out, "premultiplied PSNR %.4f dB\n", r->psnr_premultiplied);
    } else {
      std::fprintf(out, "premultiplied PSNR inf (identical colour x alpha)\n");
    }
  }
  if (r->has_normal) {
    std::fprintf(out, "angular error mean %.4f°, p99 %.4f°, max %.4f°\n", r->angular_error_mean_deg,
                 r->angular_error_p99_deg, r->angular_error_max_deg);
  }
  return kExitOk;
}
}  // namespace

Command add_compare_command(CLI::App& app, const GlobalOptions& global) {
  auto args = std::make_shared<CompareArgs>();
  CLI::App* sub = app.add_subcommand(
      "compare",
      "Compare two images: PSNR over RGB (and alpha), SSIM on Rec.709 grey, MSE, max error");
  sub->add_option("A", args->a, "Reference image (PNG, JPEG, TGA, BMP; '-' = stdin)")->required();
  sub->add_option("B", args->b, "Test image of the same size")->required();
  sub->add_flag("--json", args->json,
                "Print one JSON object (keys psnr_rgb, ssim_gray, mse, max_abs, ...; "
                "psnr_rgb is null for identical images)");
  sub->add_flag("--premultiplied", args->premultiplied,
                "Also the PSNR of colour x alpha, what blending shows (psnr_premultiplied, "
                "mse_premultiplied; colour under alpha 0 does not count)");
  sub->add_flag("--normal", args->normal,
                "The images are normal maps: also the angle between their normalised vectors "
                "(angular_error_mean_deg, angular_error_p99_deg, angular_error_max_deg)");
  sub->add_flag("-q,--quiet", args->quiet,
                "Print nothing: exit status 0 when both images read and have the same size (1 "
                "otherwise); --heatmap is still written");
  sub->add_option("--heatmap", args->heatmap,
                  "Also write a difference heatmap here (.png, .bmp, .tga or .jpg by extension; "
                  "'-' = PNG on stdout, the results then go to stderr)");
  return {sub, [args, &global] { return run_compare(*args, global); }};
}

}  // namespace tessera::cli
