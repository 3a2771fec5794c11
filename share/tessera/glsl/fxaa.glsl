// fxaa.glsl — public GLSL API: FXAA 3.11 "quality" (PC) (Lottes, Fxaa3_11.h, FxaaPixelShader),
// the arithmetic of tessera's CPU port (src/deferred/fxaa.cpp) step for step, in pixel units
// (pixel (x, y) has its centre at (x + 0.5, y + 0.5)).
//
// The including shader first defines
//   float tessera_fxaa_luma(ivec2 p);   // luma of pixel p, coordinates clamped to the image
//                                       // (FXAA: Rec.601 on the sRGB values in [0, 1])
// and the preset:
//   #define TESSERA_FXAA_STEPS S          // 3..12
//   const float tessera_fxaa_p[12] = ...; // FXAA_QUALITY__P0..P11 (unused entries 0)
// then calls tessera_fxaa_position(pixel, subpix, edge_threshold, edge_threshold_min, early):
// it returns the position (pixel units) at which to fetch the output colour bilinearly
// (clamp to edge), or the pixel centre with early = true when the local contrast is below
// the threshold (copy the input pixel).
// Vulkan (glslangValidator -V, glslc): the same source and contract; fxaa.glsl declares no
// resources, so the bindings are those of the includer's tessera_fxaa_luma.

#ifndef TESSERA_FXAA_STEPS
#error "define TESSERA_FXAA_STEPS and tessera_fxaa_p before including fxaa.glsl"
#endif

float tessera_fxaa_luma_bilinear(vec2 pos) {
  vec2 f = pos - 0.5;
  vec2 f0 = floor(f);
  vec2 a = f - f0;
  ivec2 i0 = ivec2(f0);
  float l00 = tessera_fxaa_luma(i0), l10 = tessera_fxaa_luma(i0 + ivec2(1, 0));
  float l01 = tessera_fxaa_luma(i0 + ivec2(0, 1)), l11 = tessera_fxaa_luma(i0 + ivec2(1, 1));
  return (l00 * (1.0 - a.x) + l10 * a.x) * (1.0 - a.y) + (l01 * (1.0 - a.x) + l11 * a.x) * a.y;
}

vec2 tessera_fxaa_position(ivec2 pixel, float subpix, float edge_threshold,
                           float edge_threshold_min, out bool early) {
  vec2 posM = vec2(pixel) + 0.5;
  float lumaM = tessera_fxaa_luma(pixel);
  float lumaS = tessera_fxaa_luma(pixel + ivec2(0, 1));
  float lumaE = tessera_fxaa_luma(pixel + ivec2(1, 0));
  float lumaN = tessera_fxaa_luma(pixel + ivec2(0, -1));
  float lumaW = tessera_fxaa_luma(pixel + ivec2(-1, 0));
  float maxSM = max(lumaS, lumaM), minSM = min(lumaS, lumaM);
  float maxESM = max(lumaE, maxSM), minESM = min(lumaE, minSM);
  float maxWN = max(lumaN, lumaW), minWN = min(lumaN, lumaW);
  float rangeMax = max(maxWN, maxESM), rangeMin = min(minWN, minESM);
  float rangeMaxScaled = rangeMax * edge_threshold;
  float range = rangeMax - rangeMin;
  float rangeMaxClamped = max(edge_threshold_min, rangeMaxScaled);
  early = range < rangeMaxClamped;
  if (early) return posM;

  float lumaNW = tessera_fxaa_luma(pixel + ivec2(-1, -1));
  float lumaSE = tessera_fxaa_luma(pixel + ivec2(1, 1));
  float lumaNE = tessera_fxaa_luma(pixel + ivec2(1, -1));
  float lumaSW = tessera_fxaa_luma(pixel + ivec2(-1, 1));
  float lumaNS = lumaN + lumaS, lumaWE = lumaW + lumaE;
  float subpixRcpRange = 1.0 / range;
  float subpixNSWE = lumaNS + lumaWE;
  float edgeHorz1 = -2.0 * lumaM + lumaNS, edgeVert1 = -2.0 * lumaM + lumaWE;
  float lumaNESE = lumaNE + lumaSE, lumaNWNE = lumaNW + lumaNE;
  float edgeHorz2 = -2.0 * lumaE + lumaNESE, edgeVert2 = -2.0 * lumaN + lumaNWNE;
  float lumaNWSW = lumaNW + lumaSW, lumaSWSE = lumaSW + lumaSE;
  float edgeHorz4 = abs(edgeHorz1) * 2.0 + abs(edgeHorz2);
  float edgeVert4 = abs(edgeVert1) * 2.0 + abs(edgeVert2);
  float edgeHorz3 = -2.0 * lumaW + lumaNWSW, edgeVert3 = -2.0 * lumaS + lumaSWSE;
  float edgeHorz = abs(edgeHorz3) + edgeHorz4;
  float edgeVert = abs(edgeVert3) + edgeVert4;
  float subpixNWSWNESE = lumaNWSW + lumaNESE;
  float lengthSign = 1.0;
  bool horzSpan = edgeHorz >= edgeVert;
  float subpixA = subpixNSWE * 2.0 + subpixNWSWNESE;
  if (!horzSpan) {
    lumaN = lumaW;
    lumaS = lumaE;
  }
  float subpixB = subpixA * (1.0 / 12.0) - lumaM;
  float gradientN = lumaN - lumaM, gradientS = lumaS - lumaM;
  float lumaNN = lumaN + lumaM;
  float lumaSS = lumaS + lumaM;
  bool pairN = abs(gradientN) >= abs(gradientS);
  float gradient = max(abs(gradientN), abs(gradientS));
  if (pairN) lengthSign = -lengthSign;
  float subpixC = clamp(abs(subpixB) * subpixRcpRange, 0.0, 1.0);

  vec2 posB = posM;
  vec2 offNP = vec2(!horzSpan ? 0.0 : 1.0, horzSpan ? 0.0 : 1.0);
  if (!horzSpan) posB.x += lengthSign * 0.5;
  if (horzSpan) posB.y += lengthSign * 0.5;
  vec2 posN = posB - offNP * tessera_fxaa_p[0];
  vec2 posP = posB + offNP * tessera_fxaa_p[0];
  float subpixD = -2.0 * subpixC + 3.0;
  float lumaEndN = tessera_fxaa_luma_bilinear(posN);
  float subpixE = subpixC * subpixC;
  float lumaEndP = tessera_fxaa_luma_bilinear(posP);
  if (!pairN) lumaNN = lumaSS;
  float gradientScaled = gradient * 1.0 / 4.0;
  float lumaMM = lumaM - lumaNN * 0.5;
  float subpixF = subpixD * subpixE;
  bool lumaMLTZero = lumaMM < 0.0;
  lumaEndN -= lumaNN * 0.5;
  lumaEndP -= lumaNN * 0.5;
  bool doneN = abs(lumaEndN) >= gradientScaled;
  bool doneP = abs(lumaEndP) >= gradientScaled;
  if (!doneN) posN -= offNP * tessera_fxaa_p[1];
  bool doneNP = !doneN || !doneP;
  if (!doneP) posP += offNP * tessera_fxaa_p[1];
  for (int step = 2; step < TESSERA_FXAA_STEPS && doneNP; ++step) {
    if (!doneN) lumaEndN = tessera_fxaa_luma_bilinear(posN) - lumaNN * 0.5;
    if (!doneP) lumaEndP = tessera_fxaa_luma_bilinear(posP) - lumaNN * 0.5;
    doneN = abs(lumaEndN) >= gradientScaled;
    doneP = abs(lumaEndP) >= gradientScaled;
    if (!doneN) posN -= offNP * tessera_fxaa_p[step];
    doneNP = !doneN || !doneP;
    if (!doneP) posP += offNP * tessera_fxaa_p[step];
  }
  float dstN = posM.x - posN.x, dstP = posP.x - posM.x;
  if (!horzSpan) {
    dstN = posM.y - posN.y;
    dstP = posP.y - posM.y;
  }
  bool goodSpanN = (lumaEndN < 0.0) != lumaMLTZero;
  float spanLength = dstP + dstN;
  bool goodSpanP = (lumaEndP < 0.0) != lumaMLTZero;
  float spanLengthRcp = 1.0 / spanLength;
  bool directionN = dstN < dstP;
  float dst = min(dstN, dstP);
  bool goodSpan = directionN ? goodSpanN : goodSpanP;
  float subpixG = subpixF * subpixF;
  float pixelOffset = dst * -spanLengthRcp + 0.5;
  float subpixH = subpixG * subpix;
  float pixelOffsetGood = goodSpan ? pixelOffset : 0.0;
  float pixelOffsetSubpix = max(pixelOffsetGood, subpixH);
  if (!horzSpan) posM.x += pixelOffsetSubpix * lengthSign;
  if (horzSpan) posM.y += pixelOffsetSubpix * lengthSign;
  return posM;
}
