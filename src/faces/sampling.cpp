// The sampling methods: Clamp, Discard (Toth 2013), Traverse (McDonald 2013, Listing 1) and
// Traverse with valence-4 corners. The tap arithmetic is the kernel's (Texture::sample with
// border addressing returns Σ w·T in rgb and Σ w in alpha, since alpha is the coverage channel);
// this file is the traversal driver.
#include <cmath>

#include "tessera/faces.h"

namespace tessera::faces {

namespace {
texture::SamplerState make_sampler(const SampleOptions& o, texture::AddressMode mode) {
  texture::SamplerState s;
  s.filter = o.filter;
  s.max_aniso = o.max_aniso;
  s.address_u = mode;
  s.address_v = mode;
  s.border_color = {0.0f, 0.0f, 0.0f, 0.0f};
  return s;
}

inline void add(std::array<float, 4>& acc, const std::array<float, 4>& c) {
  for (int k = 0; k < 4; ++k) acc[std::size_t(k)] += c[std::size_t(k)];
}
}  // namespace

const std::vector<SeamMethod>& all_methods() {
  static const std::vector<SeamMethod> m = {SeamMethod::clamp, SeamMethod::discard,
                                            SeamMethod::traverse, SeamMethod::traverse_corners};
  return m;
}

const char* method_name(SeamMethod m) {
  switch (m) {
    case SeamMethod::clamp:
      return "clamp";
    case SeamMethod::discard:
      return "discard";
    case SeamMethod::traverse:
      return "traverse";
    case SeamMethod::traverse_corners:
      return "traverse_corners";
  }
  return "?";
}

bool parse_method(const std::string& text, SeamMethod& out) {
  for (SeamMethod m : all_methods()) {
    if (text == method_name(m)) {
      out = m;
      return true;
    }
  }
  return false;
}

namespace {
// Normalises a border-lookup sum `c` of face `face` (Listing 1, line 17), or, when no tap was
// covered, falls back to a clamped lookup (lines 13-15): coverage 0 then. GLSL:
// tessera_seams_resolve.
std::array<float, 4> resolve(const std::array<float, 4>& c, const texture::Texture& tex,
                             texture::Uv uv, const texture::UvGradients& g,
                             const SampleOptions& options) {
  const float w = c[3];
  if (!(w > 0.0f)) {
    if (!options.clamp_fallback) {
      const float nan = std::nanf("");
      return {nan, nan, nan, 0.0f};
    }
    std::array<float, 4> f = tex.sample(make_sampler(options, texture::AddressMode::clamp), uv, g);
    f[3] = 0.0f;
    return f;
  }
  const float inv = 1.0f / w;  // Equation 6
  return {c[0] * inv, c[1] * inv, c[2] * inv, w};
}

// Traverse's taps: the own face with border colour 0 (Listing 1, line 2; alpha accumulates
// Σw), the four edge neighbours in their own UV spaces (lines 4-12) and, with `corners`, the
// diagonal face at each valence-4 corner; not yet normalised.
std::array<float, 4> traverse_sum(const FaceTextureSet& set, int face, texture::Uv uv,
                                  const texture::UvGradients& g, const SampleOptions& options,
                                  bool corners) {
  const texture::SamplerState border = make_sampler(options, texture::AddressMode::border);
  std::array<float, 4> c = set.texture(face).sample(border, uv, g);
  const FaceAdjacency& adj = set.adjacency(face);
  for (int e = 0; e < 4; ++e) {
    const int nb = adj.face[std::size_t(e)];
    if (nb < 0) continue;
    const UvTransform& t = edge_transform(e, adj.edge[std::size_t(e)]);
    add(c, set.texture(nb).sample(border, t.apply(uv), t.apply(g)));
  }
  if (corners) {
    for (int k = 0; k < 4; ++k) {
      const CornerLink& l = set.corner(face, k);
      if (l.face < 0) continue;
      add(c, set.texture(l.face).sample(border, l.transform.apply(uv), l.transform.apply(g)));
    }
  }
  return c;
}
}  // namespace

std::array<float, 4> sample_clamp(const FaceTextureSet& set, int face, texture::Uv uv,
                                  const texture::UvGradients& g, const SampleOptions& options) {
  const texture::Texture& tex = set.texture(face);
  std::array<float, 4> c = tex.sample(make_sampler(options, texture::AddressMode::clamp), uv, g);
  c[3] = 1.0f;
  return c;
}

std::array<float, 4> sample_discard(const FaceTextureSet& set, int face, texture::Uv uv,
                                    const texture::UvGradients& g, const SampleOptions& options) {
  const texture::Texture& tex = set.texture(face);
  // Listing 1, line 2 alone: the own face with border colour 0; alpha accumulates Σw.
  const std::array<float, 4> c =
      tex.sample(make_sampler(options, texture::AddressMode::border), uv, g);
  return resolve(c, tex, uv, g, options);
}

std::array<float, 4> sample_traverse(const FaceTextureSet& set, int face, texture::Uv uv,
                                     const texture::UvGradients& g, const SampleOptions& options) {
  return resolve(traverse_sum(set, face, uv, g, options, false), set.texture(face), uv, g, options);
}

std::array<float, 4> sample_traverse_corners(const FaceTextureSet& set, int face, texture::Uv uv,
                                             const texture::UvGradients& g,
                                             const SampleOptions& options) {
  return resolve(traverse_sum(set, face, uv, g, options, true), set.texture(face), uv, g, options);
}

std::array<float, 4> sample_face(const FaceTextureSet& set, int face, texture::Uv uv,
                                 const texture::UvGradients& g, const SampleOptions& options) {
  switch (options.method) {
    case SeamMethod::clamp:
      return sample_clamp(set, face, uv, g, options);
    case SeamMethod::discard:
      return sample_discard(set, face, uv, g, options);
    case SeamMethod::traverse:
      return sample_traverse(set, face, uv, g, options);
    case SeamMethod::traverse_corners:
      return sample_traverse_corners(set, face, uv, g, options);
  }
  return sample_discard(set, face, uv, g, options);
}

}  // namespace tessera::faces
