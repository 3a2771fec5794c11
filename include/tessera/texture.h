// tessera/texture.h — float mip chains, texture arrays and a GPU-style sampler.
//
// The texture system of the rendering core, in two layers (as in Ptex's kernel/traversal split):
//
//  * Kernel (pure functions, no texture data): level-of-detail selection from texture-coordinate
//    gradients, anisotropic footprint analysis, address-mode resolution and *tap generation*.
//    A filter evaluation is a list of weighted texel taps (`TapList`), each naming a mip level,
//    an array layer, the integer texel before and after address-mode resolution and whether it
//    lay outside the level. Code that acts on individual taps (Toth 2013's Discard drops the taps
//    outside the face and renormalises) works on that list.
//  * Driver (`Texture`): owns the levels of every layer in linear-light float RGBA, builds mip
//    chains, and resolves taps to texels. `Texture::sample` runs exactly the same tap generator
//    as `Texture::taps` and accumulates in the same order, so `sample` and
//    `resolve(taps(...))` agree bit for bit.
//
// Conventions
//  * Texture coordinates (u, v) are normalised: [0, 1] spans level 0, u to the right, v down
//    (v = 0 is the first row). Texel (x, y) of a level of size w x h has its centre at
//    ((x + 0.5) / w, (y + 0.5) / h), as in GL and D3D.
//  * Gradients (`UvGradients`) are derivatives of (u, v) per screen pixel, in normalised units,
//    like the arguments of GLSL `textureGrad`; the kernel scales them by the level-0 size to get
//    the footprint in texels of level 0.
//  * Mip level sizes follow GL for any size: level l is max(1, floor(w / 2^l)) x
//    max(1, floor(h / 2^l)), down to 1x1 (so 5x3 -> 2x1 -> 1x1).
//  * Colours are linear RGBA floats; alpha is straight (not premultiplied).
//
// Discard (Toth 2013) either way: walk `Texture::taps` and drop the taps marked `outside`, then
// divide by the remaining weight; or, cheaper, sample with `AddressMode::border`, a zero border
// colour and alpha 1 in the texture, and divide rgb by a (the two agree; see texture_test).
//
// Thread safety: a `Texture` is immutable after construction; all its const methods (sampling
// included) may be called concurrently from any number of threads. Kernel functions are pure.
// Nothing on the sampling path allocates.
// Tests: tests/unit/texture_test.cpp, texture_filtering_test.cpp.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "tessera/core.h"

namespace tessera::texture {

// ---------------------------------------------------------------------------------------------
// Sampler state
// ---------------------------------------------------------------------------------------------

/// Filter applied within and between mip levels.
enum class TextureFilter {
  nearest,      ///< Nearest texel of the nearest level (GL_NEAREST_MIPMAP_NEAREST). 1 tap;
                ///< a footprint's probes are ignored.
  bilinear,     ///< 2x2 bilinear in the nearest level (GL_LINEAR_MIPMAP_NEAREST). 4 taps.
  trilinear,    ///< Bilinear in the two nearest levels, blended by the fractional LOD. <= 8 taps.
  anisotropic,  ///< N trilinear probes along the footprint's major axis. <= 16 * 8 taps.
};

/// What a texel coordinate outside [0, size) reads.
enum class AddressMode {
  wrap,    ///< Repeat with period size (GL_REPEAT).
  clamp,   ///< Clamp to the edge texel (GL_CLAMP_TO_EDGE).
  mirror,  ///< Mirror with period 2 * size (GL_MIRRORED_REPEAT).
  border,  ///< Read `SamplerState::border_color` (GL_CLAMP_TO_BORDER).
};

/// Sampler settings: a plain struct, like a GL sampler object. Out-of-range values are clamped
/// where they are used, so no setting can make a lookup read outside the texture.
struct SamplerState {
  TextureFilter filter = TextureFilter::trilinear;
  AddressMode address_u = AddressMode::wrap;
  AddressMode address_v = AddressMode::wrap;
  /// Linear RGBA returned by border taps (transparent black by default, as Discard needs);
  /// GL TEXTURE_BORDER_COLOR, named after it.
  std::array<float, 4> border_color = {0.0f, 0.0f, 0.0f, 0.0f};
  /// Largest probe count of anisotropic filtering, clamped to [1, 16].
  int max_aniso = 16;
  /// Added to the computed LOD before clamping (GL TEXTURE_LOD_BIAS), in levels.
  float lod_bias = 0.0f;
  /// LOD clamp range (GL TEXTURE_MIN_LOD / MAX_LOD); the result is further clamped to
  /// [0, levels - 1]. `max_lod = 0` disables mipmapping.
  float min_lod = -1000.0f;
  float max_lod = 1000.0f;
};

// ---------------------------------------------------------------------------------------------
// Kernel: footprints, LOD, addressing and taps (pure functions)
// ---------------------------------------------------------------------------------------------

/// Largest number of mip levels (a 65536 texel side has 17).
inline constexpr int kMaxMipLevels = 17;
/// Largest anisotropic probe count.
inline constexpr int kMaxAnisotropy = 16;
/// Capacity of a tap list: 16 probes x 2 levels x 4 bilinear taps.
inline constexpr int kMaxTexelTaps = kMaxAnisotropy * 2 * 4;

/// A texture coordinate pair, normalised (see the conventions above).
struct Uv {
  float u = 0.0f;
  float v = 0.0f;
};

/// Screen-space derivatives of (u, v): d/dx along a pixel row, d/dy down a pixel column.
/// Normalised units per pixel when passed to samplers; texels of level 0 per pixel when passed
/// to `isotropic_lod` / `anisotropic_footprint`.
struct UvGradients {
  float dudx = 0.0f;
  float dvdx = 0.0f;
  float dudy = 0.0f;
  float dvdy = 0.0f;
};

/// Coarse derivatives of a 2x2 pixel quad, as a GPU computes them for implicit-gradient
/// sampling: `quad` holds the coordinates of pixels (x, y), (x+1, y), (x, y+1), (x+1, y+1) in
/// that order; d/dx = quad[1] - quad[0], d/dy = quad[2] - quad[0], shared by all four pixels.
UvGradients quad_gradients(const std::array<Uv, 4>& quad);

/// Size and level/layer counts of a texture: all the kernel needs to know about storage.
struct TextureShape {
  int width = 0;   ///< Level-0 width in texels, >= 1.
  int height = 0;  ///< Level-0 height in texels, >= 1.
  int levels = 1;  ///< Mip levels, 1..kMaxMipLevels (and at most the full chain).
  int layers = 1;  ///< Array layers, >= 1.

  /// Width of level `level` (GL rule): max(1, width >> level) (`mip_dimension`).
  int level_width(int level) const { return mip_dimension(width, level); }
  /// Height of level `level`: max(1, height >> level).
  int level_height(int level) const { return mip_dimension(height, level); }
};

/// Isotropic LOD before bias and clamping (GL): log2 of the longer of the two gradient
/// vectors, given in texels of level 0 per pixel. -infinity for zero gradients.
float isotropic_lod(const UvGradients& texel_gradients);

/// Anisotropic footprint per EXT_texture_filter_anisotropic: Px = |d/dx|, Py = |d/dy|
/// (texels of level 0), Pmax / Pmin their larger / smaller, N = min(ceil(Pmax / Pmin), max_aniso)
/// probes, LOD = log2(Pmax / N). `axis_*` is the major-axis gradient vector (the longer one).
struct AnisoFootprint {
  int probes = 1;
  float lod = 0.0f;  ///< Before bias and clamping; -infinity for zero gradients.
  float axis_x = 0.0f;
  float axis_y = 0.0f;
};

/// Computes the anisotropic footprint of gradients in texels of level 0. `max_aniso` is
/// clamped to [1, kMaxAnisotropy]. The ratio is rounded up with a 1e-4 tolerance so that an
/// exact k:1 footprint computed in floating point gives k probes, not k + 1.
AnisoFootprint anisotropic_footprint(const UvGradients& texel_gradients, int max_aniso);

/// Everything the tap generator needs for one lookup, with LOD already biased and clamped.
struct Footprint {
  Uv centre;            ///< Lookup position, normalised.
  float axis_u = 0.0f;  ///< Major axis of the footprint (normalised units, full pixel extent);
  float axis_v = 0.0f;  ///< probes lie at centre + ((i + 0.5) / N - 0.5) * axis.
  int probes = 1;       ///< N (1 unless anisotropic).
  float lod = 0.0f;     ///< Final LOD in [0, levels - 1].
};

/// Footprint of a lookup at `uv` with explicit gradients (normalised units), the `textureGrad`
/// analogue: LOD from the gradients (isotropic or anisotropic per `sampler.filter`), plus
/// `lod_bias`, clamped to [min_lod, max_lod] and then to [0, levels - 1]. Non-finite gradients
/// still give a finite LOD in range (NaN counts as 0); non-finite coordinates are passed through
/// and clamped to +-2^24 texels when taps are generated.
Footprint compute_footprint(const SamplerState& sampler, const TextureShape& shape, Uv uv,
                            const UvGradients& gradients);

/// Footprint of a lookup at an explicit LOD (the `textureLod` analogue): one probe, `lod` plus
/// `lod_bias` clamped as in `compute_footprint`.
Footprint footprint_at_lod(const SamplerState& sampler, const TextureShape& shape, Uv uv,
                           float lod);

/// Resolves integer texel coordinate `x` along an axis of `size` texels: wrap -> x mod size,
/// clamp -> nearest of [0, size - 1], mirror -> period 2 * size reflected (size .. 2size-1 map
/// to size-1 .. 0), border -> x inside [0, size) else -1. Any int, including negatives.
int resolve_address(int x, int size, AddressMode mode);

/// Array layer of a floating-point layer coordinate (GL): clamp(floor(r + 0.5), 0, layers - 1).
int array_layer(float r, int layers);

/// One weighted texel of a filter evaluation.
struct TexelTap {
  int level = 0;         ///< Mip level.
  int layer = 0;         ///< Array layer (already clamped).
  int x = 0;             ///< Texel column before address resolution (may be < 0 or >= width).
  int y = 0;             ///< Texel row before address resolution.
  int resolved_x = 0;    ///< Column after address resolution; -1 for a border tap outside.
  int resolved_y = 0;    ///< Row after address resolution; -1 for a border tap outside.
  float weight = 0.0f;   ///< Filter weight; the weights of one lookup sum to 1.
  bool outside = false;  ///< (x, y) was outside [0, width) x [0, height) of its level.

  /// True when the tap reads the border colour instead of a texel.
  bool is_border() const { return resolved_x < 0 || resolved_y < 0; }
};

/// Caller-owned, fixed-capacity list of taps (no allocation). Bilinear quads always contribute
/// all four taps (some may weigh 0); a level whose trilinear weight is 0 contributes none.
struct TapList {
  std::array<TexelTap, kMaxTexelTaps> taps;
  int count = 0;

  const TexelTap* begin() const { return taps.data(); }
  const TexelTap* end() const { return taps.data() + count; }
  /// Sum of the weights (1 up to rounding for a complete lookup).
  float weight_sum() const;
};

/// Generates the taps of `footprint` on layer `layer` (clamped to [0, layers - 1]) into `out`
/// (overwritten; at most kMaxTexelTaps). Pure: depends only on its arguments.
void generate_taps(const SamplerState& sampler, const TextureShape& shape,
                   const Footprint& footprint, int layer, TapList& out);

// ---------------------------------------------------------------------------------------------
// Driver: texture storage and sampling
// ---------------------------------------------------------------------------------------------

/// How a texture is built.
struct TextureOptions {
  /// 8-bit input colour is sRGB-encoded: decode to linear light before filtering (the
  /// gamma-correct chain). `false` maps bytes linearly to [0, 1]. Alpha is always linear.
  /// Ignored for float input, which is taken as linear.
  bool srgb = true;
  /// Alpha-weighted downsampling: colour is averaged weighted by alpha so transparent texels do
  /// not bleed; a fully transparent footprint keeps the plain average.
  bool alpha_weighted = false;
  /// Mip levels to build including level 0; 0 = the full chain down to 1x1, 1 = no mipmaps.
  int max_levels = 0;
  /// Worker threads for chain construction (0 = all). Results do not depend on it.
  int threads = 0;
};

/// Read-only view of one level of one layer: width * height RGBA float texels, row-major.
/// Valid while the texture lives and is not assigned to.
struct TextureLevelView {
  int width = 0;
  int height = 0;
  const float* texels = nullptr;

  const float* at(int x, int y) const { return texels + (std::size_t(y) * width + x) * 4; }
};

/// An immutable mipmapped 2D texture or texture array in linear float RGBA.
///
/// Built by one of the `from_*` factories (which validate and return a status), then sampled
/// with a `SamplerState`. Copyable and movable; every const method is thread-safe.
class Texture {
 public:
  /// An empty texture (0x0, no levels); only `empty()` and the shape accessors are valid.
  Texture() = default;

  /// Builds a texture (one layer) from 8-bit RGBA, decoding sRGB per `options.srgb`, and its
  /// mip chain. Fails with invalid_argument on an empty image.
  static Result<Texture> from_rgba8(const ImageRGBA8& image, const TextureOptions& options = {});
  /// Builds a texture from linear float RGBA and its mip chain.
  static Result<Texture> from_float(const ImageRGBAF& image, const TextureOptions& options = {});
  /// Builds a texture array; all layers must have the same size (size_mismatch otherwise).
  static Result<Texture> array_from_rgba8(const std::vector<ImageRGBA8>& layers,
                                          const TextureOptions& options = {});
  /// Builds a float texture array; all layers must have the same size.
  static Result<Texture> array_from_float(const std::vector<ImageRGBAF>& layers,
                                          const TextureOptions& options = {});
  /// Uses `levels` as a ready-made chain of one layer (e.g. loaded from a KTX file): level i
  /// must be exactly level_width(i) x level_height(i) of level 0; 1..kMaxMipLevels levels.
  static Result<Texture> from_float_levels(std::vector<ImageRGBAF> levels);

  bool empty() const { return shape_.width == 0; }
  const TextureShape& shape() const { return shape_; }
  int width() const { return shape_.width; }
  int height() const { return shape_.height; }
  int level_count() const { return shape_.levels; }
  int layer_count() const { return shape_.layers; }

  /// Texels of `level` of `layer` (both must be in range).
  TextureLevelView level(int layer, int level) const;
  /// A copy of `level` of `layer` as an image.
  ImageRGBAF level_image(int layer, int level) const;

  /// Filtered lookup with explicit gradients (normalised units per pixel): GLSL `textureGrad`.
  /// `layer` is clamped to [0, layers - 1]. Returns linear RGBA.
  std::array<float, 4> sample(const SamplerState& sampler, Uv uv, const UvGradients& gradients,
                              int layer = 0) const;
  /// Four independent `sample` lookups, e.g. the pixels of a 2x2 quad with per-pixel (fine)
  /// gradients: for every lane i whose bit is set in `active` (bits 0..3),
  /// `out[i] = sample(sampler, uv[i], gradients[i], layer)`, bit for bit. Other lanes' outputs
  /// are left as they were; their inputs must be initialised but do not matter. Bilinear and
  /// trilinear lookups share the footprint, LOD, level and weight arithmetic across the four lanes
  /// (SSE2 where available); texels are still read and weighted per lane.
  void sample4(const SamplerState& sampler, const std::array<Uv, 4>& uv,
               const std::array<UvGradients, 4>& gradients, std::uint32_t active,
               std::array<std::array<float, 4>, 4>& out, int layer = 0) const;
  /// Filtered lookup at an explicit LOD (one probe even when anisotropic): GLSL `textureLod`.
  std::array<float, 4> sample_lod(const SamplerState& sampler, Uv uv, float lod,
                                  int layer = 0) const;
  /// Implicit-gradient lookup of a 2x2 pixel quad (GLSL `texture` in a fragment shader):
  /// gradients from `quad_gradients(quad)`, shared by the four lookups; results in quad order.
  std::array<std::array<float, 4>, 4> sample_quad(const SamplerState& sampler,
                                                  const std::array<Uv, 4>& quad,
                                                  int layer = 0) const;
  /// Lookup of an already computed footprint (e.g. one adjusted by the caller).
  std::array<float, 4> sample_footprint(const SamplerState& sampler, const Footprint& footprint,
                                        int layer = 0) const;

  /// The filter evaluation of `sample(sampler, uv, gradients, layer)` as weighted taps.
  void taps(const SamplerState& sampler, Uv uv, const UvGradients& gradients, int layer,
            TapList& out) const;
  /// Value of one tap: its texel, or `sampler.border_color` for a border tap.
  std::array<float, 4> fetch(const SamplerState& sampler, const TexelTap& tap) const;
  /// Weighted sum of the taps' values (no renormalisation), in list order.
  std::array<float, 4> resolve(const SamplerState& sampler, const TapList& taps) const;

 private:
  TextureShape shape_{0, 0, 0, 0};
  /// All texels: layer-major, then level, then rows. `offsets_[layer * levels + level]` is the
  /// float index of that level's first texel.
  std::vector<float> texels_;
  std::vector<std::size_t> offsets_;

  friend struct TextureBuilder;
};

// ---------------------------------------------------------------------------------------------
// Mip chain construction (also usable on its own)
// ---------------------------------------------------------------------------------------------

/// One box-downsampling step to max(1, w/2) x max(1, h/2): each output texel is the exact
/// area average of the source region it covers (fractional weights at odd sizes), so the mean
/// is preserved. Linear float input; alpha-weighted when `options.alpha_weighted`, on
/// `options.threads` threads (deterministic for any); the other options do not apply.
ImageRGBAF downsample_box(const ImageRGBAF& image, const TextureOptions& options = {});

/// Full chain (level 0 = a copy of `image`) by repeated `downsample_box`: exactly the levels
/// `Texture::from_float(image, options)` holds. `options.max_levels` levels at most (0 = down
/// to 1x1), alpha-weighted per `options.alpha_weighted`, on `options.threads` threads;
/// `options.srgb` does not apply (float input is linear). Empty input gives an empty vector.
std::vector<ImageRGBAF> build_mip_chain(const ImageRGBAF& image,
                                        const TextureOptions& options = {});

}  // namespace tessera::texture
