// vk::FaceTextureSet (tessera/vk_faces.h) in an engine's own forward pass: the test engine's
// fragment shader includes seams.glsl (the one GLSL source of GL and Vulkan) with the
// component's glsl_defines, is compiled with shaderc, and draws the Disney teapot from
// ../shared/data/ptex with tessera_seams_sample_discard at the set index the engine chose; the
// frame agrees with the CPU Discard renderer (faces::FaceRenderer, trilinear) at >= 60 dB.
// Negative controls: the same shader reading the next face's record (face + 1) and the camera
// moved one pixel fall clearly below the bound. The packing is gl::FaceTextureSet's (same
// records, byte for byte). Bad input (no faces, colliding bindings, a null queue, a set index
// past the device's limit, a null command buffer) fails with one line before anything is
// created or recorded. Validation-clean and leak-free (vk_harness.h), or the test fails.
#include "tessera/vk_faces.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "ptex_report.h"  // examples/common: the example engines' vertex and frame block
#include "shaders.h"      // examples/engine_ptex_vk
#include "tessera/faces.h"
#include "tessera/faces_gpu.h"
#include "tessera/glsl.h"
#include "tessera/image_ops.h"
#include "tessera/metrics.h"
#include "tessera/ptex.h"
#include "test_support.h"
#include "vk_draw.h"

namespace tessera::vk_test {
namespace {

// The engine's stages: examples/engine_ptex_vk's own (the defines of
// vk::FaceTextureSet::glsl_defines go after #version: ExpandOptions::preamble).
const char* const kVertex = engine::kVertexShader;
const char* const kFragment = engine::kFragmentShader;

// The example engines' vertex (examples/common/ptex_report.h): 4 per face.
using Vertex = engine::FaceVertex;

struct Teapot {
  faces::FaceScene scene;
  faces::FaceTextureSet set;
};

constexpr int kW = 320, kH = 240;

using VkFaces = EngineTest;

Teapot load_teapot(const std::filesystem::path& data) {
  const std::string dir = (data / "ptex" / "teapot").string();
  Teapot t;
  auto poly = faces::load_obj_polygons(dir + "/teapot.obj");
  auto file = ptex::read_ptex(dir + "/teapot.ptx");
  EXPECT_TRUE(poly && file);
  if (!poly || !file) return t;
  auto mesh = faces::ptex_quad_mesh(*poly, *file, "teapot");
  auto set = faces::FaceTextureSet::from_ptex(*file, "teapot");
  EXPECT_TRUE(mesh && set) << (mesh ? set.status().message : mesh.status().message);
  if (!mesh || !set) return t;
  t.scene.name = "teapot";
  t.scene.mesh = std::move(*mesh);
  t.set = std::move(*set);
  return t;
}

// The engine's frame: 4 vertices per face, the camera moved `shift_px` right, the light (as
// examples/engine_ptex_vk's).
DrawInput frame_input(const Teapot& t, const scene::Camera& camera, float shift_px,
                      std::vector<Vertex>& verts) {
  DrawInput in;
  in.width = kW;
  in.height = kH;
  in.background.assign(std::size_t(kW) * kH * 4, 0.0f);
  for (std::size_t i = 0; i < in.background.size(); i += 4) {
    for (int c = 0; c < 3; ++c)
      in.background[i + std::size_t(c)] = faces::kFaceBackground[std::size_t(c)];
  }
  engine::face_vertices(t.scene.mesh, verts, in.indices);
  in.vertices = verts.data();
  in.vertex_bytes = verts.size() * sizeof(Vertex);
  in.stride = sizeof(Vertex);
  in.attributes = {{0, 0, VK_FORMAT_R32G32B32_SFLOAT, 0},
                   {1, 0, VK_FORMAT_R32G32B32_SFLOAT, 12},
                   {2, 0, VK_FORMAT_R32G32_SFLOAT, 24},
                   {3, 0, VK_FORMAT_R32_SINT, 32}};
  // The example engines' frame block (view-projection, light, ambient and diffuse).
  const engine::ForwardFrameBlock block = engine::forward_frame_block(camera, kW, kH, shift_px);
  in.frame.resize(sizeof block);
  std::memcpy(in.frame.data(), &block, sizeof block);
  return in;
}

// The engine's fragment stage for the component at `set` (face + `shift` as the control).
std::vector<std::uint32_t> fragment(const vk::FaceTextureSet& tex, std::uint32_t set, int faces,
                                    int shift) {
  glsl::ExpandOptions so;
  so.preamble = tex.glsl_defines(set);
  so.preamble.push_back("#define ENGINE_FACES " + std::to_string(faces));
  so.preamble.push_back("#define ENGINE_FACE_SHIFT " + std::to_string(shift));
  auto src = glsl::expand_includes({glsl::Stage::fragment, kFragment, "engine.frag"}, so);
  EXPECT_TRUE(src) << src.status().message;
  if (!src) return {};
  auto spirv = compile_glsl(VK_SHADER_STAGE_FRAGMENT_BIT, src->text, "engine.frag");
  EXPECT_TRUE(spirv) << (spirv ? "" : glsl::format_log(spirv.status().message, src->files));
  return spirv ? *spirv : std::vector<std::uint32_t>{};
}

/// The CPU Discard renderer's frame (trilinear, the zero-coverage fallback): the reference.
Result<faces::FaceFrame> cpu_discard_frame(const Teapot& t, const scene::Camera& camera) {
  auto cpu = faces::FaceRenderer::create(t.scene, t.set);
  if (!cpu) return cpu.status();
  faces::FaceRenderOptions o;
  o.width = kW;
  o.height = kH;
  o.sampling.method = faces::SeamMethod::discard;
  o.sampling.filter = texture::TextureFilter::trilinear;
  o.sampling.clamp_fallback = true;
  return (*cpu)->render(camera, o);
}

/// The teapot drawn by the test engine with `tex` at set 2 (set 1 is an empty hole), the
/// fragment shader reading face + `face_shift`, the camera `shift_px` right; `before_pass`
/// records into the frame's command buffer before its render pass (an upload).
ImageRGBAF render_teapot(Engine& e, const Teapot& t, const scene::Camera& camera,
                         vk::FaceTextureSet& tex, int face_shift, float shift_px,
                         std::function<Status(VkCommandBuffer)> before_pass = {}) {
  const std::uint32_t set = 2;
  auto vert = compile_glsl(VK_SHADER_STAGE_VERTEX_BIT, kVertex, "engine.vert");
  EXPECT_TRUE(vert) << vert.status().message;
  std::vector<Vertex> verts;
  DrawInput in = frame_input(t, camera, shift_px, verts);
  if (vert) in.vertex_spirv = *vert;
  in.fragment_spirv = fragment(tex, set, t.scene.mesh.face_count(), face_shift);
  in.component_layout = tex.set_layout();
  in.component_set = set;
  in.bind_component = [&](VkCommandBuffer cmd, VkPipelineLayout layout) {
    return tex.bind(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout, set);
  };
  in.before_pass = std::move(before_pass);
  auto pixels = draw(e, in);
  EXPECT_TRUE(pixels) << pixels.status().message;
  ImageRGBAF img(kW, kH);
  if (pixels) img.pixels = *pixels;
  return img;
}

TEST_F(VkFaces, TeapotDiscardAgreesWithCpu) {
  TESSERA_REQUIRE_SHARED_DATA(data);
  const Teapot t = load_teapot(data);
  ASSERT_EQ(t.scene.mesh.face_count(), 448);
  vk::FaceTextureSetOptions to;
  to.max_anisotropy = 1.0f;                               // trilinear: the CPU renderer's filter
  to.bindings = {2, 0, 5, VK_SHADER_STAGE_FRAGMENT_BIT};  // the engine's binding numbers
  auto tex = vk::FaceTextureSet::create(engine_->context(), t.set, to);
  ASSERT_TRUE(tex) << tex.status().message;
  EXPECT_GT((*tex)->class_count(), 1);
  EXPECT_EQ((*tex)->anisotropy(), 1.0f);
  // The GPU layout is the shared one (gl::FaceTextureSet packs the same records).
  auto packed = faces::pack_faces(t.set, {}, {});
  ASSERT_TRUE(packed);
  ASSERT_EQ(packed->records.size(), (*tex)->layout().records.size());
  EXPECT_EQ(std::memcmp(packed->records.data(), (*tex)->layout().records.data(),
                        packed->records.size() * sizeof(faces::FaceRecord)),
            0);

  const scene::Camera camera = faces::face_orbit_camera(t.scene, 1, 8);
  const Result<faces::FaceFrame> cpu_frame = cpu_discard_frame(t, camera);
  ASSERT_TRUE(cpu_frame) << cpu_frame.status().message;

  auto render = [&](int face_shift, float shift_px) {
    return render_teapot(*engine_, t, camera, **tex, face_shift, shift_px);
  };
  const double discard = test::psnr_srgb8(render(0, 0.0f), cpu_frame->image);
  const double wrong_face = test::psnr_srgb8(render(1, 0.0f), cpu_frame->image);
  const double shifted = test::psnr_srgb8(render(0, 1.0f), cpu_frame->image);
  std::printf(
      "teapot %dx%d, %d classes: Vulkan Discard vs CPU %.2f dB; controls: face + 1 "
      "%.2f dB, one pixel right %.2f dB\n",
      kW, kH, (*tex)->class_count(), discard, wrong_face, shifted);
  EXPECT_GE(discard, 60.0);
  EXPECT_LT(wrong_face, 40.0);
  EXPECT_LT(shifted, 45.0);
}

/// Every texel format, each uploaded in the engine's own command buffer (recorded before the
/// frame's render pass; nothing submitted by tessera; the staging buffer released after the
/// frame's completion) against the CPU Discard renderer: R32G32B32A32 the same image as the
/// queue-submitted upload, the smaller formats within their measured bounds and above the
/// one-pixel-moved control.
TEST_F(VkFaces, EveryTexelFormatUploadedInTheEnginesCommandBuffer) {
  TESSERA_REQUIRE_SHARED_DATA(data);
  const Teapot t = load_teapot(data);
  const scene::Camera camera = faces::face_orbit_camera(t.scene, 1, 8);
  const Result<faces::FaceFrame> cpu_frame = cpu_discard_frame(t, camera);
  ASSERT_TRUE(cpu_frame) << cpu_frame.status().message;
  vk::FaceTextureSetOptions to;
  to.max_anisotropy = 1.0f;
  to.bindings = {2, 0, 5, VK_SHADER_STAGE_FRAGMENT_BIT};
  auto submitted = vk::FaceTextureSet::create(engine_->context(), t.set, to);
  ASSERT_TRUE(submitted) << submitted.status().message;
  const ImageRGBAF reference = render_teapot(*engine_, t, camera, **submitted, 0, 0.0f);
  const double moved =
      test::psnr_srgb8(render_teapot(*engine_, t, camera, **submitted, 0, 1.0f), cpu_frame->image);
  struct Case {
    faces::TexelFormat format;
    double min_db;
    std::uint64_t bytes_per_texel;
  };
  // Bounds: measured on lavapipe (69.3, 69.1, 65.5, 64.4 dB; printed below) less 2 dB.
  for (const Case& c :
       {Case{faces::TexelFormat::rgba32f, 60.0, 16}, Case{faces::TexelFormat::rgba16f, 67.0, 8},
        Case{faces::TexelFormat::rgba8_unorm, 63.0, 4},
        Case{faces::TexelFormat::rgba8_srgb, 62.0, 4}}) {
    to.format = c.format;
    to.upload = vk::FaceUpload::engine_command_buffer;
    auto tex = vk::FaceTextureSet::create(engine_->context(), t.set, to);
    ASSERT_TRUE(tex) << tex.status().message;
    EXPECT_FALSE((*tex)->upload_recorded());
    EXPECT_EQ((*tex)->texture_bytes(), (*submitted)->texture_bytes() / 16 * c.bytes_per_texel);
    EXPECT_FALSE((*tex)->release_staging().ok());  // nothing recorded yet
    const ImageRGBAF img =
        render_teapot(*engine_, t, camera, **tex, 0, 0.0f,
                      [&](VkCommandBuffer cmd) { return (*tex)->record_upload(cmd); });
    EXPECT_TRUE((*tex)->upload_recorded());
    EXPECT_TRUE((*tex)->release_staging().ok());  // draw() waited for the frame
    const Status again = (*tex)->record_upload(engine_->idle_command_buffer());
    EXPECT_NE(again.message.find("recorded already"), std::string::npos) << again.message;
    const double db = test::psnr_srgb8(img, cpu_frame->image);
    std::printf("texel format %d: Vulkan Discard vs CPU %.2f dB (one pixel moved: %.2f dB)\n",
                int(c.format), db, moved);
    EXPECT_GE(db, c.min_db);
    EXPECT_GT(db, moved + 3.0);
    if (c.format == faces::TexelFormat::rgba32f) {
      EXPECT_EQ(img.pixels, reference.pixels);
    }
  }
  const Status wrong_mode = (*submitted)->record_upload(engine_->idle_command_buffer());
  EXPECT_NE(wrong_mode.message.find("queue_submit"), std::string::npos) << wrong_mode.message;
}

TEST_F(VkFaces, BadInputFailsWithOneLineBeforeAnything) {
  TESSERA_REQUIRE_SHARED_DATA(data);
  const Teapot t = load_teapot(data);
  auto one_line = [](const Status& s, const char* want) {
    EXPECT_FALSE(s.ok());
    EXPECT_EQ(s.message.find('\n'), std::string::npos) << s.message;
    EXPECT_NE(s.message.find(want), std::string::npos) << s.message;
  };
  one_line(vk::FaceTextureSet::create(engine_->context(), faces::FaceTextureSet{}).status(),
           "no faces");
  vk::FaceTextureSetOptions collide;
  collide.bindings.clamp = collide.bindings.faces;
  one_line(vk::FaceTextureSet::create(engine_->context(), t.set, collide).status(), "collide");
  vk::FaceTextureSetOptions no_stage;
  no_stage.bindings.stages = 0;
  one_line(vk::FaceTextureSet::create(engine_->context(), t.set, no_stage).status(), "stages");
  vk::DeviceContext no_queue = engine_->context();
  no_queue.queue = VK_NULL_HANDLE;
  one_line(vk::FaceTextureSet::create(no_queue, t.set).status(), "queue");
  vk::DeviceContext no_device = engine_->context();
  no_device.device = VK_NULL_HANDLE;
  EXPECT_FALSE(vk::FaceTextureSet::create(no_device, t.set).ok());

  auto tex = vk::FaceTextureSet::create(engine_->context(), t.set);
  ASSERT_TRUE(tex) << tex.status().message;
  // Recording into a command buffer that was never begun would be a validation error: the
  // refusals below must not reach it (the messenger counts any message).
  VkCommandBuffer idle = engine_->idle_command_buffer();
  VkPhysicalDeviceProperties props{};
  vkGetPhysicalDeviceProperties(engine_->context().physical_device, &props);
  const VkPipelineLayout fake = reinterpret_cast<VkPipelineLayout>(std::uintptr_t(1));
  one_line((*tex)->bind(idle, VK_PIPELINE_BIND_POINT_GRAPHICS, fake,
                        props.limits.maxBoundDescriptorSets),
           "maxBoundDescriptorSets");
  one_line((*tex)->bind(VK_NULL_HANDLE, VK_PIPELINE_BIND_POINT_GRAPHICS, fake, 0), "null");
  one_line((*tex)->bind(idle, VK_PIPELINE_BIND_POINT_GRAPHICS, VK_NULL_HANDLE, 0), "null");
  // Negative control: the defines name the chosen set and bindings.
  const std::vector<std::string> d = (*tex)->glsl_defines(3);
  EXPECT_EQ(d[1], "#define TESSERA_SEAMS_SET 3");
  EXPECT_EQ(d[2], "#define TESSERA_SEAMS_FACES_BINDING 0");
  EXPECT_EQ(d[0], "#define TESSERA_SEAMS_CLASSES " + std::to_string((*tex)->class_count()));
}

}  // namespace
}  // namespace tessera::vk_test
