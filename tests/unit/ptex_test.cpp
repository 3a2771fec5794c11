// Ptex reader: synthetic files in every encoding and data type, the shared Disney samples
// (face counts, resolutions and adjacency against the accompanying .obj), and corrupt input.
#include "tessera/ptex.h"

#include <gtest/gtest.h>
#include <zlib.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <set>

#include "tessera/faces.h"
#include "tessera/io.h"
#include "test_support.h"

namespace tessera {
namespace {

// ---- A tiny .ptx writer for tests (little-endian, quad mesh, no meta data) ----

void put16(std::vector<std::uint8_t>& b, std::uint32_t v) {
  b.push_back(std::uint8_t(v));
  b.push_back(std::uint8_t(v >> 8));
}
void put32(std::vector<std::uint8_t>& b, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) b.push_back(std::uint8_t(v >> (8 * i)));
}
void put64(std::vector<std::uint8_t>& b, std::uint64_t v) {
  for (int i = 0; i < 8; ++i) b.push_back(std::uint8_t(v >> (8 * i)));
}
std::vector<std::uint8_t> zip(const std::vector<std::uint8_t>& in) {
  uLongf n = compressBound(uLong(in.size()));
  std::vector<std::uint8_t> out(n);
  EXPECT_EQ(compress(out.data(), &n, in.data(), uLong(in.size())), Z_OK);
  out.resize(n);
  return out;
}

struct TestFace {
  int ulog2, vlog2;
  int encoding;                      // 0 constant, 1 zip, 2 diff-zip, 3 tiled (2x2 tiles, zip)
  std::vector<std::uint8_t> pixels;  // interleaved u8, channels per texel
  std::array<int, 4> adj{-1, -1, -1, -1};
  std::array<int, 4> adj_edge{0, 0, 0, 0};
};

std::vector<std::uint8_t> planar(const std::vector<std::uint8_t>& px, int w, int /*h*/, int ch,
                                 int x0, int y0, int tw, int th) {
  std::vector<std::uint8_t> out;
  for (int c = 0; c < ch; ++c) {
    for (int y = y0; y < y0 + th; ++y) {
      for (int x = x0; x < x0 + tw; ++x) out.push_back(px[std::size_t((y * w + x) * ch + c)]);
    }
  }
  return out;
}

std::vector<std::uint8_t> write_ptx(const std::vector<TestFace>& faces, int ch) {
  std::vector<std::uint8_t> fi, cd, level_hdr, level_data;
  for (const TestFace& f : faces) {
    fi.push_back(std::uint8_t(f.ulog2));
    fi.push_back(std::uint8_t(f.vlog2));
    fi.push_back(std::uint8_t((f.adj_edge[0] & 3) | ((f.adj_edge[1] & 3) << 2) |
                              ((f.adj_edge[2] & 3) << 4) | ((f.adj_edge[3] & 3) << 6)));
    fi.push_back(f.encoding == 0 ? 1 : 0);
    for (int a : f.adj) put32(fi, std::uint32_t(a));
    for (int c = 0; c < ch; ++c) cd.push_back(f.pixels[std::size_t(c)]);
    const int w = 1 << f.ulog2, h = 1 << f.vlog2;
    std::vector<std::uint8_t> block;
    std::uint32_t enc = std::uint32_t(f.encoding);
    if (f.encoding == 0) {
      block.assign(f.pixels.begin(), f.pixels.begin() + ch);
    } else if (f.encoding == 1) {
      block = zip(planar(f.pixels, w, h, ch, 0, 0, w, h));
    } else if (f.encoding == 2) {
      std::vector<std::uint8_t> p = planar(f.pixels, w, h, ch, 0, 0, w, h);
      std::uint8_t prev = 0;
      for (std::uint8_t& x : p) {
        const std::uint8_t cur = x;
        x = std::uint8_t(x - prev);
        prev = cur;
      }
      block = zip(p);
    } else {
      const int tu = f.ulog2 - 1, tv = f.vlog2 - 1;
      std::vector<std::uint8_t> hdr, tiles;
      for (int t = 0; t < 4; ++t) {
        const int tx = (t % 2) << tu, ty = (t / 2) << tv;
        std::vector<std::uint8_t> z = zip(planar(f.pixels, w, h, ch, tx, ty, 1 << tu, 1 << tv));
        put32(hdr, std::uint32_t(z.size()) | (1u << 30));
        tiles.insert(tiles.end(), z.begin(), z.end());
      }
      std::vector<std::uint8_t> zh = zip(hdr);
      block.push_back(std::uint8_t(tu));
      block.push_back(std::uint8_t(tv));
      put32(block, std::uint32_t(zh.size()));
      block.insert(block.end(), zh.begin(), zh.end());
      block.insert(block.end(), tiles.begin(), tiles.end());
    }
    put32(level_hdr, std::uint32_t(block.size()) | (enc << 30));
    level_data.insert(level_data.end(), block.begin(), block.end());
  }
  const std::vector<std::uint8_t> zfi = zip(fi), zcd = zip(cd), zlh = zip(level_hdr);
  const std::uint64_t level_size = zlh.size() + level_data.size();
  std::vector<std::uint8_t> b;
  put32(b, 0x78657450u);
  put32(b, 1);
  put32(b, 1);  // quad
  put32(b, 0);  // u8
  put32(b, 0xFFFFFFFFu);
  put16(b, std::uint32_t(ch));
  put16(b, 1);  // levels
  put32(b, std::uint32_t(faces.size()));
  put32(b, 40);
  put32(b, std::uint32_t(zfi.size()));
  put32(b, std::uint32_t(zcd.size()));
  put32(b, 16);
  put32(b, 3);
  put64(b, level_size);
  put32(b, 0);
  put32(b, 0);
  b.resize(b.size() + 40, 0);  // extended header: all zero
  b.insert(b.end(), zfi.begin(), zfi.end());
  b.insert(b.end(), zcd.begin(), zcd.end());
  put64(b, level_size);
  put32(b, std::uint32_t(zlh.size()));
  put32(b, std::uint32_t(faces.size()));
  b.insert(b.end(), zlh.begin(), zlh.end());
  b.insert(b.end(), level_data.begin(), level_data.end());
  return b;
}

std::vector<TestFace> sample_faces() {
  std::vector<TestFace> faces;
  for (int enc = 0; enc < 4; ++enc) {
    TestFace f;
    f.ulog2 = 2;
    f.vlog2 = enc == 3 ? 2 : 1;  // non-square faces too
    f.encoding = enc;
    const int n = (1 << f.ulog2) * (1 << f.vlog2) * 3;
    for (int i = 0; i < n; ++i) {
      f.pixels.push_back(enc == 0 ? std::uint8_t(40 + i % 3) : std::uint8_t((i * 37 + enc) & 255));
    }
    faces.push_back(f);
  }
  faces[0].adj = {1, -1, -1, -1};
  faces[0].adj_edge = {2, 0, 0, 0};
  faces[1].adj = {-1, -1, 0, -1};
  faces[1].adj_edge = {0, 0, 0, 0};
  return faces;
}

TEST(Ptex, DecodesEveryEncoding) {
  const std::vector<TestFace> faces = sample_faces();
  const std::vector<std::uint8_t> bytes = write_ptx(faces, 3);
  Result<ptex::PtexFile> f = ptex::parse_ptex(bytes, "synthetic.ptx");
  ASSERT_TRUE(f.ok()) << f.status().message;
  ASSERT_EQ(f->face_count(), 4);
  EXPECT_EQ(f->channels, 3);
  EXPECT_EQ(f->encodings.constant, 1);
  EXPECT_EQ(f->encodings.zipped, 1);
  EXPECT_EQ(f->encodings.diff_zipped, 1);
  EXPECT_EQ(f->encodings.tiled, 1);
  for (int i = 0; i < 4; ++i) {
    const TestFace& t = faces[std::size_t(i)];
    EXPECT_EQ(f->faces[std::size_t(i)].ulog2, t.ulog2);
    EXPECT_EQ(f->faces[std::size_t(i)].vlog2, t.vlog2);
    const std::vector<float>& texels = f->texels[std::size_t(i)];
    ASSERT_EQ(texels.size(), t.pixels.size());
    for (std::size_t k = 0; k < texels.size(); ++k) {
      const std::uint8_t expect = t.encoding == 0 ? t.pixels[k % 3] : t.pixels[k];
      EXPECT_EQ(texels[k], float(expect) / 255.0f) << "face " << i << " value " << k;
    }
  }
  EXPECT_EQ(f->faces[0].adj_faces[0], 1);
  EXPECT_EQ(f->faces[0].adj_edges[0], 2);
  EXPECT_EQ(f->faces[1].adj_faces[2], 0);
}

TEST(Ptex, HalfFloat) {
  EXPECT_EQ(ptex::half_to_float(0x3C00), 1.0f);
  EXPECT_EQ(ptex::half_to_float(0xC000), -2.0f);
  EXPECT_EQ(ptex::half_to_float(0x0000), 0.0f);
  EXPECT_EQ(ptex::half_to_float(0x0001), std::ldexp(1.0f, -24));
  EXPECT_EQ(ptex::half_to_float(0x7BFF), 65504.0f);
  EXPECT_TRUE(std::isinf(ptex::half_to_float(0x7C00)));
  EXPECT_TRUE(std::isnan(ptex::half_to_float(0x7E00)));
}

TEST(Ptex, CorruptFilesGiveOneLineErrors) {
  const std::vector<std::uint8_t> good = write_ptx(sample_faces(), 3);
  // Every truncation fails cleanly and names the file.
  for (std::size_t n = 0; n < good.size(); n += 7) {
    std::vector<std::uint8_t> cut(good.begin(), good.begin() + std::ptrdiff_t(n));
    Result<ptex::PtexFile> f = ptex::parse_ptex(cut, "cut.ptx");
    ASSERT_FALSE(f.ok()) << n;
    EXPECT_EQ(f.status().message.rfind("cut.ptx: ", 0), 0u) << f.status().message;
    EXPECT_EQ(f.status().message.find('\n'), std::string::npos);
  }
  // Single-byte corruption anywhere never crashes (it may or may not be detected).
  for (std::size_t i = 0; i < good.size(); ++i) {
    std::vector<std::uint8_t> bad = good;
    bad[i] ^= 0x5A;
    Result<ptex::PtexFile> f = ptex::parse_ptex(bad, "flip.ptx");
    if (!f.ok()) {
      EXPECT_FALSE(f.status().message.empty());
    }
  }
  std::vector<std::uint8_t> magic = good;
  magic[0] = 'X';
  EXPECT_NE(ptex::parse_ptex(magic, "m.ptx").status().message.find("bad magic"), std::string::npos);
  // A face count that cannot fit the face-info block is refused before allocation.
  std::vector<std::uint8_t> many = good;
  many[24] = 0xFF;
  many[25] = 0xFF;
  many[26] = 0xFF;
  EXPECT_EQ(ptex::parse_ptex(many, "n.ptx").status().code, ErrorCode::corrupt_data);
  // The texel budget is enforced before decoding.
  ptex::ParseOptions small;
  small.max_floats = 10;
  EXPECT_EQ(ptex::parse_ptex(good, "b.ptx", small).status().code, ErrorCode::too_large);
  EXPECT_EQ(ptex::read_ptex("/nonexistent/x.ptx").status().code, ErrorCode::io_error);
}

TEST(Ptex, FuzzSeedsParse) {
  // The committed fuzz seeds (fuzz/make_ptex_corpus.py) freeze the reader's accepted layout.
  int n = 0;
  for (const auto& e : std::filesystem::directory_iterator(TESSERA_PTEX_CORPUS)) {
    Result<ptex::PtexFile> f = ptex::read_ptex(e.path().string());
    ASSERT_TRUE(f.ok()) << f.status().message;
    EXPECT_GE(f->face_count(), 1);
    ++n;
  }
  EXPECT_GE(n, 5);
  Result<ptex::PtexFile> tiled =
      ptex::read_ptex(std::string(TESSERA_PTEX_CORPUS) + "/float-tiled.ptx");
  ASSERT_TRUE(tiled.ok());
  EXPECT_EQ(tiled->data_type, ptex::DataType::f32);
  EXPECT_EQ(tiled->encodings.tiled, 1);
  // value(3, i) = (i % 17) / 16 in the generator; texel (x, y), channel c is index
  // (y * 4 + x) * 3 + c of the interleaved pixels.
  for (int i = 0; i < 48; ++i) EXPECT_EQ(tiled->texels[0][std::size_t(i)], float(i % 17) / 16.0f);
  Result<ptex::PtexFile> diff =
      ptex::read_ptex(std::string(TESSERA_PTEX_CORPUS) + "/u16-diffzip.ptx");
  ASSERT_TRUE(diff.ok());
  EXPECT_EQ(diff->encodings.diff_zipped, 2);
  for (int i = 0; i < 16; ++i) {
    EXPECT_EQ(diff->texels[0][std::size_t(i)], float((i * 4099 + 7) & 65535) / 65535.0f);
  }
}

// ---- The shared Disney samples ----

struct Sample {
  const char* dir;
  const char* ptx;
};

TEST(PtexShared, TeapotMatchesObj) {
  TESSERA_REQUIRE_SHARED_DATA(data);
  const std::string dir = (data / "ptex" / "teapot").string();
  Result<ptex::PtexFile> f = ptex::read_ptex(dir + "/teapot.ptx");
  ASSERT_TRUE(f.ok()) << f.status().message;
  EXPECT_EQ(f->face_count(), 448);
  EXPECT_EQ(f->mesh_type, ptex::MeshType::quad);
  // Mixed and non-square resolutions.
  std::set<std::pair<int, int>> res;
  for (const ptex::FaceInfo& fi : f->faces) res.insert({fi.ulog2, fi.vlog2});
  EXPECT_GT(res.size(), 2u);
  bool non_square = false;
  for (const auto& r : res) non_square |= r.first != r.second;
  EXPECT_TRUE(non_square);
}

TEST(PtexShared, AdjacencyMatchesObj) {
  TESSERA_REQUIRE_SHARED_DATA(data);
  const Sample samples[] = {
      {"teapot", "teapot.ptx"}, {"holeycube", "holeycube.ptx"}, {"envcube", "envcube.ptx"}};
  for (const Sample& s : samples) {
    const std::string dir = (data / "ptex" / s.dir).string();
    Result<ptex::PtexFile> f = ptex::read_ptex(dir + "/" + s.ptx);
    ASSERT_TRUE(f.ok()) << f.status().message;
    Result<faces::PolygonMesh> poly = faces::load_obj_polygons(dir + "/" + s.dir + ".obj");
    ASSERT_TRUE(poly.ok()) << poly.status().message;
    Result<faces::QuadMesh> quads = faces::to_quad_mesh(*poly, s.dir);
    ASSERT_TRUE(quads.ok()) << quads.status().message;
    ASSERT_EQ(quads->face_count(), f->face_count()) << s.dir;
    Result<std::vector<faces::FaceAdjacency>> adj = faces::build_adjacency(*quads);
    ASSERT_TRUE(adj.ok()) << adj.status().message;
    int boundary = 0;
    for (int i = 0; i < f->face_count(); ++i) {
      for (int e = 0; e < 4; ++e) {
        const int a = (*adj)[std::size_t(i)].face[std::size_t(e)];
        ASSERT_EQ(a, f->faces[std::size_t(i)].adj_faces[std::size_t(e)])
            << s.dir << " face " << i << " edge " << e;
        if (a >= 0) {
          EXPECT_EQ((*adj)[std::size_t(i)].edge[std::size_t(e)],
                    f->faces[std::size_t(i)].adj_edges[std::size_t(e)]);
        } else {
          ++boundary;
        }
      }
    }
    if (std::string(s.dir) == "teapot") {
      EXPECT_GT(boundary, 0);
    }
    // The face set builds (all quads, u8/u16/half/float data).
    Result<faces::FaceTextureSet> set = faces::FaceTextureSet::from_ptex(*f, s.ptx, {2});
    ASSERT_TRUE(set.ok()) << set.status().message;
    EXPECT_EQ(set->face_count(), f->face_count());
  }
}

TEST(PtexShared, TeapotValences) {
  TESSERA_REQUIRE_SHARED_DATA(data);
  Result<ptex::PtexFile> f = ptex::read_ptex((data / "ptex/teapot/teapot.ptx").string());
  ASSERT_TRUE(f.ok());
  Result<faces::FaceTextureSet> set = faces::FaceTextureSet::from_ptex(*f, "teapot", {2});
  ASSERT_TRUE(set.ok());
  // Valence-3 and -5 vertices and boundaries leave some corners unlinked.
  EXPECT_GT(set->linked_corner_count(), 0);
  EXPECT_LT(set->linked_corner_count(), 4 * 448);
}

TEST(PtexShared, SubfacesAndTrianglesAreHandled) {
  TESSERA_REQUIRE_SHARED_DATA(data);
  for (const char* name : {"nonquad", "pentagon"}) {
    const std::string dir = (data / "ptex" / name).string();
    Result<ptex::PtexFile> f = ptex::read_ptex(dir + "/" + name + ".ptx");
    ASSERT_TRUE(f.ok()) << f.status().message;
    int sub = 0;
    for (const ptex::FaceInfo& fi : f->faces) sub += fi.subface ? 1 : 0;
    EXPECT_GT(sub, 0) << name;
    // The subfaces form a quad texture set; the polygon .obj is refused with a clear message.
    EXPECT_TRUE(faces::FaceTextureSet::from_ptex(*f, name, {2}).ok());
    Result<faces::PolygonMesh> poly = faces::load_obj_polygons(dir + "/" + name + ".obj");
    ASSERT_TRUE(poly.ok());
    Result<faces::QuadMesh> q = faces::to_quad_mesh(*poly, name);
    ASSERT_FALSE(q.ok());
    EXPECT_NE(q.status().message.find("only all-quad meshes"), std::string::npos);
  }
  // Split into Ptex subfaces, the polygon meshes match the files' faces and adjacency.
  for (const char* name : {"nonquad", "pentagon"}) {
    const std::string dir = (data / "ptex" / name).string();
    Result<ptex::PtexFile> f = ptex::read_ptex(dir + "/" + name + ".ptx");
    Result<faces::PolygonMesh> poly = faces::load_obj_polygons(dir + "/" + name + ".obj");
    ASSERT_TRUE(f.ok() && poly.ok());
    std::vector<bool> sub;
    const faces::QuadMesh q = faces::ptex_face_layout(*poly, &sub);
    ASSERT_EQ(q.face_count(), f->face_count()) << name;
    Result<std::vector<faces::FaceAdjacency>> adj = faces::build_adjacency(q);
    ASSERT_TRUE(adj.ok()) << adj.status().message;
    int t_junctions = 0;
    for (int i = 0; i < q.face_count(); ++i) {
      EXPECT_EQ(sub[std::size_t(i)], f->faces[std::size_t(i)].subface) << name << " " << i;
      for (int e = 0; e < 4; ++e) {
        const int nb = f->faces[std::size_t(i)].adj_faces[std::size_t(e)];
        if (nb >= 0 && sub[std::size_t(i)] != sub[std::size_t(nb)]) {
          // A quad edge meets two subface half-edges (a T-junction): Ptex links one of them;
          // the directed-edge map (and FaceTextureSet::from_ptex) treat it as a border.
          EXPECT_EQ((*adj)[std::size_t(i)].face[std::size_t(e)], -1);
          ++t_junctions;
          continue;
        }
        EXPECT_EQ((*adj)[std::size_t(i)].face[std::size_t(e)],
                  f->faces[std::size_t(i)].adj_faces[std::size_t(e)])
            << name << " face " << i << " edge " << e;
        if ((*adj)[std::size_t(i)].face[std::size_t(e)] >= 0) {
          EXPECT_EQ((*adj)[std::size_t(i)].edge[std::size_t(e)],
                    f->faces[std::size_t(i)].adj_edges[std::size_t(e)]);
        }
      }
    }
    if (std::string(name) == "nonquad") {
      EXPECT_GT(t_junctions, 0);
    }
  }
  Result<ptex::PtexFile> tri = ptex::read_ptex((data / "ptex/triangle/triangle.ptx").string());
  ASSERT_TRUE(tri.ok()) << tri.status().message;
  EXPECT_EQ(tri->mesh_type, ptex::MeshType::triangle);
  Result<faces::FaceTextureSet> set = faces::FaceTextureSet::from_ptex(*tri, "triangle.ptx");
  ASSERT_FALSE(set.ok());
  EXPECT_NE(set.status().message.find("triangle-mesh"), std::string::npos);
}

TEST(PtexShared, HoleycubeIsSixteenBit) {
  TESSERA_REQUIRE_SHARED_DATA(data);
  Result<ptex::PtexFile> f = ptex::read_ptex((data / "ptex/holeycube/holeycube.ptx").string());
  ASSERT_TRUE(f.ok()) << f.status().message;
  EXPECT_EQ(f->face_count(), 72);
  EXPECT_EQ(f->data_type, ptex::DataType::u16);
  for (const ptex::FaceInfo& fi : f->faces) {
    EXPECT_EQ(fi.width(), 128);
    EXPECT_EQ(fi.height(), 128);
  }
  // Decoded data is not all constant.
  float lo = 1, hi = 0;
  for (float v : f->texels[0]) {
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  EXPECT_LT(lo, hi);
}

}  // namespace
}  // namespace tessera
