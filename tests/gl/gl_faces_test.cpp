// Per-face textures packed for the GPU (tessera/gl_faces.h): the CPU layout mirrors the
// FaceTextureSet's adjacency and corner links exactly; the uploaded face-record buffer and
// texture arrays read back equal to the CPU data (the Disney Ptex samples, skipped when
// ../shared/data is absent); hardware border sampling of the packed arrays against tessera's
// sampler.
#include "tessera/gl_faces.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <set>

#include "gl/gl_api.h"
#include "gl_test_fixture.h"
#include "tessera/faces.h"
#include "tessera/gl.h"
#include "tessera/ptex.h"
#include "test_support.h"

namespace {

using namespace tessera;
using namespace tessera::gl;
using namespace tessera::gl::api;  // NOLINT(google-build-using-namespace)

// Checks every record against the CPU set: class/layer consistent with the classes, size,
// neighbours, edge mappings, and corner mappings composing to the CPU corner transforms.
void expect_mirrors(const faces::FaceTextureSet& set, const faces::PackedFaces& p,
                    const std::vector<faces::FaceRecord>& records, const std::string& name) {
  ASSERT_EQ(int(records.size()), set.face_count()) << name;
  const auto& table = faces::edge_transform_table();
  int checked_corners = 0;
  for (int f = 0; f < set.face_count(); ++f) {
    const faces::FaceRecord& r = records[std::size_t(f)];
    SCOPED_TRACE(name + " face " + std::to_string(f));
    ASSERT_GE(r.info[0], 0);
    ASSERT_LT(r.info[0], int(p.classes.size()));
    const faces::FaceClass& c = p.classes[std::size_t(r.info[0])];
    ASSERT_LT(r.info[1], int(c.faces.size()));
    EXPECT_EQ(c.faces[std::size_t(r.info[1])], f);
    EXPECT_EQ(r.info[2], set.texture(f).width());
    EXPECT_EQ(r.info[3], set.texture(f).height());
    EXPECT_EQ(c.levels, set.texture(f).level_count());
    const faces::FaceAdjacency& a = set.adjacency(f);
    for (int e = 0; e < 4; ++e) {
      const std::size_t ei = std::size_t(e);
      EXPECT_EQ(r.neighbour[ei], a.face[ei]);
      EXPECT_EQ(r.mapping[ei], a.face[ei] < 0 ? -1 : e * 4 + a.edge[ei]);
      const faces::CornerLink& link = set.corner(f, e);
      EXPECT_EQ(r.corner[ei], link.face);
      if (link.face < 0) {
        EXPECT_EQ(r.corner_mapping[ei], -1);
        continue;
      }
      const int m1 = r.corner_mapping[ei] / 16, m2 = r.corner_mapping[ei] % 16;
      EXPECT_EQ(m1 / 4, e);  // leaves across my edge e
      const faces::UvTransform t = table[std::size_t(m1)].then(table[std::size_t(m2)]);
      EXPECT_EQ(t.a, link.transform.a);
      EXPECT_EQ(t.b, link.transform.b);
      EXPECT_EQ(t.c, link.transform.c);
      EXPECT_EQ(t.d, link.transform.d);
      EXPECT_EQ(t.e, link.transform.e);
      EXPECT_EQ(t.f, link.transform.f);
      ++checked_corners;
    }
  }
  if (set.linked_corner_count() > 0) {
    EXPECT_EQ(checked_corners, set.linked_corner_count());
  }
}

TEST(GlPack, Figure1LayoutMirrorsTheCpuSet) {
  const faces::FaceTextureSet set = test::figure1_texture_set(6, 3);
  Result<faces::PackedFaces> p = pack_faces(set);
  ASSERT_TRUE(p.ok()) << p.status().message;
  expect_mirrors(set, *p, p->records, "figure1");
  // Classes sorted by (height, width), each face in exactly one layer.
  std::set<int> seen;
  for (std::size_t i = 0; i < p->classes.size(); ++i) {
    if (i > 0) {
      const faces::FaceClass &a = p->classes[i - 1], &b = p->classes[i];
      EXPECT_LT(std::make_pair(a.height, a.width), std::make_pair(b.height, b.width));
    }
    for (int f : p->classes[i].faces) EXPECT_TRUE(seen.insert(f).second);
  }
  EXPECT_EQ(int(seen.size()), set.face_count());
  EXPECT_GT(set.linked_corner_count(), 0);
  EXPECT_GT(p->classes.size(), 1u);
}

TEST(GlPack, LimitsGiveOneLineErrors) {
  const faces::FaceTextureSet set = test::figure1_texture_set(6, 3);
  faces::PackLimits l;
  l.max_array_layers = 1;
  Result<faces::PackedFaces> p = pack_faces(set, l);
  ASSERT_FALSE(p.ok());
  EXPECT_EQ(p.status().code, ErrorCode::too_large);
  EXPECT_NE(p.status().message.find("exceed GL_MAX_ARRAY_TEXTURE_LAYERS = 1"), std::string::npos)
      << p.status().message;
  l = {};
  l.max_texture_size = 2;
  p = pack_faces(set, l);
  ASSERT_FALSE(p.ok());
  EXPECT_NE(p.status().message.find("above GL_MAX_TEXTURE_SIZE = 2"), std::string::npos)
      << p.status().message;
  l = {};
  l.max_classes = 1;
  EXPECT_FALSE(pack_faces(set, l).ok());
  l = {};
  l.max_ssbo_bytes = 80;
  EXPECT_FALSE(pack_faces(set, l).ok());
  EXPECT_FALSE(pack_faces(faces::FaceTextureSet{}).ok());
}

class GlPtex : public test::GlTest {};

// Runs compute program `prog` (local size 64, uniform `count`) on `queries` (storage buffer 1)
// and returns the `count` vec4s it writes to storage buffer 2; the caller binds its textures.
// A GL error fails it, `what` naming the lookups.
Result<std::vector<std::array<float, 4>>> run_lookups(const Program& prog,
                                                      const std::vector<float>& queries, int count,
                                                      const std::string& what) {
  Object qbuf = create_object(ObjectType::buffer), rbuf = create_object(ObjectType::buffer);
  glNamedBufferData(qbuf.get(), GLsizeiptr(queries.size() * 4), queries.data(), GL_STATIC_DRAW);
  glNamedBufferData(rbuf.get(), GLsizeiptr(count * 16), nullptr, GL_STATIC_READ);
  glUseProgram(prog.get());
  glProgramUniform1i(prog.get(), prog.uniform("count"), count);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, qbuf.get());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, rbuf.get());
  glDispatchCompute(GLuint((count + 63) / 64), 1, 1);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  std::vector<std::array<float, 4>> got(static_cast<std::size_t>(count));
  glGetNamedBufferSubData(rbuf.get(), 0, GLsizeiptr(count * 16), got.data());
  if (Status s = check_errors(what); !s.ok()) return s;
  return got;
}

// The shared Disney samples that FaceTextureSet accepts (quad meshes).
std::vector<std::pair<std::string, faces::FaceTextureSet>> disney_sets(
    const std::filesystem::path& data) {
  std::vector<std::pair<std::string, faces::FaceTextureSet>> out;
  std::vector<std::filesystem::path> files;
  for (const auto& dir : std::filesystem::directory_iterator(data / "ptex")) {
    if (!dir.is_directory()) continue;
    for (const auto& f : std::filesystem::directory_iterator(dir.path())) {
      if (f.path().extension() == ".ptx") files.push_back(f.path());
    }
  }
  std::sort(files.begin(), files.end());
  for (const auto& path : files) {
    Result<ptex::PtexFile> file = ptex::read_ptex(path.string());
    if (!file) {
      ADD_FAILURE() << file.status().message;
      continue;
    }
    Result<faces::FaceTextureSet> set =
        faces::FaceTextureSet::from_ptex(*file, path.filename().string());
    if (!set) {
      EXPECT_EQ(file->mesh_type, ptex::MeshType::triangle) << set.status().message;
      continue;
    }
    out.emplace_back(path.filename().string(), std::move(*set));
  }
  return out;
}

TEST_F(GlPtex, DisneySamplesUploadAndReadBackExactly) {
  TESSERA_REQUIRE_SHARED_DATA(data);
  if (!std::filesystem::is_directory(data / "ptex"))
    TESSERA_SKIP_OR_FAIL("shared", "no ptex samples");
  const auto sets = disney_sets(data);
  ASSERT_GE(sets.size(), 5u);
  for (const auto& [name, set] : sets) {
    SCOPED_TRACE(name);
    Result<FaceTextureSet> gpu = FaceTextureSet::upload(set);
    ASSERT_TRUE(gpu.ok()) << gpu.status().message;
    const faces::PackedFaces& p = gpu->layout();
    std::vector<faces::FaceRecord> records(std::size_t(set.face_count()));
    glGetNamedBufferSubData(gpu->record_buffer(), 0,
                            GLsizeiptr(records.size() * sizeof(faces::FaceRecord)), records.data());
    ASSERT_TRUE(check_errors("records").ok());
    expect_mirrors(set, p, records, name);
    // Every level of (up to) 3 faces per class reads back bit-identical to the CPU chain.
    for (int c = 0; c < gpu->class_count(); ++c) {
      const faces::FaceClass& cls = p.classes[std::size_t(c)];
      for (std::size_t layer = 0; layer < cls.faces.size(); layer += 1 + cls.faces.size() / 3) {
        const texture::Texture& t = set.texture(cls.faces[layer]);
        for (int level = 0; level < cls.levels; ++level) {
          Result<ImageRGBAF> img = read_texture_rgbaf(gpu->array_texture(c), level, int(layer));
          ASSERT_TRUE(img.ok()) << img.status().message;
          const tessera::texture::TextureLevelView v = t.level(0, level);
          ASSERT_EQ(img->width, v.width);
          ASSERT_EQ(img->height, v.height);
          EXPECT_EQ(std::memcmp(img->pixels.data(), v.texels, img->pixels.size() * 4), 0)
              << "class " << c << " layer " << layer << " level " << level;
        }
      }
    }
    std::printf("%s: %d faces, %d classes, %.1f MiB of RGBA32F arrays\n", name.c_str(),
                set.face_count(), gpu->class_count(), double(gpu->texture_bytes()) / 1048576.0);
    GLint units = 0;
    glGetIntegerv(GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS, &units);
    const Status bound = gpu->bind(0, 0, true);
    EXPECT_EQ(bound.ok(), 2 * gpu->class_count() <= units) << bound.message;
  }
}

// The smaller texel formats hold faces::convert_texels's bytes (the bytes Vulkan uploads): the
// first face of every class, level 0, read back raw.
TEST_F(GlPtex, TexelFormatsHoldTheConvertedBytes) {
  TESSERA_REQUIRE_SHARED_DATA(data);
  if (!std::filesystem::is_directory(data / "ptex"))
    TESSERA_SKIP_OR_FAIL("shared", "no ptex samples");
  const auto sets = disney_sets(data);
  ASSERT_FALSE(sets.empty());
  const auto& [name, set] = *sets.begin();
  struct Case {
    faces::TexelFormat format;
    GLenum type;
  };
  for (const Case& k : {Case{faces::TexelFormat::rgba16f, GL_HALF_FLOAT},
                        Case{faces::TexelFormat::rgba8_unorm, GL_UNSIGNED_BYTE},
                        Case{faces::TexelFormat::rgba8_srgb, GL_UNSIGNED_BYTE}}) {
    FaceTextureSetOptions o;
    o.format = k.format;
    Result<FaceTextureSet> gpu = FaceTextureSet::upload(set, o);
    ASSERT_TRUE(gpu.ok()) << gpu.status().message;
    for (int c = 0; c < gpu->class_count(); ++c) {
      const faces::FaceClass& cls = gpu->layout().classes[std::size_t(c)];
      const texture::TextureLevelView v = set.texture(cls.faces[0]).level(0, 0);
      const std::size_t texels = std::size_t(v.width) * std::size_t(v.height);
      const std::size_t bytes = texels * faces::texel_bytes(k.format);
      std::vector<std::uint8_t> want(bytes), got(bytes);
      faces::convert_texels(v.texels, texels, k.format, want.data());
      glGetTextureSubImage(gpu->array_texture(c), 0, 0, 0, 0, v.width, v.height, 1, GL_RGBA, k.type,
                           GLsizei(bytes), got.data());
      ASSERT_TRUE(check_errors("read back").ok());
      EXPECT_EQ(got, want) << name << " class " << c << " format " << int(k.format);
    }
    EXPECT_EQ(gpu->texture_bytes() % faces::texel_bytes(k.format), 0u);
  }
}

// Hardware clamp-to-border trilinear lookups of the packed arrays (Σ w·T in rgb, Σ w in alpha:
// Discard's numerator and denominator) against tessera's sampler on the same texels.
TEST_F(GlPtex, BorderLookupsMatchTheCpuSampler) {
  const faces::FaceTextureSet set = test::figure1_texture_set(6, 3);
  FaceTextureSetOptions options;
  options.max_anisotropy = 1.0f;  // trilinear (anisotropic filtering is implementation-defined)
  Result<FaceTextureSet> gpu = FaceTextureSet::upload(set, options);
  ASSERT_TRUE(gpu.ok()) << gpu.status().message;
  Result<Program> prog = link_program({{glsl::Stage::compute, R"(#version 450 core
layout(local_size_x = 64) in;
layout(binding = 0) uniform sampler2DArray faces;
layout(std430, binding = 1) readonly buffer Queries { vec4 q[]; };  // (u, v, layer, unused) + grads
layout(std430, binding = 2) writeonly buffer Results { vec4 r[]; };
uniform int count;
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= uint(count)) return;
  vec4 a = q[2 * i], g = q[2 * i + 1];
  r[i] = textureGrad(faces, a.xyz, g.xy, g.zw);
})",
                                        "border_lookup.comp"}});
  ASSERT_TRUE(prog.ok()) << prog.status().message;
  tessera::texture::SamplerState border;
  border.filter = tessera::texture::TextureFilter::trilinear;
  border.address_u = border.address_v = tessera::texture::AddressMode::border;
  double max_diff = 0.0;
  int lookups = 0;
  for (int c = 0; c < gpu->class_count(); ++c) {
    const faces::FaceClass& cls = gpu->layout().classes[std::size_t(c)];
    std::vector<float> queries;
    std::vector<std::array<float, 4>> expected;
    for (std::size_t layer = 0; layer < cls.faces.size(); ++layer) {
      const texture::Texture& t = set.texture(cls.faces[layer]);
      for (int k = 0; k < 24; ++k) {
        // Positions inside, on and beyond the borders; footprints from magnified to 8 texels.
        const float u = -0.2f + 1.4f * float((k * 7 + int(layer)) % 24) / 23.0f;
        const float v = -0.2f + 1.4f * float((k * 5 + 3 * int(layer)) % 24) / 23.0f;
        const float s = std::ldexp(1.0f, k % 5 - 1) / float(t.width());
        const tessera::texture::UvGradients g{s, 0.0f, 0.0f,
                                              s * float(t.width()) / float(t.height())};
        queries.insert(queries.end(), {u, v, float(layer), 0.0f, g.dudx, g.dvdx, g.dudy, g.dvdy});
        expected.push_back(t.sample(border, {u, v}, g));
      }
    }
    const int count = int(expected.size());
    glBindTextureUnit(0, gpu->array_texture(c));
    glBindSampler(0, gpu->border_sampler());
    Result<std::vector<std::array<float, 4>>> got =
        run_lookups(*prog, queries, count, "border lookups");
    ASSERT_TRUE(got.ok()) << got.status().message;
    for (int i = 0; i < count; ++i) {
      for (int k = 0; k < 4; ++k) {
        const double d = std::fabs((*got)[std::size_t(i)][std::size_t(k)] -
                                   expected[std::size_t(i)][std::size_t(k)]);
        max_diff = std::max(max_diff, d);
      }
    }
    lookups += count;
  }
  std::printf("%d trilinear border lookups, GL (%s) vs tessera: max |diff| %.3g\n", lookups,
              ctx_->renderer().c_str(), max_diff);
  // Exact bilinear arithmetic up to float rounding (measured 1.2e-7 on llvmpipe). A hardware
  // texture unit quantises the bilinear weights to 1/256 (error <= 1/512 per axis on texel
  // values in [0, 1]) and the mip blend likewise: <= 3/512 per trilinear lookup, bounded at
  // 1/128 (measured 0.0038 on an NVIDIA H200).
  EXPECT_LT(max_diff, test::float_texture_filtering(ctx_->renderer()) ? 1e-5 : 1.0 / 128);
}

}  // namespace

namespace {

// share/tessera/glsl/seams.glsl in a compute shader against faces::sample_face (trilinear):
// all four methods, at points inside, near edges and corners and beyond the face, with
// footprints from magnified to several texels.
TEST_F(GlPtex, SeamsGlslMatchesTheCpuMethods) {
  const faces::FaceTextureSet set = test::figure1_texture_set(6, 3);
  FaceTextureSetOptions options;
  options.max_anisotropy = 1.0f;
  Result<FaceTextureSet> gpu = FaceTextureSet::upload(set, options);
  ASSERT_TRUE(gpu.ok()) << gpu.status().message;
  ASSERT_LE(gpu->class_count(), 16);
  glsl::ExpandOptions so;
  so.include_paths = {TESSERA_GLSL_DIR};
  so.preamble = {"#define TESSERA_SEAMS_CLASSES " + std::to_string(gpu->class_count())};
  Result<Program> prog = link_program({{glsl::Stage::compute, R"(#version 450 core
#include "seams.glsl"
layout(local_size_x = 64) in;
struct Query { vec4 a; vec4 g; };  // a: u, v, face, method; g: dudx, dvdx, dudy, dvdy
layout(std430, binding = 1) readonly buffer Queries { Query q[]; };
layout(std430, binding = 2) writeonly buffer Results { vec4 r[]; };
uniform int count;
void main() {
  int i = int(gl_GlobalInvocationID.x);
  if (i >= count) return;
  Query x = q[i];
  r[i] = tessera_seams_sample(int(x.a.w), int(x.a.z), x.a.xy, x.g.xy, x.g.zw);
})",
                                        "seams_test.comp"}},
                                      so);
  ASSERT_TRUE(prog.ok()) << prog.status().message;
  ASSERT_TRUE(gpu->bind(0, 0).ok());

  std::vector<float> queries;
  std::vector<std::array<float, 4>> expected;
  for (int face = 0; face < set.face_count(); face += 3) {
    const texture::Texture& t = set.texture(face);
    for (int k = 0; k < 12; ++k) {
      const float u = -0.15f + 1.3f * float((k * 5 + face) % 12) / 11.0f;
      const float v = -0.15f + 1.3f * float((k * 7 + 2 * face) % 12) / 11.0f;
      const float s = std::ldexp(1.0f, k % 5 - 1) / float(t.width());
      const tessera::texture::UvGradients g{s, 0.0f, 0.0f,
                                            s * float(t.width()) / float(t.height())};
      for (faces::SeamMethod m : faces::all_methods()) {
        faces::SampleOptions so_cpu;
        so_cpu.method = m;
        so_cpu.filter = tessera::texture::TextureFilter::trilinear;
        queries.insert(queries.end(),
                       {u, v, float(face), float(int(m)), g.dudx, g.dvdx, g.dudy, g.dvdy});
        expected.push_back(faces::sample_face(set, face, {u, v}, g, so_cpu));
      }
    }
  }
  const int count = int(expected.size());
  Result<std::vector<std::array<float, 4>>> got =
      run_lookups(*prog, queries, count, "seams lookups");
  ASSERT_TRUE(got.ok()) << got.status().message;
  std::array<double, 4> max_diff{};
  for (int i = 0; i < count; ++i) {
    const int m = i % 4;
    for (int k = 0; k < 4; ++k) {
      const double d = std::fabs(double((*got)[std::size_t(i)][std::size_t(k)]) -
                                 double(expected[std::size_t(i)][std::size_t(k)]));
      max_diff[std::size_t(m)] = std::max(max_diff[std::size_t(m)], std::isnan(d) ? 1e9 : d);
    }
  }
  for (faces::SeamMethod m : faces::all_methods()) {
    std::printf("seams.glsl %-16s vs faces::sample_face: %d lookups, max |diff| %.3g\n",
                faces::method_name(m), count / 4, max_diff[std::size_t(int(m))]);
    // As BorderLookupsMatchTheCpuSampler: float rounding on llvmpipe, the fixed-point filter
    // weights of a hardware texture unit elsewhere (measured 0.0010-0.0039 on an NVIDIA H200).
    EXPECT_LT(max_diff[std::size_t(int(m))],
              test::float_texture_filtering(ctx_->renderer()) ? 1e-5 : 1.0 / 128)
        << faces::method_name(m);
  }
}

}  // namespace
