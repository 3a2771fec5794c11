// Kernel: the 16 edge-to-edge UV transforms of quad faces (pure functions).
//
// Each edge e of the unit square has an origin corner c_e, a direction d_e (towards c_{e+1})
// and an inward normal n_e = (-d_e.y, d_e.x). A point is (t, s) in the edge's frame when
// uv = c_e + t d_e + s n_e. Across a shared edge the neighbour walks the edge backwards and
// its inside is my outside, so my (t, s) is the neighbour's (1 - t, -s).
#include <cmath>

#include "core/check.h"
#include "tessera/faces.h"

namespace tessera::faces {

namespace {
struct EdgeFrame {
  float cu, cv;  // origin corner
  float du, dv;  // direction along the edge
  float nu, nv;  // inward normal
};

constexpr EdgeFrame kFrames[4] = {
    {0, 0, 1, 0, 0, 1},    // edge 0: (0,0) -> (1,0), v = 0
    {1, 0, 0, 1, -1, 0},   // edge 1: (1,0) -> (1,1), u = 1
    {1, 1, -1, 0, 0, -1},  // edge 2: (1,1) -> (0,1), v = 1
    {0, 1, 0, -1, 1, 0},   // edge 3: (0,1) -> (0,0), u = 0
};

UvTransform build(int my_edge, int nb_edge) {
  const EdgeFrame& m = kFrames[my_edge & 3];
  const EdgeFrame& n = kFrames[nb_edge & 3];
  // t = (u - cu) du + (v - cv) dv ; s = (u - cu) nu + (v - cv) nv  (orthonormal frame)
  // uv' = n.c + (1 - t) n.d - s n.n
  UvTransform r;
  // Coefficients of t and s in (u, v, 1).
  const float ta = m.du, tb = m.dv, tc = -(m.cu * m.du + m.cv * m.dv);
  const float sa = m.nu, sb = m.nv, sc = -(m.cu * m.nu + m.cv * m.nv);
  r.a = -ta * n.du - sa * n.nu;
  r.b = -tb * n.du - sb * n.nu;
  r.c = n.cu + n.du - tc * n.du - sc * n.nu;
  r.d = -ta * n.dv - sa * n.nv;
  r.e = -tb * n.dv - sb * n.nv;
  r.f = n.cv + n.dv - tc * n.dv - sc * n.nv;
  return r;
}
}  // namespace

UvTransform UvTransform::then(const UvTransform& n) const {
  UvTransform r;
  r.a = n.a * a + n.b * d;
  r.b = n.a * b + n.b * e;
  r.c = n.a * c + n.b * f + n.c;
  r.d = n.d * a + n.e * d;
  r.e = n.d * b + n.e * e;
  r.f = n.d * c + n.e * f + n.f;
  return r;
}

UvTransform edge_transform(int my_edge, int neighbour_edge) {
  TESSERA_DCHECK(my_edge >= 0 && my_edge < 4 && neighbour_edge >= 0 && neighbour_edge < 4);
  return edge_transform_table()[std::size_t((my_edge & 3) * 4 + (neighbour_edge & 3))];
}

const std::array<UvTransform, 16>& edge_transform_table() {
  static const std::array<UvTransform, 16> table = [] {
    std::array<UvTransform, 16> t;
    for (int i = 0; i < 16; ++i) t[std::size_t(i)] = build(i / 4, i % 4);
    return t;
  }();
  return table;
}

}  // namespace tessera::faces
