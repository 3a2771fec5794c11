// Per-face textures in an engine's own program (tessera/gl_faces.h, the recipe there):
// `FaceTextureSet::bind(FaceTextureSetBindings)` binds exactly the documented points and nothing
// else (distinctive engine state set on every unit and buffer binding beforehand, read back
// after), refuses bad binding points before touching any state, and `glsl_defines` names the
// same points; `faces::ptex_quad_mesh` maps the Disney samples' OBJ polygons to their Ptex faces
// and refuses an unsplit non-quad polygon naming it, and triangle-mesh files. Skips the GL test
// when no OpenGL 4.5 context can be made, the data tests without ../shared/data.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "gl/gl_api.h"
#include "gl_test_fixture.h"
#include "tessera/faces.h"
#include "tessera/gl.h"
#include "tessera/gl_faces.h"
#include "tessera/ptex.h"
#include "test_support.h"

namespace {

using namespace tessera;
using namespace tessera::gl;
using namespace tessera::gl::api;  // NOLINT(google-build-using-namespace)

/// The bindings `bind` may touch, per texture unit and per storage-buffer index.
struct Snapshot {
  std::vector<GLint> array, tex2d, sampler;  // per unit
  std::vector<GLint> ssbo;                   // per indexed binding
  std::vector<GLint64> ssbo_start, ssbo_size;
  GLint active = 0, generic_ssbo = 0, ubo0 = 0, program = 0, vao = 0, fbo = 0;
};

Snapshot snapshot(int units, int bindings) {
  Snapshot s;
  glGetIntegerv(GL_ACTIVE_TEXTURE, &s.active);
  for (int u = 0; u < units; ++u) {
    glActiveTexture(GLenum(GL_TEXTURE0 + u));
    GLint v = 0;
    glGetIntegerv(GL_TEXTURE_BINDING_2D_ARRAY, &v);
    s.array.push_back(v);
    glGetIntegerv(GL_TEXTURE_BINDING_2D, &v);
    s.tex2d.push_back(v);
    glGetIntegerv(GL_SAMPLER_BINDING, &v);
    s.sampler.push_back(v);
  }
  glActiveTexture(GLenum(s.active));
  for (int b = 0; b < bindings; ++b) {
    GLint v = 0;
    GLint64 start = 0, size = 0;
    glGetIntegeri_v(GL_SHADER_STORAGE_BUFFER_BINDING, GLuint(b), &v);
    glGetInteger64i_v(GL_SHADER_STORAGE_BUFFER_START, GLuint(b), &start);
    glGetInteger64i_v(GL_SHADER_STORAGE_BUFFER_SIZE, GLuint(b), &size);
    s.ssbo.push_back(v);
    s.ssbo_start.push_back(start);
    s.ssbo_size.push_back(size);
  }
  glGetIntegerv(GL_SHADER_STORAGE_BUFFER_BINDING, &s.generic_ssbo);
  glGetIntegeri_v(GL_UNIFORM_BUFFER_BINDING, 0, &s.ubo0);
  glGetIntegerv(GL_CURRENT_PROGRAM, &s.program);
  glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &s.vao);
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &s.fbo);
  return s;
}

/// The engine's state: its own 2D and 2D-array textures and samplers on every unit, a buffer
/// on every storage binding (a sub-range), the generic binding, a UBO, a program, a VAO and an
/// FBO, active unit 7.
struct EngineState {
  GLuint tex2d = 0, array = 0, sampler = 0, buf = 0, vao = 0, fbo = 0;

  EngineState(int units, int bindings) {
    glCreateTextures(GL_TEXTURE_2D, 1, &tex2d);
    glTextureStorage2D(tex2d, 1, GL_RGBA8, 4, 4);
    glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &array);
    glTextureStorage3D(array, 1, GL_RGBA8, 4, 4, 2);
    glCreateSamplers(1, &sampler);
    glCreateBuffers(1, &buf);
    glNamedBufferStorage(buf, 4096, nullptr, 0);
    glCreateVertexArrays(1, &vao);
    glCreateFramebuffers(1, &fbo);
    GLint align = 1;
    glGetIntegerv(GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT, &align);
    for (int u = 0; u < units; ++u) {
      glActiveTexture(GLenum(GL_TEXTURE0 + u));
      glBindTexture(GL_TEXTURE_2D, tex2d);
      glBindTexture(GL_TEXTURE_2D_ARRAY, array);
      glBindSampler(GLuint(u), sampler);
    }
    for (int i = 0; i < bindings; ++i) {
      glBindBufferRange(GL_SHADER_STORAGE_BUFFER, GLuint(i), buf, align, 256);
    }
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, buf);
    glBindBufferBase(GL_UNIFORM_BUFFER, 0, buf);
    glBindVertexArray(vao);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo);
    glActiveTexture(GL_TEXTURE7);
  }
  EngineState(const EngineState&) = delete;
  EngineState& operator=(const EngineState&) = delete;
  ~EngineState() {
    glBindVertexArray(0);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
    glDeleteTextures(1, &tex2d);
    glDeleteTextures(1, &array);
    glDeleteSamplers(1, &sampler);
    glDeleteBuffers(1, &buf);
    glDeleteVertexArrays(1, &vao);
    glDeleteFramebuffers(1, &fbo);
  }
};

/// After `tex.bind(b)`: exactly the units and the storage binding of `b` changed, the rest of
/// the engine's state (`before`, `engine`) is as it was.
void expect_only_bound_points(const FaceTextureSet& tex, const FaceTextureSetBindings& b,
                              const EngineState& engine, const Snapshot& before,
                              const Snapshot& after) {
  const int classes = tex.class_count();
  const int units = int(before.array.size()), bindings = int(before.ssbo.size());
  int changed_units = 0;
  for (int u = 0; u < units; ++u) {
    SCOPED_TRACE("unit " + std::to_string(u));
    const bool border = u >= b.border_unit && u < b.border_unit + classes;
    const bool clamp = u >= b.clamp_unit && u < b.clamp_unit + classes;
    EXPECT_EQ(after.tex2d[std::size_t(u)], before.tex2d[std::size_t(u)]);
    if (border || clamp) {
      const int c = u - (border ? b.border_unit : b.clamp_unit);
      EXPECT_EQ(GLuint(after.array[std::size_t(u)]), tex.array_texture(c));
      EXPECT_EQ(GLuint(after.sampler[std::size_t(u)]),
                border ? tex.border_sampler() : tex.clamp_sampler());
      ++changed_units;
    } else {
      EXPECT_EQ(after.array[std::size_t(u)], before.array[std::size_t(u)]);
      EXPECT_EQ(after.sampler[std::size_t(u)], before.sampler[std::size_t(u)]);
    }
  }
  EXPECT_EQ(changed_units, 2 * classes);
  for (int i = 0; i < bindings; ++i) {
    SCOPED_TRACE("storage binding " + std::to_string(i));
    if (i == b.records_binding) {
      EXPECT_EQ(GLuint(after.ssbo[std::size_t(i)]), tex.record_buffer());
      EXPECT_EQ(after.ssbo_start[std::size_t(i)], 0);
      EXPECT_EQ(after.ssbo_size[std::size_t(i)], 0);  // the whole buffer
    } else {
      EXPECT_EQ(after.ssbo[std::size_t(i)], before.ssbo[std::size_t(i)]);
      EXPECT_EQ(after.ssbo_start[std::size_t(i)], before.ssbo_start[std::size_t(i)]);
      EXPECT_EQ(after.ssbo_size[std::size_t(i)], before.ssbo_size[std::size_t(i)]);
    }
  }
  EXPECT_EQ(after.active, GL_TEXTURE7);
  EXPECT_EQ(GLuint(after.generic_ssbo), engine.buf);
  EXPECT_EQ(after.ubo0, before.ubo0);
  EXPECT_EQ(after.program, before.program);
  EXPECT_EQ(after.vao, before.vao);
  EXPECT_EQ(after.fbo, before.fbo);
}

/// Bad points: one-line invalid_argument, and no binding changed from `after`.
void expect_bad_points_refused(const FaceTextureSet& tex, int max_units, int max_bindings,
                               const Snapshot& after) {
  const int classes = tex.class_count();
  const int units = int(after.array.size()), bindings = int(after.ssbo.size());
  const FaceTextureSetBindings bad[] = {
      {-1, 20, 5, true},                        // negative unit
      {3, 3 + classes - 1, 5, true},            // clamp range overlaps the border range
      {max_units - classes + 1, -1, 5, false},  // past the last unit
      {3, 20, max_bindings, true},              // past the last storage binding
      {3, 20, -2, true},                        // negative binding
  };
  for (const FaceTextureSetBindings& x : bad) {
    const Status s = tex.bind(x);
    EXPECT_EQ(s.code, ErrorCode::invalid_argument) << s.message;
    EXPECT_NE(s.message.find("FaceTextureSet::bind: "), std::string::npos) << s.message;
    EXPECT_EQ(s.message.find('\n'), std::string::npos) << s.message;
    const Snapshot again = snapshot(units, bindings);
    EXPECT_EQ(again.array, after.array);
    EXPECT_EQ(again.sampler, after.sampler);
    EXPECT_EQ(again.ssbo, after.ssbo);
  }
}

class GlPtexBind : public test::GlTest {};

// Distinctive engine state on every unit and binding; bind to caller-chosen points (border
// units 3.., clamp units 20.., records at 5); exactly those points change.
TEST_F(GlPtexBind, BindsExactlyTheDocumentedPoints) {
  const faces::FaceTextureSet set = test::figure1_texture_set(4, 2);
  Result<FaceTextureSet> tex = FaceTextureSet::upload(set);
  ASSERT_TRUE(tex.ok()) << tex.status().message;
  const int classes = tex->class_count();
  ASSERT_GE(classes, 2);
  GLint max_units = 0, max_bindings = 0;
  glGetIntegerv(GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS, &max_units);
  glGetIntegerv(GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS, &max_bindings);
  const int units = std::min(max_units, 48), bindings = std::min(max_bindings, 8);
  const FaceTextureSetBindings b{3, 20, 5, true};
  ASSERT_LE(b.clamp_unit + classes, units);

  const EngineState engine(units, bindings);
  ASSERT_TRUE(check_errors("engine state").ok());
  const Snapshot before = snapshot(units, bindings);
  ASSERT_TRUE(tex->bind(b).ok());
  const Snapshot after = snapshot(units, bindings);
  ASSERT_TRUE(check_errors("snapshot").ok());
  expect_only_bound_points(*tex, b, engine, before, after);

  // The shader side names the same points.
  const std::vector<std::string> defines = tex->glsl_defines(b);
  const std::vector<std::string> want = {"#define TESSERA_SEAMS_CLASSES " + std::to_string(classes),
                                         "#define TESSERA_SEAMS_FIRST_UNIT 3",
                                         "#define TESSERA_SEAMS_CLAMP_UNIT 20",
                                         "#define TESSERA_SEAMS_FACES_BINDING 5"};
  EXPECT_EQ(defines, want);
  // Default clamp unit: right after the border units (seams.glsl's default).
  EXPECT_EQ(tex->glsl_defines({3, -1, 5, true})[2],
            "#define TESSERA_SEAMS_CLAMP_UNIT " + std::to_string(3 + classes));

  expect_bad_points_refused(*tex, max_units, max_bindings, after);
  // Without clamp units only the border units and the records change.
  for (int u = 0; u < units; ++u) {
    glBindTextureUnit(GLuint(u), engine.array);
    glBindSampler(GLuint(u), engine.sampler);
  }
  ASSERT_TRUE(tex->bind({30, -1, 1, false}).ok());
  const Snapshot border_only = snapshot(units, bindings);
  for (int u = 0; u < units; ++u) {
    const bool mine = u >= 30 && u < 30 + classes;
    EXPECT_EQ(GLuint(border_only.array[std::size_t(u)]),
              mine ? tex->array_texture(u - 30) : engine.array)
        << "unit " << u;
  }
}

// The recipe's mesh step on the Disney samples: quads only (teapot), n-gons split into subfaces
// (nonquad, pentagon), and the refusals.
TEST(PtexQuadMesh, DisneySamplesAndRefusals) {
  TESSERA_REQUIRE_SHARED_DATA(data);
  const std::filesystem::path dir = data / "ptex";
  if (!std::filesystem::is_directory(dir)) TESSERA_SKIP_OR_FAIL("shared", "no ptex samples");
  auto load = [&](const std::string& name) {
    Result<faces::PolygonMesh> obj =
        faces::load_obj_polygons((dir / name / (name + ".obj")).string());
    Result<ptex::PtexFile> file = ptex::read_ptex((dir / name / (name + ".ptx")).string());
    EXPECT_TRUE(obj.ok()) << obj.status().message;
    return std::pair{std::move(*obj), std::move(file)};
  };
  for (const char* name : {"teapot", "nonquad", "pentagon"}) {
    SCOPED_TRACE(name);
    auto [obj, file] = load(name);
    ASSERT_TRUE(file.ok()) << file.status().message;
    Result<faces::QuadMesh> mesh = faces::ptex_quad_mesh(obj, *file, name);
    ASSERT_TRUE(mesh.ok()) << mesh.status().message;
    EXPECT_EQ(mesh->face_count(), file->face_count());
    // The file's own adjacency agrees with the mesh's (face f of the mesh is Ptex face f).
    Result<std::vector<faces::FaceAdjacency>> adj = faces::build_adjacency(*mesh);
    ASSERT_TRUE(adj.ok()) << adj.status().message;
    // Every edge the file links between faces of one kind (quad-quad, subface-subface) is the
    // mesh's; an edge between a subface and a quad is a T-junction in the mesh (no shared edge).
    int agree = 0, edges = 0, t_junctions = 0;
    for (int f = 0; f < file->face_count(); ++f) {
      for (int e = 0; e < 4; ++e) {
        const int nf = file->faces[std::size_t(f)].adj_faces[std::size_t(e)];
        if (nf < 0) continue;
        if (file->faces[std::size_t(f)].subface != file->faces[std::size_t(nf)].subface) {
          ++t_junctions;
          continue;
        }
        ++edges;
        agree += (*adj)[std::size_t(f)].face[std::size_t(e)] == nf;
      }
    }
    std::printf(
        "%s: %d polygons -> %d Ptex faces; %d of %d file edges match the mesh (%d "
        "subface-quad edges)\n",
        name, int(obj.faces.size()), mesh->face_count(), agree, edges, t_junctions);
    EXPECT_EQ(agree, edges);
    EXPECT_GT(edges, 0);
  }
  // An n-gon the file did not split: the teapot's (quad-only) file under nonquad's polygons.
  {
    auto [obj, file] = load("nonquad");
    auto [tobj, tfile] = load("teapot");
    ASSERT_TRUE(tfile.ok());
    Result<faces::QuadMesh> mesh = faces::ptex_quad_mesh(obj, *tfile, "nonquad.obj");
    ASSERT_FALSE(mesh.ok());
    EXPECT_EQ(mesh.status().code, ErrorCode::unsupported);
    std::printf("refused: %s\n", mesh.status().message.c_str());
    EXPECT_NE(mesh.status().message.find("nonquad.obj: polygon "), std::string::npos);
    EXPECT_NE(mesh.status().message.find("is not a subface"), std::string::npos);
    // A quad mesh against a file with subfaces, and against fewer faces.
    Result<faces::QuadMesh> swapped = faces::ptex_quad_mesh(tobj, *file, "teapot.obj");
    ASSERT_FALSE(swapped.ok());
    EXPECT_EQ(swapped.status().code, ErrorCode::size_mismatch);
    faces::PolygonMesh fewer = tobj;
    fewer.faces.pop_back();
    Result<faces::QuadMesh> short_mesh = faces::ptex_quad_mesh(fewer, *tfile, "teapot.obj");
    ASSERT_FALSE(short_mesh.ok());
    EXPECT_NE(short_mesh.status().message.find("the file has"), std::string::npos)
        << short_mesh.status().message;
    // A triangle-mesh file (triangle.ptx) is refused naming the kind.
    auto [tri_obj, tri] = load("triangle");
    ASSERT_TRUE(tri.ok()) << tri.status().message;
    ASSERT_EQ(tri->mesh_type, ptex::MeshType::triangle);
    Result<faces::QuadMesh> t = faces::ptex_quad_mesh(tri_obj, *tri, "triangle.ptx");
    ASSERT_FALSE(t.ok());
    EXPECT_EQ(t.status().code, ErrorCode::unsupported);
    EXPECT_NE(t.status().message.find("triangle.ptx: a triangle-mesh Ptex file"), std::string::npos)
        << t.status().message;
  }
}

}  // namespace
