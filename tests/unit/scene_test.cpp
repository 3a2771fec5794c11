// Tests of tessera/math.h and tessera/scene.h: matrices, OBJ/glTF loading, errors, cameras.
#include "tessera/scene.h"

#include <gtest/gtest.h>

#include <fstream>

#include "tessera/io.h"
#include "tessera/procedural.h"
#include "test_support.h"

namespace tessera::scene {
namespace {

namespace fs = std::filesystem;

void write_text(const fs::path& p, const std::string& text) {
  std::ofstream(p, std::ios::binary) << text;
}

TEST(Math, InverseAndProjection) {
  const Mat4 m =
      translation({1, 2, 3}) * rotation_quat(0, 0.38268343f, 0, 0.92387953f) * scaling({2, 3, 4});
  const Mat4 id = m * inverse(m);
  for (int c = 0; c < 4; ++c) {
    for (int r = 0; r < 4; ++r) EXPECT_NEAR(id.m[c][r], c == r ? 1.0f : 0.0f, 1e-5f);
  }
  // A point on the near plane maps to z/w = -1, on the far plane to +1 (OpenGL).
  const Mat4 p = perspective(90.0f, 1.0f, 1.0f, 10.0f);
  const Vec4 n = p * Vec4{0, 0, -1, 1}, f = p * Vec4{0, 0, -10, 1};
  EXPECT_NEAR(n.z / n.w, -1.0f, 1e-6f);
  EXPECT_NEAR(f.z / f.w, 1.0f, 1e-6f);
  // 90 degrees: x = -z maps to the right edge.
  const Vec4 e = p * Vec4{2, 0, -2, 1};
  EXPECT_NEAR(e.x / e.w, 1.0f, 1e-6f);
  // look_at puts the target straight ahead (-z in view space).
  const Mat4 v = look_at({1, 2, 3}, {1, 2, -7}, {0, 1, 0});
  const Vec3 t = v.transform_point({1, 2, -7});
  EXPECT_NEAR(t.x, 0, 1e-5f);
  EXPECT_NEAR(t.y, 0, 1e-5f);
  EXPECT_NEAR(t.z, -10, 1e-5f);
}

TEST(Obj, LoadsQuadsWithMaterialAndTexture) {
  const fs::path dir = test::temp_dir("obj");
  ASSERT_TRUE(
      io::write_png((dir / "tex.png").string(), make_procedural(Procedural::bricks, 16, 8)).ok());
  write_text(dir / "m.mtl", "newmtl red\nKd 1 0 0\nmap_Kd tex.png\n");
  write_text(dir / "q.obj",
             "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
             "usemtl red\nf 1/1 2/2 3/3 4/4\n");
  Result<Scene> s = load_scene((dir / "q.obj").string());
  ASSERT_TRUE(s.ok()) << s.status().message;
  ASSERT_EQ(s->meshes.size(), 1u);
  EXPECT_EQ(s->triangle_count(), 2u);
  EXPECT_EQ(s->meshes[0].positions.size(), 4u);
  const Material& m = s->materials[std::size_t(s->meshes[0].material)];
  EXPECT_EQ(m.name, "red");
  EXPECT_FLOAT_EQ(m.base_color[0], 1.0f);
  ASSERT_EQ(m.base_color_texture, 0);
  EXPECT_EQ(s->textures[0].image.width, 16);
  // Normals computed from the winding: +z.
  EXPECT_NEAR(s->meshes[0].normals[0].z, 1.0f, 1e-6f);
  // OBJ v flipped to image rows: vt (0, 1) -> (0, 0).
  EXPECT_FLOAT_EQ(s->meshes[0].uvs[3].y, 0.0f);
  EXPECT_FLOAT_EQ(s->bounds_max.y, 1.0f);
}

TEST(Obj, MalformedFilesAreOneLineErrors) {
  const fs::path dir = test::temp_dir("objbad");
  write_text(dir / "range.obj", "v 0 0 0\nv 1 0 0\nf 1 2 7\n");
  write_text(dir / "empty.obj", "# nothing\n");
  write_text(dir / "badtex.obj", "mtllib t.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl x\nf 1 2 3\n");
  write_text(dir / "t.mtl", "newmtl x\nmap_Kd missing.png\n");
  for (const char* name : {"range.obj", "empty.obj", "badtex.obj", "missing.obj"}) {
    const std::string path = (dir / name).string();
    Result<Scene> s = load_scene(path);
    ASSERT_FALSE(s.ok()) << name;
    EXPECT_NE(s.status().message.find(path), std::string::npos) << s.status().message;
    EXPECT_EQ(s.status().message.find('\n'), std::string::npos) << s.status().message;
  }
}

TEST(Gltf, MinimalFileWithDataUriAndTransforms) {
  // One triangle, positions as floats in a base64 data URI, node translated by (10, 0, 0) and
  // child scaled by 2.
  // Floats: (0,0,0) (1,0,0) (0,1,0) = 36 bytes.
  const std::string b64 = "AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA";
  const std::string gltf = R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],
    "nodes":[{"translation":[10,0,0],"children":[1]},{"scale":[2,2,2],"mesh":0}],
    "meshes":[{"name":"tri","primitives":[{"attributes":{"POSITION":0}}]}],
    "accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3",
                  "min":[0,0,0],"max":[1,1,0]}],
    "bufferViews":[{"buffer":0,"byteLength":36}],
    "buffers":[{"byteLength":36,"uri":"data:application/octet-stream;base64,)" +
                           b64 + R"("}]})";
  const fs::path dir = test::temp_dir("gltf");
  write_text(dir / "t.gltf", gltf);
  Result<Scene> s = load_scene((dir / "t.gltf").string());
  ASSERT_TRUE(s.ok()) << s.status().message;
  ASSERT_EQ(s->meshes.size(), 1u);
  EXPECT_EQ(s->triangle_count(), 1u);
  EXPECT_FLOAT_EQ(s->meshes[0].positions[1].x, 12.0f);
  EXPECT_FLOAT_EQ(s->meshes[0].positions[2].y, 2.0f);
  EXPECT_EQ(s->materials.back().name, "default");

  // The same file with an accessor that reads past its buffer view.
  std::string bad = gltf;
  bad.replace(bad.find("\"count\":3"), 9, "\"count\":9");
  write_text(dir / "bad.gltf", bad);
  Result<Scene> b = load_scene((dir / "bad.gltf").string());
  ASSERT_FALSE(b.ok());
  EXPECT_NE(b.status().message.find("bad.gltf"), std::string::npos);
  write_text(dir / "junk.gltf", "{\"asset\":");
  EXPECT_FALSE(load_scene((dir / "junk.gltf").string()).ok());
}

TEST(Gltf, DungeonLevel) {
  TESSERA_REQUIRE_SHARED_DATA(data);
  Result<Scene> s = load_scene((data / "scenes" / "dungeon" / "level-dungeon.gltf").string());
  ASSERT_TRUE(s.ok()) << s.status().message;
  EXPECT_EQ(s->triangle_count(), 32397u);
  EXPECT_EQ(s->materials.size(), 12u);  // 11 + default
  EXPECT_GE(s->textures.size(), 11u);
  int textured = 0;
  for (const Material& m : s->materials) textured += m.base_color_texture >= 0;
  EXPECT_GE(textured, 10);
}

TEST(Camera, ParseAndOrbit) {
  Result<Camera> c = parse_camera("0,1,5,0,0,0,0,1,0,45");
  ASSERT_TRUE(c.ok()) << c.status().message;
  EXPECT_FLOAT_EQ(c->eye.y, 1.0f);
  EXPECT_FLOAT_EQ(c->fov_y_degrees, 45.0f);
  EXPECT_FALSE(parse_camera("1,2,3").ok());
  EXPECT_FALSE(parse_camera("0,0,0,0,0,0,0,1,0,45").ok());  // eye == target
  EXPECT_FALSE(parse_camera("0,1,5,0,0,0,0,1,0,abc").ok());
  const Scene s = builtin_scene();
  const Camera a = orbit_camera(s, 0, 8), b = orbit_camera(s, 4, 8);
  const Vec3 centre = (s.bounds_min + s.bounds_max) * 0.5f;
  EXPECT_NEAR(length(a.eye - centre), length(b.eye - centre), 1e-4f);
  EXPECT_NEAR(a.eye.x - centre.x, -(b.eye.x - centre.x), 1e-3f);  // opposite sides
}

TEST(Builtin, SceneIsDeterministicAndValid) {
  const Scene a = builtin_scene(), b = builtin_scene();
  EXPECT_EQ(a.triangle_count(), b.triangle_count());
  EXPECT_GT(a.triangle_count(), 2000u);
  EXPECT_EQ(a.lights.size(), 4u);
  for (const Mesh& m : a.meshes) {
    EXPECT_EQ(m.normals.size(), m.positions.size());
    for (std::uint32_t i : m.indices) EXPECT_LT(i, m.positions.size());
  }
}

}  // namespace
}  // namespace tessera::scene
