// FXAA 3.11 "quality" (PC), ported from Timothy Lottes' published description and shader
// (Fxaa3_11.h, FxaaPixelShader, FXAA_PC path) to the CPU. Work in pixel units: the shader's
// fxaaQualityRcpFrame is (1, 1) here and pixel (x, y) has its centre at (x + 0.5, y + 0.5).
// Luma is precomputed into a plane (the shader's "luma in alpha" input); FxaaTexTop becomes a
// bilinear fetch with clamp-to-edge, FxaaTexOff a point fetch.
#include <algorithm>
#include <array>
#include <cmath>

#include "tessera/deferred.h"

namespace tessera::deferred {

namespace {

struct Preset {
  int id;
  FxaaPresetSteps steps;
};

// FXAA_QUALITY__P0..P11 of every preset in Fxaa3_11.h.
constexpr Preset kPresets[] = {
    {10, {3, {1.5f, 3.0f, 12.0f}}},
    {11, {4, {1.0f, 1.5f, 3.0f, 12.0f}}},
    {12, {5, {1.0f, 1.5f, 2.0f, 4.0f, 12.0f}}},
    {13, {6, {1.0f, 1.5f, 2.0f, 2.0f, 4.0f, 12.0f}}},
    {14, {7, {1.0f, 1.5f, 2.0f, 2.0f, 2.0f, 4.0f, 12.0f}}},
    {15, {8, {1.0f, 1.5f, 2.0f, 2.0f, 2.0f, 2.0f, 4.0f, 12.0f}}},
    {20, {3, {1.5f, 2.0f, 8.0f}}},
    {21, {4, {1.0f, 1.5f, 2.0f, 8.0f}}},
    {22, {5, {1.0f, 1.5f, 2.0f, 2.0f, 8.0f}}},
    {23, {6, {1.0f, 1.5f, 2.0f, 2.0f, 2.0f, 8.0f}}},
    {24, {7, {1.0f, 1.5f, 2.0f, 2.0f, 2.0f, 3.0f, 8.0f}}},
    {25, {8, {1.0f, 1.5f, 2.0f, 2.0f, 2.0f, 2.0f, 4.0f, 8.0f}}},
    {26, {9, {1.0f, 1.5f, 2.0f, 2.0f, 2.0f, 2.0f, 2.0f, 4.0f, 8.0f}}},
    {27, {10, {1.0f, 1.5f, 2.0f, 2.0f, 2.0f, 2.0f, 2.0f, 2.0f, 4.0f, 8.0f}}},
    {28, {11, {1.0f, 1.5f, 2.0f, 2.0f, 2.0f, 2.0f, 2.0f, 2.0f, 2.0f, 4.0f, 8.0f}}},
    {29, {12, {1.0f, 1.5f, 2.0f, 2.0f, 2.0f, 2.0f, 2.0f, 2.0f, 2.0f, 2.0f, 4.0f, 8.0f}}},
    {39, {12, {1.0f, 1.0f, 1.0f, 1.0f, 1.0f, 1.5f, 2.0f, 2.0f, 2.0f, 2.0f, 4.0f, 8.0f}}},
};

const Preset* find_preset(int id) {
  for (const Preset& p : kPresets) {
    if (p.id == id) return &p;
  }
  return nullptr;
}

/// A float plane with point and bilinear (clamp-to-edge) fetches, `c` floats per texel.
struct Plane {
  const float* data;
  int w, h, c;

  const float* texel(int x, int y) const {
    x = std::clamp(x, 0, w - 1);
    y = std::clamp(y, 0, h - 1);
    return data + (std::size_t(y) * std::size_t(w) + std::size_t(x)) * std::size_t(c);
  }
  /// Bilinear fetch at (px, py) in pixel units (texel centres at i + 0.5) of channel `ch`.
  float bilinear(float px, float py, int ch) const {
    const float fx = px - 0.5f, fy = py - 0.5f;
    const float x0f = std::floor(fx), y0f = std::floor(fy);
    const float ax = fx - x0f, ay = fy - y0f;
    const int x0 = int(x0f), y0 = int(y0f);
    const float a = texel(x0, y0)[ch], b = texel(x0 + 1, y0)[ch];
    const float cc = texel(x0, y0 + 1)[ch], d = texel(x0 + 1, y0 + 1)[ch];
    return (a * (1 - ax) + b * ax) * (1 - ay) + (cc * (1 - ax) + d * ax) * ay;
  }
};

/// FxaaPixelShader for pixel (x, y): returns the sampling position (posM after the offset).
void fxaa_pixel(const Plane& luma, int x, int y, const FxaaPresetSteps& preset,
                const FxaaOptions& o, float& out_x, float& out_y, bool& early_exit) {
  float posMx = float(x) + 0.5f, posMy = float(y) + 0.5f;
  out_x = posMx;
  out_y = posMy;
  auto L = [&](int dx, int dy) { return *luma.texel(x + dx, y + dy); };
  const float lumaM = L(0, 0);
  float lumaS = L(0, 1);
  const float lumaE = L(1, 0);
  float lumaN = L(0, -1);
  const float lumaW = L(-1, 0);
  const float maxSM = std::max(lumaS, lumaM), minSM = std::min(lumaS, lumaM);
  const float maxESM = std::max(lumaE, maxSM), minESM = std::min(lumaE, minSM);
  const float maxWN = std::max(lumaN, lumaW), minWN = std::min(lumaN, lumaW);
  const float rangeMax = std::max(maxWN, maxESM), rangeMin = std::min(minWN, minESM);
  const float rangeMaxScaled = rangeMax * o.edge_threshold;
  const float range = rangeMax - rangeMin;
  const float rangeMaxClamped = std::max(o.edge_threshold_min, rangeMaxScaled);
  early_exit = range < rangeMaxClamped;
  if (early_exit) return;

  const float lumaNW = L(-1, -1), lumaSE = L(1, 1), lumaNE = L(1, -1), lumaSW = L(-1, 1);
  const float lumaNS = lumaN + lumaS, lumaWE = lumaW + lumaE;
  const float subpixRcpRange = 1.0f / range;
  const float subpixNSWE = lumaNS + lumaWE;
  const float edgeHorz1 = -2.0f * lumaM + lumaNS, edgeVert1 = -2.0f * lumaM + lumaWE;
  const float lumaNESE = lumaNE + lumaSE, lumaNWNE = lumaNW + lumaNE;
  const float edgeHorz2 = -2.0f * lumaE + lumaNESE, edgeVert2 = -2.0f * lumaN + lumaNWNE;
  const float lumaNWSW = lumaNW + lumaSW, lumaSWSE = lumaSW + lumaSE;
  const float edgeHorz4 = std::fabs(edgeHorz1) * 2.0f + std::fabs(edgeHorz2);
  const float edgeVert4 = std::fabs(edgeVert1) * 2.0f + std::fabs(edgeVert2);
  const float edgeHorz3 = -2.0f * lumaW + lumaNWSW, edgeVert3 = -2.0f * lumaS + lumaSWSE;
  const float edgeHorz = std::fabs(edgeHorz3) + edgeHorz4;
  const float edgeVert = std::fabs(edgeVert3) + edgeVert4;
  const float subpixNWSWNESE = lumaNWSW + lumaNESE;
  float lengthSign = 1.0f;  // rcpFrame.x (or .y) in pixel units
  const bool horzSpan = edgeHorz >= edgeVert;
  const float subpixA = subpixNSWE * 2.0f + subpixNWSWNESE;
  if (!horzSpan) {
    lumaN = lumaW;
    lumaS = lumaE;
  }
  const float subpixB = subpixA * (1.0f / 12.0f) - lumaM;
  const float gradientN = lumaN - lumaM, gradientS = lumaS - lumaM;
  float lumaNN = lumaN + lumaM;
  const float lumaSS = lumaS + lumaM;
  const bool pairN = std::fabs(gradientN) >= std::fabs(gradientS);
  const float gradient = std::max(std::fabs(gradientN), std::fabs(gradientS));
  if (pairN) lengthSign = -lengthSign;
  const float subpixC = std::clamp(std::fabs(subpixB) * subpixRcpRange, 0.0f, 1.0f);

  float posBx = posMx, posBy = posMy;
  const float offNPx = !horzSpan ? 0.0f : 1.0f, offNPy = horzSpan ? 0.0f : 1.0f;
  if (!horzSpan) posBx += lengthSign * 0.5f;
  if (horzSpan) posBy += lengthSign * 0.5f;
  float posNx = posBx - offNPx * preset.p[0], posNy = posBy - offNPy * preset.p[0];
  float posPx = posBx + offNPx * preset.p[0], posPy = posBy + offNPy * preset.p[0];
  const float subpixD = -2.0f * subpixC + 3.0f;
  float lumaEndN = luma.bilinear(posNx, posNy, 0);
  const float subpixE = subpixC * subpixC;
  float lumaEndP = luma.bilinear(posPx, posPy, 0);
  if (!pairN) lumaNN = lumaSS;
  const float gradientScaled = gradient * 1.0f / 4.0f;
  const float lumaMM = lumaM - lumaNN * 0.5f;
  const float subpixF = subpixD * subpixE;
  const bool lumaMLTZero = lumaMM < 0.0f;
  lumaEndN -= lumaNN * 0.5f;
  lumaEndP -= lumaNN * 0.5f;
  bool doneN = std::fabs(lumaEndN) >= gradientScaled;
  bool doneP = std::fabs(lumaEndP) >= gradientScaled;
  if (!doneN) {
    posNx -= offNPx * preset.p[1];
    posNy -= offNPy * preset.p[1];
  }
  bool doneNP = !doneN || !doneP;
  if (!doneP) {
    posPx += offNPx * preset.p[1];
    posPy += offNPy * preset.p[1];
  }
  // Steps P2 .. P(PS-1), the shader's nested `if (doneNP)` blocks.
  for (int step = 2; step < preset.steps && doneNP; ++step) {
    if (!doneN) lumaEndN = luma.bilinear(posNx, posNy, 0) - lumaNN * 0.5f;
    if (!doneP) lumaEndP = luma.bilinear(posPx, posPy, 0) - lumaNN * 0.5f;
    doneN = std::fabs(lumaEndN) >= gradientScaled;
    doneP = std::fabs(lumaEndP) >= gradientScaled;
    if (!doneN) {
      posNx -= offNPx * preset.p[std::size_t(step)];
      posNy -= offNPy * preset.p[std::size_t(step)];
    }
    doneNP = !doneN || !doneP;
    if (!doneP) {
      posPx += offNPx * preset.p[std::size_t(step)];
      posPy += offNPy * preset.p[std::size_t(step)];
    }
  }
  float dstN = posMx - posNx, dstP = posPx - posMx;
  if (!horzSpan) {
    dstN = posMy - posNy;
    dstP = posPy - posMy;
  }
  const bool goodSpanN = (lumaEndN < 0.0f) != lumaMLTZero;
  const float spanLength = dstP + dstN;
  const bool goodSpanP = (lumaEndP < 0.0f) != lumaMLTZero;
  const float spanLengthRcp = 1.0f / spanLength;
  const bool directionN = dstN < dstP;
  const float dst = std::min(dstN, dstP);
  const bool goodSpan = directionN ? goodSpanN : goodSpanP;
  const float subpixG = subpixF * subpixF;
  const float pixelOffset = dst * -spanLengthRcp + 0.5f;
  const float subpixH = subpixG * o.subpix;
  const float pixelOffsetGood = goodSpan ? pixelOffset : 0.0f;
  const float pixelOffsetSubpix = std::max(pixelOffsetGood, subpixH);
  if (!horzSpan) posMx += pixelOffsetSubpix * lengthSign;
  if (horzSpan) posMy += pixelOffsetSubpix * lengthSign;
  out_x = posMx;
  out_y = posMy;
}

}  // namespace

bool valid_fxaa_preset(int preset) { return find_preset(preset) != nullptr; }

const FxaaPresetSteps* fxaa_preset_steps(int preset) {
  const Preset* p = find_preset(preset);
  return p ? &p->steps : nullptr;
}

Result<ImageRGBA8> fxaa(const ImageRGBA8& image, const FxaaOptions& options) {
  const Preset* preset = find_preset(options.preset);
  if (!preset) {
    return Status::error(ErrorCode::invalid_argument, "fxaa: unknown quality preset " +
                                                          std::to_string(options.preset) +
                                                          " (10..15, 20..29 or 39)");
  }
  if (image.empty()) return Status::error(ErrorCode::invalid_argument, "fxaa: empty image");
  const int w = image.width, h = image.height;
  // The shader's input texture: sRGB values in [0, 1] with luma in alpha.
  std::vector<float> rgbl(image.pixel_count() * 4);
  for (std::size_t i = 0; i < image.pixel_count(); ++i) {
    const std::uint8_t* p = &image.pixels[i * 4];
    float* o = &rgbl[i * 4];
    o[0] = float(p[0]) / 255.0f;
    o[1] = float(p[1]) / 255.0f;
    o[2] = float(p[2]) / 255.0f;
    o[3] = 0.299f * o[0] + 0.587f * o[1] + 0.114f * o[2];
  }
  const Plane colour{rgbl.data(), w, h, 4};
  const Plane luma{rgbl.data() + 3, w, h, 4};
  ImageRGBA8 out(w, h);
  out.has_alpha = image.has_alpha;
  parallel_for(0, h, 4,
               [&](std::int64_t y0, std::int64_t y1) {
                 for (int y = int(y0); y < int(y1); ++y) {
                   for (int x = 0; x < w; ++x) {
                     float px = 0, py = 0;
                     bool early = false;
                     fxaa_pixel(luma, x, y, preset->steps, options, px, py, early);
                     std::uint8_t* o = out.at(x, y);
                     const std::uint8_t* in = image.at(x, y);
                     o[3] = in[3];
                     if (early) {
                       o[0] = in[0];
                       o[1] = in[1];
                       o[2] = in[2];
                       continue;
                     }
                     for (int c = 0; c < 3; ++c) {
                       const float v = colour.bilinear(px, py, c);
                       o[c] = std::uint8_t(std::clamp(std::lround(v * 255.0f), 0L, 255L));
                     }
                   }
                 }
               },
               {options.threads});
  return out;
}

}  // namespace tessera::deferred
