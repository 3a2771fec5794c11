// pvrtc_quality — prints a Markdown table of tessera's PVRTC quality and encode time per image
// and quality preset: RGB PSNR, alpha PSNR (RGBA inputs), SSIM and wall time (best of 3).
//
// Usage: pvrtc_quality [--bpp 4|2] [--threads N] image.png...   (power-of-two images only;
// others are skipped with a note).
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "tessera/io.h"
#include "tessera/metrics.h"
#include "tessera/pvrtc.h"

using namespace tessera;

int main(int argc, char** argv) {
  pvrtc::Format format = pvrtc::Format::pvrtc1_4bpp;
  int threads = 0;
  std::vector<std::string> files;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--bpp") && i + 1 < argc) {
      format = std::atoi(argv[++i]) == 2 ? pvrtc::Format::pvrtc1_2bpp : pvrtc::Format::pvrtc1_4bpp;
    } else if (!std::strcmp(argv[i], "--threads") && i + 1 < argc) {
      threads = std::atoi(argv[++i]);
    } else {
      files.emplace_back(argv[i]);
    }
  }
  std::printf("| image | quality | PSNR RGB | PSNR A | SSIM | ms |\n|---|---|---|---|---|---|\n");
  const char* names[] = {"fast", "normal", "high"};
  double sum_psnr[3] = {0, 0, 0};
  int n = 0;
  for (const std::string& f : files) {
    auto img = io::read_image(f);
    if (!img.ok() || !pvrtc::check_dimensions(img->width, img->height, f).ok()) {
      std::fprintf(stderr, "skipping %s\n", f.c_str());
      continue;
    }
    ++n;
    for (int q = 0; q < 3; ++q) {
      pvrtc::EncodeOptions opt;
      opt.format = format;
      opt.quality = pvrtc::Quality(q);
      opt.threads = threads;
      double best_ms = 1e30;
      Result<std::vector<std::uint8_t>> enc = Status::error(ErrorCode::invalid_argument, "");
      for (int rep = 0; rep < 3; ++rep) {
        const auto t0 = std::chrono::steady_clock::now();
        enc = pvrtc::encode(*img, opt);
        const auto t1 = std::chrono::steady_clock::now();
        best_ms = std::min(best_ms, std::chrono::duration<double, std::milli>(t1 - t0).count());
      }
      if (!enc.ok()) return 1;
      auto dec = pvrtc::decode(*enc, format, img->width, img->height);
      auto cmp = metrics::compare_images(*img, *dec);
      sum_psnr[q] += cmp->psnr_rgb;
      const std::string base = f.substr(f.find_last_of('/') + 1);
      std::printf("| %s | %s | %.2f | %s | %.4f | %.1f |\n", base.c_str(), names[q], cmp->psnr_rgb,
                  cmp->has_alpha ? std::to_string(cmp->psnr_alpha).substr(0, 5).c_str() : "-",
                  cmp->ssim_gray, best_ms);
    }
  }
  if (n > 0) {
    for (int q = 0; q < 3; ++q)
      std::printf("| mean (%d) | %s | %.2f | | | |\n", n, names[q], sum_psnr[q] / n);
  }
  return 0;
}
