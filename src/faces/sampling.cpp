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
  static const std::vector<SeamMethod> m = {SeamMethod::clamp, SeamMethod::discard, SeamMethod::traverse,
                                        SeamMethod::traverse_corners};
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

std::array<float, 4> sample_face(const FaceTextureSet& set, int face, texture::Uv uv,
                                 const texture::UvGradients& g, const SampleOptions& options) {
  const texture::Texture& tex = set.texture(face);
  if (options.method == SeamMethod::clamp) {
    std::array<float, 4> c = tex.sample(make_sampler(options, texture::AddressMode::clamp), uv, g);
    c[3] = 1.0f;
    return c;
  }
  const texture::SamplerState border = make_sampler(options, texture::AddressMode::border);
  // Listing 1, line 2: the own face with border colour 0; alpha accumulates Σw.
  std::array<float, 4> c = tex.sample(border, uv, g);
  if (options.method == SeamMethod::traverse || options.method == SeamMethod::traverse_corners) {
    // Lines 4-12: the four edge neighbours in their own UV spaces.
    const FaceAdjacency& adj = set.adjacency(face);
    for (int e = 0; e < 4; ++e) {
      const int nb = adj.face[std::size_t(e)];
      if (nb < 0) continue;
      const UvTransform& t = edge_transform(e, adj.edge[std::size_t(e)]);
      add(c, set.texture(nb).sample(border, t.apply(uv), t.apply(g)));
    }
    if (options.method == SeamMethod::traverse_corners) {
      for (int k = 0; k < 4; ++k) {
        const CornerLink& l = set.corner(face, k);
        if (l.face < 0) continue;
        add(c, set.texture(l.face).sample(border, l.transform.apply(uv), l.transform.apply(g)));
      }
    }
  }
  const float w = c[3];
  if (!(w > 0.0f)) {
    if (!options.clamp_fallback) {
      const float nan = std::nanf("");
      return {nan, nan, nan, 0.0f};
    }
    // Lines 13-15: no tap inside the face; clamp the lookup (bi/trilinear as configured).
    std::array<float, 4> f = tex.sample(make_sampler(options, texture::AddressMode::clamp), uv, g);
    f[3] = 0.0f;
    return f;
  }
  // Line 17: normalise by the summed coverage (Equation 6).
  const float inv = 1.0f / w;
  return {c[0] * inv, c[1] * inv, c[2] * inv, w};
}

}  // namespace tessera::faces
