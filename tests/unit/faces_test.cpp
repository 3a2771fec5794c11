// Per-face texturing: edge transforms, adjacency, the sampling methods (Discard, Traverse,
// corners), the Figure-1 scene and rendering.
#include "tessera/faces.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <set>

#include "tessera/faces_gpu.h"
#include "test_support.h"

namespace tessera {
namespace {

using faces::FaceAdjacency;
using faces::QuadMesh;
using faces::SeamMethod;
using texture::TextureFilter;
using texture::Uv;
using texture::UvGradients;

/// Two unit squares side by side in the xz plane (x in [0,2]), with vertex orders rotated by
/// r0 and r1, so the shared edge has pairing (e0, e1) for some e0, e1.
QuadMesh two_quads(int r0, int r1) {
  QuadMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 0, 1}, {1, 0, 1}, {2, 0, 1}};
  std::array<int, 4> a = {0, 3, 4, 1}, b = {1, 4, 5, 2};  // same winding
  std::array<int, 4> ra, rb;
  for (int i = 0; i < 4; ++i) {
    ra[std::size_t(i)] = a[std::size_t((i + r0) & 3)];
    rb[std::size_t(i)] = b[std::size_t((i + r1) & 3)];
  }
  m.quads = {ra, rb};
  return m;
}

float dist(const Vec3& a, const Vec3& b) { return length(a - b); }

TEST(Faces, AllSixteenTransformsAgreeIn3D) {
  std::array<int, 16> seen{};
  for (int r0 = 0; r0 < 4; ++r0) {
    for (int r1 = 0; r1 < 4; ++r1) {
      const QuadMesh m = two_quads(r0, r1);
      Result<std::vector<FaceAdjacency>> adj = faces::build_adjacency(m);
      ASSERT_TRUE(adj.ok()) << adj.status().message;
      int e0 = -1;
      for (int e = 0; e < 4; ++e) {
        if ((*adj)[0].face[std::size_t(e)] == 1) e0 = e;
      }
      ASSERT_GE(e0, 0);
      const int e1 = (*adj)[0].edge[std::size_t(e0)];
      EXPECT_EQ((*adj)[1].face[std::size_t(e1)], 0);
      EXPECT_EQ((*adj)[1].edge[std::size_t(e1)], e0);
      ++seen[std::size_t(e0 * 4 + e1)];
      const faces::UvTransform t = faces::edge_transform(e0, e1);
      const faces::UvTransform back = faces::edge_transform(e1, e0);
      // Points on my edge e0 (and, the squares being coplanar unit squares, points beyond it)
      // land on the same 3D position in the neighbour.
      const float corners[5][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0, 0}};
      for (int k = 0; k <= 8; ++k) {
        const float s = float(k) / 8.0f;
        const Uv on{corners[e0][0] + s * (corners[e0 + 1][0] - corners[e0][0]),
                    corners[e0][1] + s * (corners[e0 + 1][1] - corners[e0][1])};
        const Uv mapped = t.apply(on);
        EXPECT_LT(dist(m.point(0, on), m.point(1, mapped)), 1e-6f) << e0 << " " << e1;
        const Uv round = back.apply(mapped);
        EXPECT_NEAR(round.u, on.u, 1e-6f);
        EXPECT_NEAR(round.v, on.v, 1e-6f);
        // A point 0.25 outside my edge is inside the neighbour.
        const Uv centre{0.5f, 0.5f};
        const Uv out{on.u + 0.25f * 2 * (on.u - centre.u) * (e0 % 2 == 1 ? 1.0f : 0.0f),
                     on.v + 0.25f * 2 * (on.v - centre.v) * (e0 % 2 == 0 ? 1.0f : 0.0f)};
        const Uv in = t.apply(out);
        EXPECT_GE(in.u, -1e-6f);
        EXPECT_LE(in.u, 1 + 1e-6f);
        EXPECT_GE(in.v, -1e-6f);
        EXPECT_LE(in.v, 1 + 1e-6f);
        EXPECT_LT(dist(m.point(0, out), m.point(1, in)), 1e-5f);
      }
    }
  }
  for (int i = 0; i < 16; ++i) EXPECT_EQ(seen[std::size_t(i)], 1) << "pairing " << i;
}

TEST(Faces, AdjacencyRejectsBadMeshes) {
  QuadMesh m = two_quads(0, 0);
  std::swap(m.quads[1][1], m.quads[1][3]);  // flip the second face's winding
  EXPECT_FALSE(faces::build_adjacency(m).ok());
  QuadMesh d = two_quads(0, 0);
  d.quads[0][1] = d.quads[0][0];
  EXPECT_FALSE(faces::build_adjacency(d).ok());
}

/// A 2-face set: face textures from a colour function of the 3D position.
struct TwoFaces {
  QuadMesh mesh;
  faces::FaceTextureSet set;
};

TwoFaces make_two_faces(int r0, int r1, int size, bool constant_per_face) {
  TwoFaces t;
  t.mesh = two_quads(r0, r1);
  std::vector<ImageRGBAF> images;
  for (int f = 0; f < 2; ++f) {
    ImageRGBAF img(size, size);
    for (int y = 0; y < size; ++y) {
      for (int x = 0; x < size; ++x) {
        const Vec3 p =
            t.mesh.point(f, {(float(x) + 0.5f) / float(size), (float(y) + 0.5f) / float(size)});
        float* px = img.at(x, y);
        px[0] = constant_per_face ? (f == 0 ? 0.2f : 0.9f) : 0.1f + 0.4f * p.x;
        px[1] = constant_per_face ? 0.5f : 0.2f + 0.6f * p.z;
        px[2] = constant_per_face ? 0.1f : 0.3f + 0.1f * p.x * p.z;
        px[3] = 1;
      }
    }
    images.push_back(img);
  }
  Result<std::vector<FaceAdjacency>> adj = faces::build_adjacency(t.mesh);
  EXPECT_TRUE(adj.ok());
  Result<faces::FaceTextureSet> set = faces::FaceTextureSet::create(images, *adj, {1});
  EXPECT_TRUE(set.ok());
  t.set = std::move(*set);
  return t;
}

faces::SampleOptions opts(SeamMethod m, TextureFilter f = TextureFilter::anisotropic) {
  faces::SampleOptions o;
  o.method = m;
  o.filter = f;
  return o;
}

TEST(Faces, InFaceSamplesAreIdenticalForAllMethods) {
  const TwoFaces t = make_two_faces(1, 3, 32, false);
  const UvGradients g{0.01f, 0.002f, -0.003f, 0.02f};  // anisotropic, well inside the face
  for (float u : {0.3f, 0.5f, 0.7f}) {
    const std::array<float, 4> ref =
        faces::sample_face(t.set, 0, {u, 0.4f}, g, opts(SeamMethod::clamp));
    for (SeamMethod m : faces::all_methods()) {
      const std::array<float, 4> c = faces::sample_face(t.set, 0, {u, 0.4f}, g, opts(m));
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(c[std::size_t(k)], ref[std::size_t(k)], 1e-6f);
    }
    // Traverse adds exact zeros: it equals Discard bit for bit.
    EXPECT_EQ(faces::sample_face(t.set, 0, {u, 0.4f}, g, opts(SeamMethod::traverse)),
              faces::sample_face(t.set, 0, {u, 0.4f}, g, opts(SeamMethod::discard)));
  }
}

TEST(Faces, DiscardRenormalisesWeightsToOne) {
  // Constant colour per face: near the seam Discard returns exactly the face's own colour
  // (in-face weights renormalised to 1), Traverse blends with the neighbour.
  const TwoFaces t = make_two_faces(0, 2, 16, true);
  int e0 = -1;
  for (int e = 0; e < 4; ++e) {
    if (t.set.adjacency(0).face[std::size_t(e)] == 1) e0 = e;
  }
  ASSERT_GE(e0, 0);
  const float corners[4][2] = {{0.5f, 0.02f}, {0.98f, 0.5f}, {0.5f, 0.98f}, {0.02f, 0.5f}};
  const Uv near_edge{corners[e0][0], corners[e0][1]};
  const UvGradients g{0.15f, 0.0f, 0.0f, 0.15f};  // footprint much wider than the distance
  const std::array<float, 4> d =
      faces::sample_face(t.set, 0, near_edge, g, opts(SeamMethod::discard));
  EXPECT_NEAR(d[0], 0.2f, 1e-6f);
  EXPECT_GT(d[3], 0.0f);
  EXPECT_LT(d[3], 1.0f);  // some taps were outside
  // Σw over in-face taps from the tap list equals the coverage the method divided by.
  texture::SamplerState s;
  s.filter = TextureFilter::anisotropic;
  s.address_u = s.address_v = texture::AddressMode::border;
  texture::TapList taps;
  t.set.texture(0).taps(s, near_edge, g, 0, taps);
  float in_w = 0;
  for (const texture::TexelTap& tap : taps) in_w += tap.outside ? 0.0f : tap.weight;
  EXPECT_NEAR(in_w, d[3], 1e-5f);
  const std::array<float, 4> tr =
      faces::sample_face(t.set, 0, near_edge, g, opts(SeamMethod::traverse));
  EXPECT_GT(tr[0], 0.25f);          // blended towards the neighbour's 0.9
  EXPECT_NEAR(tr[3], 1.0f, 1e-4f);  // both faces together cover the footprint
}

TEST(Faces, TraverseIsContinuousAcrossAnEdgeAtMagnification) {
  for (int r0 = 0; r0 < 4; ++r0) {
    for (int r1 = 0; r1 < 4; ++r1) {
      const TwoFaces t = make_two_faces(r0, r1, 8, false);
      int e0 = -1;
      for (int e = 0; e < 4; ++e) {
        if (t.set.adjacency(0).face[std::size_t(e)] == 1) e0 = e;
      }
      const faces::UvTransform tr =
          faces::edge_transform(e0, t.set.adjacency(0).edge[std::size_t(e0)]);
      const UvGradients g{0.001f, 0, 0, 0.001f};  // magnification: bilinear in level 0
      const float pts[4][2] = {{0.37f, 0}, {1, 0.37f}, {0.37f, 1}, {0, 0.37f}};
      const Uv on{pts[e0][0], pts[e0][1]};
      const std::array<float, 4> a =
          faces::sample_face(t.set, 0, on, g, opts(SeamMethod::traverse, TextureFilter::trilinear));
      const std::array<float, 4> b =
          faces::sample_face(t.set, 1, tr.apply(on), tr.apply(g),
                             opts(SeamMethod::traverse, TextureFilter::trilinear));
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(a[std::size_t(k)], b[std::size_t(k)], 1e-5f);
      // The texture is linear in 3D, so bilinear reconstruction across the seam is exact
      // (the value at the edge is the function there); Discard and Clamp are not.
      const Vec3 p = t.mesh.point(0, on);
      EXPECT_NEAR(a[0], 0.1f + 0.4f * p.x, 1e-5f);
      EXPECT_NEAR(a[1], 0.2f + 0.6f * p.z, 1e-5f);
    }
  }
}

TEST(Faces, ZeroCoverageFallback) {
  const TwoFaces t = make_two_faces(0, 0, 16, false);
  const UvGradients g{0.001f, 0, 0, 0.001f};
  faces::SampleOptions o = opts(SeamMethod::discard, TextureFilter::trilinear);
  const Uv outside{-0.3f, 0.5f};  // far outside, tiny footprint: no tap inside
  const std::array<float, 4> with = faces::sample_face(t.set, 0, outside, g, o);
  EXPECT_TRUE(std::isfinite(with[0]));
  EXPECT_EQ(with[3], 0.0f);
  o.clamp_fallback = false;
  const std::array<float, 4> without = faces::sample_face(t.set, 0, outside, g, o);
  EXPECT_TRUE(std::isnan(without[0]));
}

TEST(Faces, Figure1SceneHasAllPairingsAndValences) {
  const faces::FaceScene s = faces::figure1_scene();
  EXPECT_EQ(s.ground_faces, 1024);
  EXPECT_EQ(s.mesh.face_count(), 1024 + 6 * 16 * 16);
  Result<std::vector<FaceAdjacency>> adj = faces::build_adjacency(s.mesh);
  ASSERT_TRUE(adj.ok()) << adj.status().message;
  const std::array<int, 16> h = faces::edge_pairing_histogram(*adj);
  for (int i = 0; i < 16; ++i) EXPECT_GT(h[std::size_t(i)], 0) << "pairing " << i;
  // The character is closed: every edge has a neighbour; the ground has a boundary.
  for (int f = s.ground_faces; f < s.mesh.face_count(); ++f) {
    for (int e = 0; e < 4; ++e)
      EXPECT_GE((*adj)[std::size_t(f)].face[std::size_t(e)], s.ground_faces);
  }
  const auto corners = faces::corner_links(*adj);
  int unlinked_char = 0;
  for (int f = s.ground_faces; f < s.mesh.face_count(); ++f) {
    for (int c = 0; c < 4; ++c) unlinked_char += corners[std::size_t(f)][std::size_t(c)].face < 0;
  }
  EXPECT_EQ(unlinked_char, 8 * 3);  // 8 cube corners of valence 3, each touching 3 faces
  // Diagonal links land on faces sharing the corner's 3D position.
  for (int f = 0; f < s.mesh.face_count(); f += 7) {
    for (int c = 0; c < 4; ++c) {
      const faces::CornerLink& l = corners[std::size_t(f)][std::size_t(c)];
      if (l.face < 0) continue;
      const float cu[4] = {0, 1, 1, 0}, cv[4] = {0, 0, 1, 1};
      const Uv corner{cu[c], cv[c]};
      EXPECT_LT(dist(s.mesh.point(f, corner), s.mesh.point(l.face, l.transform.apply(corner))),
                1e-5f);
    }
  }
  // Mixed resolutions.
  std::set<int> res(s.ulog2.begin(), s.ulog2.end());
  EXPECT_GT(res.size(), 1u);
}

TEST(Faces, SubdivideKeepsAClosedMeshClosed) {
  faces::Figure1Options fo;
  fo.ground = 2;
  fo.character = 3;
  const faces::FaceScene s = faces::figure1_scene(fo);
  QuadMesh cube;
  cube.positions = s.mesh.positions;
  for (int f = s.ground_faces; f < s.mesh.face_count(); ++f)
    cube.quads.push_back(s.mesh.quads[std::size_t(f)]);
  const QuadMesh sub = faces::subdivide(cube);
  EXPECT_EQ(sub.face_count(), 4 * cube.face_count());
  Result<std::vector<FaceAdjacency>> adj = faces::build_adjacency(sub);
  ASSERT_TRUE(adj.ok()) << adj.status().message;
  for (const FaceAdjacency& a : *adj) {
    for (int e = 0; e < 4; ++e) EXPECT_GE(a.face[std::size_t(e)], 0);
  }
  // As a Figure-1 character: ground + the subdivided mesh.
  fo.character_mesh = sub;
  const faces::FaceScene s2 = faces::figure1_scene(fo);
  EXPECT_EQ(s2.mesh.face_count(), 4 + sub.face_count());
  EXPECT_TRUE(faces::build_adjacency(s2.mesh).ok());
}

TEST(Faces, TriangleMeshSplitsIntoClosedQuadMesh) {
  // A tetrahedron: 4 triangles -> 12 quads (one Catmull-Clark-style split, unsmoothed).
  faces::PolygonMesh tet;
  tet.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  tet.faces = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  std::vector<bool> sub;
  const QuadMesh q = faces::ptex_face_layout(tet, &sub);
  EXPECT_EQ(q.face_count(), 12);
  EXPECT_EQ(std::count(sub.begin(), sub.end(), true), 12);
  Result<std::vector<FaceAdjacency>> adj = faces::build_adjacency(q);
  ASSERT_TRUE(adj.ok()) << adj.status().message;
  for (const FaceAdjacency& a : *adj) {
    for (int e = 0; e < 4; ++e) EXPECT_GE(a.face[std::size_t(e)], 0);
  }
  // Valence 3 at the original vertices, 4 at edge midpoints, 3 at face centres.
  const auto corners = faces::corner_links(*adj);
  int linked = 0;
  for (const auto& c : corners) {
    for (const faces::CornerLink& l : c) linked += l.face >= 0;
  }
  EXPECT_EQ(linked, 2 * 12);  // each quad's two edge-midpoint corners
}

/// A small Figure-1 scene (ground x ground faces, a 4x4x4 character) baked and ready to render,
/// and the orbit camera of frame 1 of 8.
struct SmallScene {
  faces::FaceScene scene;
  std::optional<faces::FaceTextureSet> set;
  std::unique_ptr<faces::FaceRenderer> renderer;
  scene::Camera camera;
};

SmallScene small_scene(int ground) {
  faces::Figure1Options fo;
  fo.ground = ground;
  fo.character = 4;
  SmallScene out;
  out.scene = faces::figure1_scene(fo);
  Result<std::vector<FaceAdjacency>> adj = faces::build_adjacency(out.scene.mesh);
  EXPECT_TRUE(adj.ok());
  if (!adj) return out;
  Result<faces::FaceTextureSet> set = faces::FaceTextureSet::create(
      faces::bake_faces(out.scene, {.scale = 1.0f, .threads = 2}), *adj, {2});
  EXPECT_TRUE(set.ok());
  if (!set) return out;
  out.set = std::move(*set);
  Result<std::unique_ptr<faces::FaceRenderer>> r = faces::FaceRenderer::create(out.scene, *out.set);
  EXPECT_TRUE(r.ok());
  if (r) out.renderer = std::move(*r);
  out.camera = faces::face_orbit_camera(out.scene, 1, 8);
  return out;
}

/// The frames the tests render the small scene at: 64 x 48, `msaa` samples, 2 threads.
faces::FaceRenderOptions small_frame(int msaa) {
  faces::FaceRenderOptions o;
  o.width = 64;
  o.height = 48;
  o.msaa = msaa;
  o.threads = 2;
  return o;
}

TEST(Faces, RendersEveryMethod) {
  const SmallScene sc = small_scene(8);
  ASSERT_TRUE(sc.renderer);
  faces::FaceRenderer& renderer = *sc.renderer;
  const scene::Camera& cam = sc.camera;
  faces::FaceRenderOptions o = small_frame(4);
  std::vector<ImageRGBAF> images;
  for (SeamMethod m : faces::all_methods()) {
    o.sampling.method = m;
    Result<faces::FaceFrame> f = renderer.render(cam, o);
    ASSERT_TRUE(f.ok());
    double covered = 0;
    for (std::size_t i = 0; i < f->image.pixel_count(); ++i) {
      for (int k = 0; k < 4; ++k)
        ASSERT_TRUE(std::isfinite(f->image.pixels[i * 4 + std::size_t(k)]));
      covered += f->image.pixels[i * 4 + 3];
    }
    EXPECT_GT(covered, 0.3 * double(f->image.pixel_count()));
    images.push_back(f->image);
  }
  Result<ImageRGBAF> ref =
      renderer.render_reference(cam, 64, 48, {.factor = 4, .threads = 2, .tile = 40});
  ASSERT_TRUE(ref.ok());
  // The reference is close to Traverse at 4x MSAA (mean linear-RGB error small).
  double err = 0;
  for (std::size_t i = 0; i < ref->pixel_count(); ++i) {
    for (int k = 0; k < 3; ++k) {
      err +=
          std::fabs(ref->pixels[i * 4 + std::size_t(k)] - images[2].pixels[i * 4 + std::size_t(k)]);
    }
  }
  EXPECT_LT(err / double(ref->pixel_count() * 3), 0.05);
}

// An explicit sample pattern reaches the frame buffer, which the renderer keeps between frames:
// the same size and rate with another pattern must not reuse the previous frame's buffer, in
// either direction (standard -> explicit -> standard -> the explicit standard pattern).
TEST(Faces, RendersAtAnExplicitSamplePattern) {
  const SmallScene sc = small_scene(6);
  ASSERT_TRUE(sc.renderer);
  faces::FaceRenderer& renderer = *sc.renderer;
  const scene::Camera& cam = sc.camera;
  faces::FaceRenderOptions o = small_frame(2);
  const auto frame = [&](std::vector<raster::SampleOffset> pattern) {
    o.sample_pattern = std::move(pattern);
    Result<faces::FaceFrame> f = renderer.render(cam, o);
    EXPECT_TRUE(f.ok()) << f.status().message;
    return f ? f->image.pixels : std::vector<float>();
  };
  const std::vector<float> standard = frame({});
  const std::vector<float> mirrored = frame({{-4, 4}, {4, -4}});
  EXPECT_NE(mirrored, standard);  // the edges are sampled elsewhere
  EXPECT_EQ(frame({}), standard);
  EXPECT_EQ(frame({{4, 4}, {-4, -4}}), standard);  // the standard 2x, given explicitly
  EXPECT_EQ(frame({{-4, 4}, {4, -4}}), mirrored);
  // A bad pattern is the frame buffer's error.
  o.sample_pattern = {{-4, 4}};
  Result<faces::FaceFrame> bad = renderer.render(cam, o);
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.status().code, ErrorCode::invalid_argument);
}

TEST(Faces, MitchellNetravali) {
  EXPECT_NEAR(faces::mitchell_netravali(0), 8.0f / 9.0f, 1e-6f);
  EXPECT_NEAR(faces::mitchell_netravali(1), 1.0f / 18.0f, 1e-6f);
  EXPECT_EQ(faces::mitchell_netravali(2), 0.0f);
  EXPECT_LT(faces::mitchell_netravali(1.5f), 0.0f);
  // Partition of unity over integer shifts.
  for (float x : {0.0f, 0.25f, 0.5f}) {
    float s = 0;
    for (int k = -2; k <= 2; ++k) s += faces::mitchell_netravali(x + float(k));
    EXPECT_NEAR(s, 1.0f, 1e-5f);
  }
}

// The GPU renderers' index list (faces_gpu.h): every face once, in the draw of its class, two
// triangles on the CPU's diagonal; reversed flips each triangle and nothing else. Negative
// control: a class with no faces gets no draw.
TEST(Faces, ClassGroupedIndicesCoverEveryFaceOnce) {
  faces::PackedFaces layout;
  layout.classes = {{4, 4, 3, {2, 0}}, {8, 8, 4, {}}, {8, 4, 4, {1, 3}}};
  std::vector<std::uint32_t> indices = {99};  // appended to
  const std::vector<faces::FaceClassDraw> draws =
      faces::class_grouped_indices(layout, false, indices);
  ASSERT_EQ(draws.size(), 2u);
  EXPECT_EQ(draws[0].cls, 0);
  EXPECT_EQ(draws[1].cls, 2);
  EXPECT_EQ(draws[0].first, 1u);
  EXPECT_EQ(draws[0].count, 12u);
  EXPECT_EQ(draws[1].first, 13u);
  ASSERT_EQ(indices.size(), 25u);
  const std::vector<std::uint32_t> face2 = {8, 9, 10, 8, 10, 11};
  EXPECT_TRUE(std::equal(face2.begin(), face2.end(), indices.begin() + 1));
  std::vector<std::uint32_t> reversed;
  const std::vector<faces::FaceClassDraw> rdraws =
      faces::class_grouped_indices(layout, true, reversed);
  ASSERT_EQ(rdraws.size(), 2u);
  ASSERT_EQ(reversed.size(), 24u);
  for (std::size_t t = 0; t < 8; ++t) {  // triangle t: (a, b, c) became (a, c, b)
    EXPECT_EQ(reversed[t * 3], indices[1 + t * 3]);
    EXPECT_EQ(reversed[t * 3 + 1], indices[1 + t * 3 + 2]);
    EXPECT_EQ(reversed[t * 3 + 2], indices[1 + t * 3 + 1]);
  }
  std::multiset<std::uint32_t> faces_seen;
  for (std::size_t k = 1; k < indices.size(); ++k) faces_seen.insert(indices[k] / 4);
  for (std::uint32_t f = 0; f < 4; ++f) EXPECT_EQ(faces_seen.count(f), 6u) << f;
}

// The texel formats every GPU backend uploads (faces::convert_texels): binary16 rounded to
// nearest even (normals, subnormals, overflow, infinities, NaN), unorm8 and sRGB8 rounded.
TEST(TexelFormat, ConvertsAsTheGpuFormatsStore) {
  auto half = [](float v) {
    const float texel[4] = {v, 0, 0, 0};
    std::uint8_t out[8];
    faces::convert_texels(texel, 1, faces::TexelFormat::rgba16f, out);
    return unsigned(out[0] | (out[1] << 8));
  };
  EXPECT_EQ(half(1.0f), 0x3c00u);
  EXPECT_EQ(half(-2.0f), 0xc000u);
  EXPECT_EQ(half(0.1f), 0x2e66u);
  EXPECT_EQ(half(65504.0f), 0x7bffu);
  EXPECT_EQ(half(65519.0f), 0x7bffu);                      // below the midpoint to 65536
  EXPECT_EQ(half(65520.0f), 0x7c00u);                      // the midpoint rounds to even: infinity
  EXPECT_EQ(half(std::ldexp(1.0f, -24)), 0x0001u);         // the smallest subnormal
  EXPECT_EQ(half(std::ldexp(1.0f, -25)), 0x0000u);         // half of it: ties to even (0)
  EXPECT_EQ(half(std::ldexp(3.0f, -26)), 0x0001u);         // above the tie
  EXPECT_EQ(half(std::ldexp(1.0f, -14)), 0x0400u);         // the smallest normal
  EXPECT_EQ(half(1.0f + std::ldexp(1.0f, -11)), 0x3c00u);  // tie: to even
  EXPECT_EQ(half(1.0f + std::ldexp(3.0f, -11)), 0x3c02u);  // tie: to even (up)
  EXPECT_EQ(half(INFINITY), 0x7c00u);
  EXPECT_EQ(half(NAN) & 0x7c00u, 0x7c00u);
  EXPECT_NE(half(NAN) & 0x3ffu, 0u);
  const float texel[4] = {0.5f, 1.5f, -0.25f, 0.5f};
  std::uint8_t u[4], s[4];
  faces::convert_texels(texel, 1, faces::TexelFormat::rgba8_unorm, u);
  faces::convert_texels(texel, 1, faces::TexelFormat::rgba8_srgb, s);
  EXPECT_EQ(std::vector<int>(u, u + 4), (std::vector<int>{128, 255, 0, 128}));
  EXPECT_EQ(std::vector<int>(s, s + 4), (std::vector<int>{188, 255, 0, 128}));  // alpha linear
  EXPECT_EQ(faces::texel_bytes(faces::TexelFormat::rgba8_srgb), 4u);
  EXPECT_EQ(faces::texel_bytes(faces::TexelFormat::rgba16f), 8u);
}

}  // namespace
}  // namespace tessera
