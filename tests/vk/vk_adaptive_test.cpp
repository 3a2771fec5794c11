// vk::AdaptiveSupersampler on its own (tessera/vk_adaptive.h): the budget is exact, the
// barriers without synchronization2 give the same bytes, the hook reads the engine's own
// descriptor set, bad input gives one-line errors before anything is recorded (counted on the
// command-recording entry points the component is handed), no object leaks (the validation
// layer's object tracking when the harness destroys its device). Negative controls: the
// messenger does count a leaked object; a valid record does reach the counted entry points.
#include <atomic>
#include <cstdio>
#include <cstring>
#include <map>

#include "vk/embedded_passes.h"
#include "vk_adaptive_test_util.h"
#include "vk_engine.h"  // examples/common: write_uniform_buffer

namespace tessera::vk_test {
namespace {

using VkAdaptive = EngineTest;

TEST_F(VkAdaptive, BudgetIsExactAndCountsAgree) {
  const SceneGBuffer g = scene_gbuffer(32, 24, 4);
  const auto o = scene_options<vk::AdaptiveSupersamplerOptions>(g);
  const VkFrameOut all = run_vk(*engine_, o, g, Which::adaptive);
  ASSERT_GT(all.extra, 10u);
  double sum = 0;
  for (float c : all.counts) sum += c - 1;
  EXPECT_EQ(std::uint64_t(sum), all.extra);
  for (std::int64_t b :
       {std::int64_t(0), std::int64_t(all.extra / 2), std::int64_t(all.extra * 2)}) {
    const VkFrameOut r = run_vk(*engine_, o, g, Which::adaptive, b);
    EXPECT_EQ(r.extra, std::min<std::uint64_t>(std::uint64_t(b), all.extra)) << "budget " << b;
  }
  const VkFrameOut ref = run_vk(*engine_, o, g, Which::reference);
  EXPECT_EQ(ref.extra, std::uint64_t(32 * 24 * 15));
}

/// The image: adaptive supersampling comes clearly closer to full supersampling than S alone,
/// and a budget of 0 extra samples gives S's image (the negative control: a component that
/// skipped its extra-sample passes would give it for every frame).
TEST_F(VkAdaptive, ImageApproachesFullSupersampling) {
  const SceneGBuffer g = scene_gbuffer(48, 32, 4);
  const auto o = scene_options<vk::AdaptiveSupersamplerOptions>(g);
  const VkFrameOut adaptive = run_vk(*engine_, o, g, Which::adaptive);
  const VkFrameOut reference = run_vk(*engine_, o, g, Which::reference);
  const VkFrameOut first = run_vk(*engine_, o, g, Which::first);
  const VkFrameOut none = run_vk(*engine_, o, g, Which::adaptive, 0);
  const double a = psnr_rgb(adaptive.colour, reference.colour);
  const double s = psnr_rgb(first.colour, reference.colour);
  std::printf("adaptive %.2f dB, 1 spp %.2f dB against full supersampling\n", a, s);
  EXPECT_GE(a, s + 6.0);
  EXPECT_EQ(none.colour, first.colour);
  EXPECT_EQ(none.extra, 0u);
  EXPECT_LT(psnr_rgb(none.colour, reference.colour), a - 6.0);
}

/// The built-in METRICS and LIST read any layout: the scene's G-buffer repacked (other slots,
/// permuted channels, stored with a scale and a bias that are exact in float) under the layout
/// that says so gives the same bytes as the scene's own layout, with UVs and without, at m = 2
/// and 3. The negative control: the repacked G-buffer read with the scene's layout differs.
TEST_F(VkAdaptive, BuiltInPassesReadAnyLayout) {
  for (int m : {2, 3}) {
    const SceneGBuffer g = scene_gbuffer(24, 16, m);
    SceneGBuffer r = g;
    for (std::size_t i = 0; i < g.slots[0].size(); i += 4) {
      const float* a = &g.slots[0][i];  // depth, normal
      const float* b = &g.slots[1][i];  // id, uv, 0
      const float* c = &g.slots[2][i];  // uv derivatives
      std::copy_n(std::array<float, 4>{b[2], 0.25f * a[0], b[1], 2.0f * b[0] - 6.0f}.data(), 4,
                  &r.slots[0][i]);
      std::copy_n(std::array<float, 4>{a[3], a[1], 0.0f, a[2]}.data(), 4, &r.slots[1][i]);
      std::copy_n(std::array<float, 4>{c[3], c[2], c[1], c[0]}.data(), 4, &r.slots[2][i]);
    }
    AdaptiveGBufferLayout l;
    l.depth = {0, "g", 4.0f, 0.0f};
    l.normal = {1, "ywx"};
    l.id = {0, "a", 0.5f, 3.0f};
    l.uv = {0, "br"};
    l.uv_derivatives = {2, "abgr"};
    for (bool uv : {true, false}) {
      auto o = scene_options<vk::AdaptiveSupersamplerOptions>(g);
      if (!uv) {
        o.layout.uv = o.layout.uv_derivatives = {};
        o.hook.source = R"(vec4 tessera_shade_sample(ivec2 g, float footprint) {
  int id = tessera_adaptive_id(g);
  if (id < 0) return vec4(0.05, 0.05, 0.08, 1.0);
  vec3 n = normalize(tessera_adaptive_normal(g));
  float d = tessera_adaptive_depth(g);
  return vec4(vec3(0.2 + 0.1 * float(id % 5)) * max(n.z, 0.0) + vec3(fract(d)), 1.0);
}
)";
      }
      auto repacked = o;
      repacked.layout = l;
      if (!uv) repacked.layout.uv = repacked.layout.uv_derivatives = {};
      const VkFrameOut want = run_vk(*engine_, o, g, Which::adaptive);
      const VkFrameOut got = run_vk(*engine_, repacked, r, Which::adaptive);
      ASSERT_FALSE(want.counts.empty());
      EXPECT_GT(want.extra, 0u);
      EXPECT_EQ(got.counts, want.counts) << "m = " << m << (uv ? ", UVs" : "");
      EXPECT_EQ(got.colour, want.colour) << "m = " << m << (uv ? ", UVs" : "");
      if (uv && m == 2) {
        const VkFrameOut wrong = run_vk(*engine_, o, r, Which::adaptive);
        EXPECT_NE(wrong.counts, want.counts);
      }
    }
  }
}

/// `create` takes METRICS and LIST built in (their modules name the specialization constants
/// in the component's shader binary) and compiles the passes with the hook only.
TEST_F(VkAdaptive, CreateTakesTheBuiltInMetricsAndListPasses) {
  const SceneGBuffer g = scene_gbuffer(16, 8, 3);
  const bool device_fp64 = engine_->context().enabled_features.shaderFloat64 == VK_TRUE;
  for (bool fp64 : {device_fp64, false}) {
    auto o = scene_options<vk::AdaptiveSupersamplerOptions>(g);
    vk::DeviceContext ctx = engine_->context();
    ctx.enabled_features.shaderFloat64 = fp64 ? VK_TRUE : VK_FALSE;
    auto c = vk::AdaptiveSupersampler::create(ctx, o);
    ASSERT_TRUE(c.ok()) << c.status().message;
    EXPECT_EQ((*c)->float64(), fp64);
    const std::vector<std::uint8_t>& b = (*c)->shader_binary();
    const std::string bytes(b.begin(), b.end());
    int built_in = 0;
    for (std::size_t at = bytes.find("tessera_adaptive_spec_has_uv"); at != std::string::npos;
         at = bytes.find("tessera_adaptive_spec_has_uv", at + 1)) {
      ++built_in;
    }
    EXPECT_EQ(built_in, 2) << "METRICS and LIST, fp64 " << fp64;
  }
}

TEST_F(VkAdaptive, WithoutSynchronization2SameBytes) {
  const SceneGBuffer g = scene_gbuffer(24, 16, 2);
  const auto o = scene_options<vk::AdaptiveSupersamplerOptions>(g);
  ASSERT_TRUE(engine_->context().synchronization2) << "lavapipe has Vulkan 1.3";
  const VkFrameOut with = run_vk(*engine_, o, g, Which::adaptive);
  TearDown();
  EngineOptions eo;
  eo.synchronization2 = false;
  make_engine(eo);
  ASSERT_FALSE(engine_->context().synchronization2);
  const VkFrameOut without = run_vk(*engine_, o, g, Which::adaptive);
  EXPECT_EQ(with.colour, without.colour);
  EXPECT_EQ(with.counts, without.counts);
}

/// Several records in one command buffer, on two G-buffers (descriptor sets follow the views;
/// the barriers between records satisfy synchronization validation): the last one's image is
/// the image of that frame alone.
TEST_F(VkAdaptive, RecordsInOneCommandBufferAndViewChanges) {
  const SceneGBuffer a = scene_gbuffer(16, 12, 2);
  SceneGBuffer b = a;
  for (std::size_t i = 0; i < b.slots[0].size(); i += 4) b.slots[0][i] *= 1.5f;   // other depths
  for (std::size_t i = 1; i < b.slots[1].size(); i += 4) b.slots[1][i] += 0.37f;  // other uvs
  auto o = scene_options<vk::AdaptiveSupersamplerOptions>(a);
  const VkFrameOut alone = run_vk(*engine_, o, b, Which::adaptive);
  const VkFrameOut other = run_vk(*engine_, o, a, Which::adaptive);
  ASSERT_NE(alone.colour, other.colour);  // the two G-buffers give different images
  auto c = vk::AdaptiveSupersampler::create(engine_->context(), o);
  ASSERT_TRUE(c.ok()) << c.status().message;
  std::array<EngineImage, 6> imgs;
  vk::AdaptiveFrame fa, fb;
  for (std::size_t s = 0; s < 3; ++s) {
    imgs[s] = engine_->upload_rgba(VK_FORMAT_R32G32B32A32_SFLOAT, 32, 24, a.slots[s],
                                   VK_IMAGE_USAGE_SAMPLED_BIT);
    imgs[3 + s] = engine_->upload_rgba(VK_FORMAT_R32G32B32A32_SFLOAT, 32, 24, b.slots[s],
                                       VK_IMAGE_USAGE_SAMPLED_BIT);
    fa.gbuffer[s] = imgs[s].resource;
    fb.gbuffer[s] = imgs[3 + s].resource;
  }
  ASSERT_TRUE((*c)->begin_frame(0).ok());
  VkCommandBuffer cmd = engine_->begin();
  Result<vk::AdaptiveOutput> r = (*c)->record(cmd, fa);
  ASSERT_TRUE(r.ok()) << r.status().message;
  EXPECT_EQ(r->view, 0u);
  for (std::size_t s = 0; s < 3; ++s) {  // the state the first record left them in
    fa.gbuffer[s].layout = r->gbuffer_layout[s];
    fa.gbuffer[s].stage = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
    fa.gbuffer[s].access = 0;
  }
  ASSERT_TRUE((*c)->record_reference(cmd, fa).ok());
  r = (*c)->record(cmd, fb);
  ASSERT_TRUE(r.ok()) << r.status().message;
  EXPECT_EQ(r->view, 2u);  // the third record of the frame
  engine_->submit_and_wait(cmd);
  EXPECT_EQ(engine_->read_back(r->colour), alone.colour);
  EXPECT_EQ(engine_->read_back(r->sample_counts), alone.counts);
  c->reset();
  for (EngineImage& img : imgs) engine_->destroy(img);
}

/// The hook reads a tint from the engine's own uniform buffer in set 0.
TEST_F(VkAdaptive, HookReadsTheEnginesDescriptorSet) {
  const SceneGBuffer g = scene_gbuffer(16, 12, 2);
  auto o = scene_options<vk::AdaptiveSupersamplerOptions>(g);
  const std::string inner = std::string(kSceneHook);
  auto renamed = [&](const std::string& to) {
    std::string s = inner;
    s.replace(s.find("tessera_shade_sample"), 20, to);
    return s;
  };
  o.hook.source = renamed("scene_shade") +
                  "vec4 tessera_shade_sample(ivec2 g, float f) {\n"
                  "  return scene_shade(g, f) * vec4(0.5, 0.25, 2.0, 1.0);\n}\n";
  const VkFrameOut constant = run_vk(*engine_, o, g, Which::adaptive);

  const VkDevice dev = engine_->context().device;
  VkDescriptorSetLayoutBinding b{};
  b.binding = 0;
  b.descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
  b.descriptorCount = 1;
  b.stageFlags = VK_SHADER_STAGE_COMPUTE_BIT;
  VkDescriptorSetLayoutCreateInfo li{};
  li.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO;
  li.bindingCount = 1;
  li.pBindings = &b;
  VkDescriptorSetLayout layout = VK_NULL_HANDLE;
  ASSERT_EQ(vkCreateDescriptorSetLayout(dev, &li, nullptr, &layout), VK_SUCCESS);
  EngineBuffer tint = engine_->host_buffer(16, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
  const float t[4] = {0.5f, 0.25f, 2.0f, 1.0f};
  std::memcpy(tint.data, t, sizeof t);
  VkDescriptorPoolSize ps{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1};
  VkDescriptorPoolCreateInfo pi{};
  pi.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO;
  pi.maxSets = 1;
  pi.poolSizeCount = 1;
  pi.pPoolSizes = &ps;
  VkDescriptorPool pool = VK_NULL_HANDLE;
  ASSERT_EQ(vkCreateDescriptorPool(dev, &pi, nullptr, &pool), VK_SUCCESS);
  VkDescriptorSetAllocateInfo ai{};
  ai.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO;
  ai.descriptorPool = pool;
  ai.descriptorSetCount = 1;
  ai.pSetLayouts = &layout;
  VkDescriptorSet set = VK_NULL_HANDLE;
  ASSERT_EQ(vkAllocateDescriptorSets(dev, &ai, &set), VK_SUCCESS);
  engine::write_uniform_buffer(dev, set, tint.buffer, 16);

  o.hook_set_layouts = {layout};
  o.hook.source = renamed("scene_shade") +
                  "layout(set = 0, binding = 0) uniform EngineTint { vec4 engine_tint; };\n"
                  "vec4 tessera_shade_sample(ivec2 g, float f) {\n"
                  "  return scene_shade(g, f) * engine_tint;\n}\n";
  VkFrameOut bound;
  {
    o.profile = false;
    auto c = vk::AdaptiveSupersampler::create(engine_->context(), o);
    ASSERT_TRUE(c.ok()) << c.status().message;
    EXPECT_EQ((*c)->descriptor_set_index(), 1u);
    std::array<EngineImage, 3> imgs;
    vk::AdaptiveFrame frame;
    for (std::size_t s = 0; s < 3; ++s) {
      imgs[s] = engine_->upload_rgba(VK_FORMAT_R32G32B32A32_SFLOAT, g.w * g.m, g.h * g.m,
                                     g.slots[s], VK_IMAGE_USAGE_SAMPLED_BIT);
      frame.gbuffer[s] = imgs[s].resource;
    }
    frame.hook_sets = {set};
    ASSERT_TRUE((*c)->begin_frame(0).ok());
    VkCommandBuffer cmd = engine_->begin();
    Result<vk::AdaptiveOutput> r = (*c)->record(cmd, frame);
    ASSERT_TRUE(r.ok()) << r.status().message;
    engine_->submit_and_wait(cmd);
    bound.colour = engine_->read_back(r->colour);
    for (EngineImage& img : imgs) engine_->destroy(img);
  }
  EXPECT_EQ(bound.colour, constant.colour);
  vkDestroyDescriptorPool(dev, pool, nullptr);
  vkDestroyDescriptorSetLayout(dev, layout, nullptr);
  engine_->destroy(tint);
}

// --- Bad input: one line, nothing recorded -----------------------------------------------------

// The command-recording entry points the component gets are counted (every record starts with
// a pipeline barrier and binds descriptor sets).
std::atomic<int> g_recorded{0};
PFN_vkGetDeviceProcAddr g_real_gdpa = nullptr;
PFN_vkCmdPipelineBarrier g_real_barrier = nullptr;
PFN_vkCmdPipelineBarrier2 g_real_barrier2 = nullptr;
PFN_vkCmdBindDescriptorSets g_real_bind = nullptr;
VKAPI_ATTR void VKAPI_CALL counted_barrier(VkCommandBuffer c, VkPipelineStageFlags a,
                                           VkPipelineStageFlags b, VkDependencyFlags d,
                                           std::uint32_t n1, const VkMemoryBarrier* p1,
                                           std::uint32_t n2, const VkBufferMemoryBarrier* p2,
                                           std::uint32_t n3, const VkImageMemoryBarrier* p3) {
  ++g_recorded;
  g_real_barrier(c, a, b, d, n1, p1, n2, p2, n3, p3);
}
VKAPI_ATTR void VKAPI_CALL counted_barrier2(VkCommandBuffer c, const VkDependencyInfo* d) {
  ++g_recorded;
  g_real_barrier2(c, d);
}
VKAPI_ATTR void VKAPI_CALL counted_bind(VkCommandBuffer c, VkPipelineBindPoint p,
                                        VkPipelineLayout l, std::uint32_t first, std::uint32_t n,
                                        const VkDescriptorSet* s, std::uint32_t nd,
                                        const std::uint32_t* d) {
  ++g_recorded;
  g_real_bind(c, p, l, first, n, s, nd, d);
}
VKAPI_ATTR PFN_vkVoidFunction VKAPI_CALL counting_gdpa(VkDevice dev, const char* name) {
  const std::string n = name;
  if (n == "vkCmdPipelineBarrier") {
    g_real_barrier = reinterpret_cast<PFN_vkCmdPipelineBarrier>(g_real_gdpa(dev, name));
    return reinterpret_cast<PFN_vkVoidFunction>(&counted_barrier);
  }
  if (n == "vkCmdPipelineBarrier2" || n == "vkCmdPipelineBarrier2KHR") {
    g_real_barrier2 = reinterpret_cast<PFN_vkCmdPipelineBarrier2>(g_real_gdpa(dev, name));
    return reinterpret_cast<PFN_vkVoidFunction>(&counted_barrier2);
  }
  if (n == "vkCmdBindDescriptorSets") {
    g_real_bind = reinterpret_cast<PFN_vkCmdBindDescriptorSets>(g_real_gdpa(dev, name));
    return reinterpret_cast<PFN_vkVoidFunction>(&counted_bind);
  }
  return g_real_gdpa(dev, name);
}

class VkAdaptiveErrors : public VkAdaptive {
 protected:
  void SetUp() override {
    VkAdaptive::SetUp();
    if (!engine_) return;
    ctx_ = engine_->context();
    g_real_gdpa = ctx_.get_device_proc_addr;
    ctx_.get_device_proc_addr = &counting_gdpa;
    g_ = scene_gbuffer(8, 6, 2);
    options_ = scene_options<vk::AdaptiveSupersamplerOptions>(g_);
  }
  void TearDown() override {
    for (EngineImage& img : imgs_) engine_->destroy(img);
    VkAdaptive::TearDown();
  }
  vk::AdaptiveFrame frame() {
    vk::AdaptiveFrame f;
    for (std::size_t s = 0; s < 3; ++s) {
      if (!imgs_[s].image) {
        imgs_[s] = engine_->upload_rgba(VK_FORMAT_R32G32B32A32_SFLOAT, g_.w * g_.m, g_.h * g_.m,
                                        g_.slots[s], VK_IMAGE_USAGE_SAMPLED_BIT);
      }
      f.gbuffer[s] = imgs_[s].resource;
    }
    return f;
  }
  /// The record's error (into a command buffer that is not recording: a recorded command would
  /// also be a validation error), and that nothing was recorded.
  std::string record_error(const vk::AdaptiveFrame& f) {
    auto c = vk::AdaptiveSupersampler::create(ctx_, options_);
    EXPECT_TRUE(c.ok()) << c.status().message;
    if (!c) return "";
    EXPECT_TRUE((*c)->begin_frame(0).ok());
    g_recorded = 0;
    Result<vk::AdaptiveOutput> r = (*c)->record(engine_->idle_command_buffer(), f);
    EXPECT_FALSE(r.ok());
    EXPECT_EQ(g_recorded.load(), 0);
    const std::string m = r ? "" : r.status().message;
    EXPECT_EQ(m.find('\n'), std::string::npos) << m;
    return m;
  }
  vk::DeviceContext ctx_;
  SceneGBuffer g_;
  vk::AdaptiveSupersamplerOptions options_;
  std::array<EngineImage, 3> imgs_;
};

TEST_F(VkAdaptiveErrors, ValidRecordIsCounted) {  // the positive control of "nothing recorded"
  auto c = vk::AdaptiveSupersampler::create(ctx_, options_);
  ASSERT_TRUE(c.ok()) << c.status().message;
  g_recorded = 0;
  ASSERT_TRUE((*c)->begin_frame(0).ok());
  VkCommandBuffer cmd = engine_->begin();
  ASSERT_TRUE((*c)->record(cmd, frame()).ok());
  engine_->submit_and_wait(cmd);
  EXPECT_GT(g_recorded.load(), 1);
}

TEST_F(VkAdaptiveErrors, NoDevice) {
  auto c = vk::AdaptiveSupersampler::create(vk::DeviceContext{}, options_);
  ASSERT_FALSE(c.ok());
  EXPECT_NE(c.status().message.find("no VkInstance"), std::string::npos) << c.status().message;
  EXPECT_TRUE(vk::check_device(ctx_).ok());
  vk::DeviceContext no_gdpa = ctx_;
  no_gdpa.get_device_proc_addr = nullptr;
  EXPECT_NE(vk::check_device(no_gdpa).message.find("no vkGetDeviceProcAddr"), std::string::npos);
  vk::DeviceContext bad_family = ctx_;
  bad_family.queue_family = 99;
  const Status s = vk::check_device(bad_family);
  EXPECT_NE(s.message.find("queue_family = 99"), std::string::npos) << s.message;
}

TEST_F(VkAdaptiveErrors, MissingFeatureIsNamed) {
  ctx_.enabled_features.shaderStorageImageExtendedFormats = VK_FALSE;
  auto c = vk::AdaptiveSupersampler::create(ctx_, options_);
  ASSERT_FALSE(c.ok());
  EXPECT_EQ(c.status().code, ErrorCode::unsupported);
  EXPECT_NE(c.status().message.find("shaderStorageImageExtendedFormats"), std::string::npos)
      << c.status().message;
  options_.sample_count_texture = false;  // without the counts the feature is not needed
  EXPECT_TRUE(vk::AdaptiveSupersampler::create(ctx_, options_).ok());
  // Without fp64 the component runs, its depth metric in float (vk_frames_test.cpp: agreement).
  ctx_.enabled_features.shaderFloat64 = VK_FALSE;
  c = vk::AdaptiveSupersampler::create(ctx_, options_);
  ASSERT_TRUE(c.ok()) << c.status().message;
  EXPECT_FALSE((*c)->float64());
}

TEST_F(VkAdaptiveErrors, HookCompileErrorHasTheHooksLine) {
  options_.hook.name = "bad_hook";
  options_.hook.source =
      "vec4 tessera_shade_sample(ivec2 g, float footprint) {\n"
      "  float x = 1.0;\n"
      "  return vec4(x, undeclared_thing, 0.0, 1.0);\n"
      "}\n";
  auto c = vk::AdaptiveSupersampler::create(ctx_, options_);
  ASSERT_FALSE(c.ok());
  std::printf("%s\n", c.status().message.c_str());
  EXPECT_NE(c.status().message.find("bad_hook:3:"), std::string::npos) << c.status().message;
  EXPECT_NE(c.status().message.find("undeclared_thing"), std::string::npos) << c.status().message;
  EXPECT_EQ(c.status().message.find('\n'), std::string::npos) << c.status().message;
}

TEST_F(VkAdaptiveErrors, BadOptions) {
  options_.m = 9;
  auto c = vk::AdaptiveSupersampler::create(ctx_, options_);
  ASSERT_FALSE(c.ok());
  EXPECT_NE(c.status().message.find("m = 9"), std::string::npos) << c.status().message;
  options_.m = 2;
  options_.layout.normal.channels = "rg";
  c = vk::AdaptiveSupersampler::create(ctx_, options_);
  ASSERT_FALSE(c.ok());
  EXPECT_NE(c.status().message.find("layout.normal"), std::string::npos) << c.status().message;
}

TEST_F(VkAdaptiveErrors, WrongImageSize) {
  vk::AdaptiveFrame f = frame();
  f.gbuffer[1].extent.width -= 1;
  const std::string m = record_error(f);
  EXPECT_NE(m.find("G-buffer slot 1: image is 15x12, smaller than the G-buffer 16x12"),
            std::string::npos)
      << m;
}

TEST_F(VkAdaptiveErrors, FrameSlotAndRenderSize) {
  auto c = vk::AdaptiveSupersampler::create(ctx_, options_);
  ASSERT_TRUE(c.ok()) << c.status().message;
  g_recorded = 0;
  Result<vk::AdaptiveOutput> r = (*c)->record(engine_->idle_command_buffer(), frame());
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message.find("record before begin_frame"), std::string::npos);
  const Status s = (*c)->begin_frame(2);  // frames_in_flight = 2
  EXPECT_NE(s.message.find("begin_frame(2): frame slots are 0..1"), std::string::npos) << s.message;
  EXPECT_EQ(g_recorded.load(), 0);
  vk::AdaptiveFrame f = frame();
  f.render_size = {9, 6};  // the options' size is 8x6
  std::string m = record_error(f);
  EXPECT_NE(m.find("render size 9x6 (1..8 x 1..6"), std::string::npos) << m;
  f.render_size = {4, 3};  // smaller: fine, and a smaller G-buffer would do
  f.gbuffer[0].extent = {7, 6};
  m = record_error(f);
  EXPECT_NE(m.find("G-buffer slot 0: image is 7x6, smaller than the G-buffer 8x6"),
            std::string::npos)
      << m;
  options_.frames_in_flight = 0;
  EXPECT_NE(vk::AdaptiveSupersampler::create(ctx_, options_)
                .status()
                .message.find("frames_in_flight = 0 (1..16)"),
            std::string::npos);
}

TEST_F(VkAdaptiveErrors, EngineOutputImage) {
  vk::AdaptiveFrame f = frame();
  EngineImage out = engine_->upload_rgba(VK_FORMAT_R32G32B32A32_SFLOAT, g_.w, g_.h, {},
                                         VK_IMAGE_USAGE_STORAGE_BIT);
  f.output = out.resource;
  f.output.usage = VK_IMAGE_USAGE_SAMPLED_BIT;
  EXPECT_NE(record_error(f).find("output image: usage 0x4 lacks VK_IMAGE_USAGE_STORAGE_BIT"),
            std::string::npos);
  f.output = out.resource;
  f.output.format = VK_FORMAT_R16G16B16A16_SFLOAT;
  EXPECT_NE(record_error(f).find("output image: VkFormat 97, the options' output is VkFormat 109"),
            std::string::npos);
  f.output = out.resource;
  f.output.extent = {7, 6};
  EXPECT_NE(record_error(f).find("output image: 7x6, smaller than the render size 8x6"),
            std::string::npos);
  engine_->destroy(out);
}

TEST_F(VkAdaptiveErrors, WrongFormat) {
  vk::AdaptiveFrame f = frame();
  EngineImage wrong = engine_->upload_rgba(VK_FORMAT_R8G8B8A8_UINT, g_.w * g_.m, g_.h * g_.m, {},
                                           VK_IMAGE_USAGE_SAMPLED_BIT);
  f.gbuffer[0] = wrong.resource;
  const std::string m = record_error(f);
  EXPECT_NE(m.find("G-buffer slot 0: VkFormat 41 is not a float or normalised"), std::string::npos)
      << m;
  engine_->destroy(wrong);
}

TEST_F(VkAdaptiveErrors, WrongUsage) {
  vk::AdaptiveFrame f = frame();
  EngineImage no_sampled =
      engine_->upload_rgba(VK_FORMAT_R32G32B32A32_SFLOAT, g_.w * g_.m, g_.h * g_.m, g_.slots[2],
                           VK_IMAGE_USAGE_STORAGE_BIT);
  f.gbuffer[2] = no_sampled.resource;
  const std::string m = record_error(f);
  EXPECT_NE(m.find("G-buffer slot 2: usage 0xA lacks VK_IMAGE_USAGE_SAMPLED_BIT"),
            std::string::npos)
      << m;
  engine_->destroy(no_sampled);
}

TEST_F(VkAdaptiveErrors, MissingImageUndefinedLayoutAndNegativeBudget) {
  vk::AdaptiveFrame f = frame();
  f.gbuffer[1] = vk::ImageResource{};
  EXPECT_NE(record_error(f).find("G-buffer slot 1: no VkImage"), std::string::npos);
  f = frame();
  f.gbuffer[0].layout = VK_IMAGE_LAYOUT_UNDEFINED;
  EXPECT_NE(record_error(f).find("G-buffer slot 0: layout 0"), std::string::npos);
  f = frame();
  f.budget = -1;
  EXPECT_NE(record_error(f).find("budget = -1"), std::string::npos);
  f = frame();
  f.hook_sets = {VK_NULL_HANDLE};
  EXPECT_NE(record_error(f).find("1 hook_sets for 0 hook_set_layouts"), std::string::npos);
}

// The leak check can fail: an object left alive is reported when the device is destroyed.
TEST(VkValidation, NegativeControlLeakIsCounted) {
  std::string missing;
  auto e = Engine::create({}, &missing);
  if (!e) TESSERA_SKIP_OR_FAIL(missing, e.status().message);
  VkSamplerCreateInfo si{};
  si.sType = VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO;
  si.maxLod = 0.0f;
  VkSampler leaked = VK_NULL_HANDLE;
  ASSERT_EQ(vkCreateSampler((*e)->context().device, &si, nullptr, &leaked), VK_SUCCESS);
  EXPECT_EQ((*e)->messages(), 0);
  (*e)->shutdown();
  EXPECT_GT((*e)->messages(), 0) << "the leaked VkSampler was not reported";
}

/// The passes the build compiles to SPIR-V and embeds (src/vk/embedded_passes.h, tools/vk_passes):
/// each a SPIR-V module whose every DescriptorSet decoration is the component's set as given;
/// the passes that shade are not embedded (compiled with the hook at create).
TEST(VkEmbeddedPasses, BudgetAndListPassesAreEmbeddedInTheComponentsSet) {
  for (const char* pass : vk::kEmbeddedPasses) {
    for (std::uint32_t set : {0u, 3u}) {
      const std::vector<std::uint32_t> w = vk::embedded_pass(pass, set);
      ASSERT_GT(w.size(), 5u) << pass << " is not embedded (glslangValidator at build time?)";
      EXPECT_EQ(w[0], 0x07230203u) << pass;  // the SPIR-V magic number
      int decorations = 0;
      for (std::size_t at = 5; at < w.size() && (w[at] >> 16) > 0; at += w[at] >> 16) {
        if ((w[at] & 0xffffu) == 71 && (w[at] >> 16) == 4 && w[at + 2] == 34) {  // DescriptorSet
          EXPECT_EQ(w[at + 3], set) << pass;
          ++decorations;
        }
      }
      EXPECT_GE(decorations, 2) << pass;  // the parameter block and the work buffer at least
    }
  }
  EXPECT_TRUE(vk::embedded_pass("FIRST", 0).empty());
  EXPECT_TRUE(vk::embedded_pass("SHADE", 0).empty());
}

/// METRICS and LIST are embedded in their variants, their samplers' bindings patched to the
/// layout's slots: each named sampler's Binding is the one asked for.
TEST(VkEmbeddedPasses, MetricsAndListVariantsTakeTheLayoutsBindings) {
  const std::vector<std::pair<std::string, std::uint32_t>> samplers = {
      {"tessera_adaptive_depth_texture", 7},
      {"tessera_adaptive_normal_texture", 6},
      {"tessera_adaptive_id_value_texture", 8},
      {"tessera_adaptive_uv_texture", 5},
      {"tessera_adaptive_uv_derivatives_texture", 5}};
  for (const char* variant : {"METRICS", "METRICS_NO_FP64", "LIST", "LIST_COUNTS"}) {
    const std::vector<std::uint32_t> w = vk::embedded_pass(variant, 2, samplers);
    ASSERT_GT(w.size(), 5u) << variant << " is not embedded";
    std::map<std::uint32_t, std::string> names;
    std::map<std::string, std::uint32_t> bound;
    for (std::size_t at = 5; at < w.size() && (w[at] >> 16) > 0; at += w[at] >> 16) {
      const std::uint32_t count = w[at] >> 16, op = w[at] & 0xffffu;
      if (op == 5) names[w[at + 1]] = reinterpret_cast<const char*>(&w[at + 2]);  // OpName
      if (op == 71 && count == 4 && w[at + 2] == 33 && names.count(w[at + 1])) {  // Binding
        bound[names[w[at + 1]]] = w[at + 3];
      }
    }
    int found = 0;
    for (const auto& [name, binding] : samplers) {
      if (!bound.count(name)) continue;
      EXPECT_EQ(bound[name], binding) << variant << " " << name;
      ++found;
    }
    EXPECT_GE(found, 3) << variant;  // depth, normal, id (METRICS); id, uv, derivatives (LIST)
  }
}

}  // namespace
}  // namespace tessera::vk_test
