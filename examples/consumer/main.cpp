// Smallest program against the installed library: make an image, compare it with itself.
#include <cstdio>

#include "tessera/metrics.h"
#include "tessera/procedural.h"

int main() {
  const tessera::ImageRGBA8 img = tessera::make_procedural(tessera::Procedural::noise, 64, 64);
  const auto r = tessera::metrics::compare_images(img, img);
  if (!r.ok() || r->ssim_gray != 1.0) return 1;
  std::printf("consumer ok: %dx%d, SSIM %.3f\n", img.width, img.height, r->ssim_gray);
  return 0;
}
