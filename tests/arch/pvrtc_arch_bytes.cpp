// pvrtc_arch_bytes: encodes a fixed set of images with every PVRTC format (4 bpp, 2 bpp) and
// quality (fast, normal, high), RGB and RGBA, and writes each encoding's bytes and its decoded
// RGBA8 texels to one file per case. tests/arch/pvrtc_arch_bytes.sh runs it on every SIMD backend
// (x86-64: SSE2 with the AVX2 kernels dispatched, and with them forced off; TESSERA_NO_SIMD;
// AArch64 NEON under qemu-user) and fails on any byte that differs.
//
//   pvrtc_arch_bytes IMAGES_DIR OUT_DIR [--baseline] [--time]
//
// IMAGES_DIR is shared/data/images. --baseline forces the baseline (SSE2 / NEON / scalar)
// kernels where the run-time dispatch would pick the AVX2 ones; --time prints each case's
// seconds to stderr.
//
// The images, and why: qemu-user runs this AArch64 code some 30 to 70 times slower than the
// host runs it natively, and the arm64 stage has to stay within a few minutes on CI's two cores,
// so every image is small: 128x128 (a 32x32 grid of 4 bpp blocks, 16x32 at 2 bpp: interior
// blocks with all eight neighbours, the wrap-around at the edges, punch-through and translucent
// RGBA blocks), each a different kind of content:
//   ldr-rgb-01.png, ldr-rgb-05.png   two photographs (256x256 RGB), their central 128x128:
//                                    smooth gradients, fine texture, high-contrast detail;
//   ldr-rgba-00.png    a 256x256 RGBA texture with cut-out and soft alpha, its central
//                      128x128, encoded as RGBA and as RGB;
//   ldr-xy-normal1.png a normal map (1024x1024), 128x128 of it, with EncodeOptions::normal_map
//                      (as RGB: its alpha is 255 throughout);
//   procedural bricks, text (RGB) and foliage (RGBA): hard edges, thin strokes, alpha edges;
// plus a 32x128 non-square noise image (the Morton order's surplus bits) and an 8x8 one
// (smaller than 2x2 blocks: padded). 70 encodings in all: each source at 4 and 2 bpp, fast /
// normal / high, as RGB and, where it has alpha (ldr-rgba-00, foliage), as RGBA; and those two
// as RGBA at 4 bpp normal and high with EncodeOptions::alpha_weighted (its kernels have the
// same 4- and 8-lane paths as the unweighted ones, so every backend must agree there too).
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include "core/simd.h"
#include "pvrtc/encode/modulation/modulation_2bpp_avx2.h"
#include "pvrtc/encode/modulation/modulation_avx2.h"
#include "pvrtc/encode/search/exact_search_window.h"
#include "pvrtc/encode/start/dilation_kernels.h"
#include "tessera/io.h"
#include "tessera/procedural.h"
#include "tessera/pvrtc.h"

namespace {

using namespace tessera;

struct Source {
  std::string name;
  ImageRGBA8 image;
  bool normal_map = false;
};

/// The `w` x `h` texels of `in` from (x0, y0); has_alpha kept.
ImageRGBA8 crop(const ImageRGBA8& in, int x0, int y0, int w, int h) {
  ImageRGBA8 out(w, h);
  out.has_alpha = in.has_alpha;
  for (int y = 0; y < h; ++y) std::memcpy(out.at(0, y), in.at(x0, y0 + y), std::size_t(w) * 4);
  return out;
}

bool write(const std::string& path, const std::vector<std::uint8_t>& bytes) {
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (f == nullptr) return false;
  const bool ok = std::fwrite(bytes.data(), 1, bytes.size(), f) == bytes.size();
  return std::fclose(f) == 0 && ok;
}

struct Args {
  std::string images, out;
  bool baseline = false, timing = false;
};

/// Parses the command line into `args`; false (after a message) on a usage error.
bool parse_args(int argc, char** argv, Args& args) {
  std::vector<std::string> paths;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--baseline") == 0) {
      args.baseline = true;
    } else if (std::strcmp(argv[i], "--time") == 0) {
      args.timing = true;
    } else if (argv[i][0] == '-') {
      std::fprintf(stderr, "unknown option %s\n", argv[i]);
      return false;
    } else {
      paths.emplace_back(argv[i]);
    }
  }
  if (paths.size() != 2) {
    std::fprintf(stderr, "usage: %s IMAGES_DIR OUT_DIR [--baseline] [--time]\n", argv[0]);
    return false;
  }
  args.images = paths[0];
  args.out = paths[1];
  return true;
}

/// The crops of the four files in `images` and the procedural images; false (after a message)
/// when a file cannot be read.
bool load_sources(const std::string& images, std::vector<Source>& sources) {
  struct FileCrop {
    const char* file;
    int x, y, size;
    bool normal_map;
  };
  static constexpr FileCrop kFiles[] = {{"ldr-rgb-01.png", 64, 64, 128, false},
                                        {"ldr-rgb-05.png", 64, 64, 128, false},
                                        {"ldr-rgba-00.png", 64, 64, 128, false},
                                        {"ldr-xy-normal1.png", 448, 448, 128, true}};
  for (const FileCrop& f : kFiles) {
    Result<ImageRGBA8> img = io::read_image(images + "/" + f.file);
    if (!img) {
      std::fprintf(stderr, "%s\n", img.status().message.c_str());
      return false;
    }
    std::string name = f.file;
    name = name.substr(0, name.size() - 4);
    ImageRGBA8 image = crop(img.value(), f.x, f.y, f.size, f.size);
    image.has_alpha = image.has_alpha && !f.normal_map;
    sources.push_back({name, std::move(image), f.normal_map});
  }
  sources.push_back({"bricks", make_procedural(Procedural::bricks, 128, 128, 7), false});
  sources.push_back({"text", make_procedural(Procedural::text, 128, 128, 3), false});
  sources.push_back({"foliage", make_procedural(Procedural::foliage, 128, 128, 5), false});
  sources.push_back({"noise32x128", make_procedural(Procedural::noise, 32, 128, 2), false});
  sources.push_back({"noise8x8", make_procedural(Procedural::noise, 8, 8, 4), false});
  return true;
}

static constexpr pvrtc::Quality kQualities[] = {pvrtc::Quality::fast, pvrtc::Quality::normal,
                                                pvrtc::Quality::high};
static constexpr const char* kQualityNames[] = {"fast", "normal", "high"};

/// Encodes `s` (as RGBA when `alpha`) in `format` at quality case `q` (0..2: fast, normal,
/// high; 3, 4: normal / high alpha-weighted), decodes it, and writes both into `args.out`;
/// false (after a message) on an error.
bool encode_case(const Args& args, const Source& s, bool alpha, pvrtc::Format format, int q) {
  pvrtc::EncodeOptions options;
  options.format = format;
  options.quality = kQualities[q < 3 ? q : q - 2];
  options.alpha_weighted = q >= 3;
  options.normal_map = s.normal_map;
  ImageRGBA8 input = s.image;
  input.has_alpha = alpha;
  const auto t0 = std::chrono::steady_clock::now();
  Result<std::vector<std::uint8_t>> bytes = pvrtc::encode(input, options);
  if (!bytes) {
    std::fprintf(stderr, "%s: %s\n", s.name.c_str(), bytes.status().message.c_str());
    return false;
  }
  Result<ImageRGBA8> decoded = pvrtc::decode(bytes.value(), format, input.width, input.height);
  if (!decoded) {
    std::fprintf(stderr, "%s: %s\n", s.name.c_str(), decoded.status().message.c_str());
    return false;
  }
  const std::string name = args.out + "/" + s.name + (alpha ? ".rgba." : ".rgb.") +
                           (format == pvrtc::Format::pvrtc1_4bpp ? "4bpp." : "2bpp.") +
                           kQualityNames[q < 3 ? q : q - 2] + (q >= 3 ? ".weighted" : "");
  if (!write(name + ".pvrtc", bytes.value()) ||
      !write(name + ".decoded.rgba", decoded.value().pixels)) {
    std::fprintf(stderr, "cannot write %s\n", name.c_str());
    return false;
  }
  if (args.timing) {
    const double sec = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::fprintf(stderr, "%8.3f s  %s\n", sec, name.c_str());
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  Args args;
  if (!parse_args(argc, argv, args)) return 2;
  const std::string& out = args.out;
  if (args.baseline) {
    pvrtc::detail::dilation_force_baseline(true);
    (void)pvrtc::detail::set_modulation_baseline_only(true);
    (void)pvrtc::detail::set_modulation_2bpp_baseline_only(true);
    (void)pvrtc::detail::set_exact_search_baseline_only(true);
  }
  std::vector<Source> sources;
  if (!load_sources(args.images, sources)) return 1;

  static constexpr pvrtc::Format kFormats[] = {pvrtc::Format::pvrtc1_4bpp,
                                               pvrtc::Format::pvrtc1_2bpp};
  int cases = 0;
  for (const Source& s : sources) {
    // The inputs themselves (decoded PNGs, procedural generators) must agree too.
    if (!write(out + "/" + s.name + ".input.rgba", s.image.pixels)) {
      std::fprintf(stderr, "cannot write in %s\n", out.c_str());
      return 1;
    }
    for (const bool alpha : {false, true}) {
      if (alpha && !s.image.has_alpha) continue;
      for (const pvrtc::Format format : kFormats) {
        // q 3, 4: 4 bpp RGBA normal / high with alpha-weighted colour error.
        const int qualities = alpha && format == pvrtc::Format::pvrtc1_4bpp ? 5 : 3;
        for (int q = 0; q < qualities; ++q) {
          if (!encode_case(args, s, alpha, format, q)) return 1;
          ++cases;
        }
      }
    }
  }
#if defined(TESSERA_SIMD_SSE2)
  const char* backend = "SSE2";
#elif defined(TESSERA_SIMD_NEON)
  const char* backend = "NEON";
#else
  const char* backend = "scalar";
#endif
  std::printf("%d encodings written to %s (SIMD backend %s, AVX2 kernels %s)\n", cases, out.c_str(),
              backend, pvrtc::detail::exact_search_avx2_active() ? "on" : "off");
  return 0;
}
