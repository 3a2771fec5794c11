// vk::AdaptiveSupersampler in a real engine's frame loop (tessera/vk.h, "frames in flight"):
// 2 and 3 frames in flight with the GPU held behind by a timeline semaphore, several views a
// frame (more than a descriptor pool holds), each output copied out in the frame's own command
// buffer; dynamic resolution (a new render size every frame, inside max-size G-buffer images
// padded with other values); an engine-owned output image; a device without shaderFloat64;
// shader binaries and pipeline caches, also compiled without a device for two device kinds. Each
// output is compared bit for bit with the same G-buffer run alone (one record, submitted and
// waited for, by a component created for that size); every run is under the validation layer
// with synchronization validation (any message fails the test).
#include <cstring>
#include <memory>

#include "vk_adaptive_test_util.h"

namespace tessera::vk_test {
namespace {

using VkFrames = EngineTest;

/// Another G-buffer of the same scene: depths scaled, uvs shifted (another image).
SceneGBuffer variant(const SceneGBuffer& g, int i) {
  SceneGBuffer v = g;
  for (std::size_t t = 0; t < v.slots[0].size(); t += 4) v.slots[0][t] *= 1.0f + 0.25f * float(i);
  for (std::size_t t = 1; t < v.slots[1].size(); t += 4) v.slots[1][t] += 0.11f * float(i);
  return v;
}

/// A G-buffer uploaded as three images, padded to grid_w x grid_h texels (0 = its own size)
/// with values that are not the scene's: a read outside the render size would change the image.
struct Uploaded {
  std::array<EngineImage, 3> imgs;
  vk::AdaptiveFrame frame;
};

std::unique_ptr<Uploaded> upload(Engine& e, const SceneGBuffer& g, int grid_w = 0, int grid_h = 0) {
  const int gw = g.w * g.m, gh = g.h * g.m;
  grid_w = std::max(grid_w, gw);
  grid_h = std::max(grid_h, gh);
  auto u = std::make_unique<Uploaded>();
  for (std::size_t s = 0; s < 3; ++s) {
    std::vector<float> texels(std::size_t(grid_w) * std::size_t(grid_h) * 4, 0.0f);
    for (std::size_t i = 0; i < texels.size(); ++i) texels[i] = float(i % 7) * 0.37f - 0.5f;
    for (int y = 0; y < gh; ++y) {
      std::memcpy(&texels[(std::size_t(y) * std::size_t(grid_w)) * 4],
                  &g.slots[s][std::size_t(y) * std::size_t(gw) * 4], std::size_t(gw) * 16);
    }
    u->imgs[s] = e.upload_rgba(VK_FORMAT_R32G32B32A32_SFLOAT, grid_w, grid_h, texels,
                               VK_IMAGE_USAGE_SAMPLED_BIT);
    u->frame.gbuffer[s] = u->imgs[s].resource;
  }
  return u;
}

void destroy(Engine& e, Uploaded& u) {
  for (EngineImage& img : u.imgs) e.destroy(img);
}

/// One view of a frame: its G-buffer, render size and the image it must give.
struct View {
  Uploaded* in = nullptr;
  VkExtent2D size{0, 0};
  const VkFrameOut* expect = nullptr;
  vk::ImageResource output{};  // the engine's own, or none
};

/// What a submitted frame must give once its fence signalled.
struct Pending {
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  std::vector<PendingRead> colour, counts;
  std::vector<View> views;
  std::uint64_t frame = 0;
  std::uint32_t slot = 0;
};

/// The engine's frame loop: frame i opens slot i % F, records its views, each output copied out
/// in the same command buffer right after its record, and is submitted waiting for the
/// timeline value i + 1, which the host signals only when it reuses that slot (waiting for its
/// fence): the GPU runs F - 1 frames behind the host. Every output and profile is checked
/// against `expect` once its frame's fence signalled.
void frame_loop(Engine& e, vk::AdaptiveSupersampler& aa, std::uint32_t F,
                const std::vector<std::vector<View>>& frames) {
  const VkSemaphore timeline = e.timeline_semaphore();
  std::vector<VkFence> fences(F);
  for (VkFence& f : fences) f = e.fence();
  std::vector<Pending> pending(F);
  auto check = [&](Pending& p) {
    for (std::size_t v = 0; v < p.views.size(); ++v) {
      const std::string where = "frame " + std::to_string(p.frame) + " view " + std::to_string(v);
      EXPECT_EQ(e.finish_read(p.colour[v]), p.views[v].expect->colour) << where;
      EXPECT_EQ(e.finish_read(p.counts[v]), p.views[v].expect->counts) << where;
      Result<vk::AdaptiveProfile> prof = aa.read_profile(p.slot, std::uint32_t(v));
      ASSERT_TRUE(prof.ok()) << where << ": " << prof.status().message;
      EXPECT_EQ(prof->frame, p.frame) << where;
      EXPECT_EQ(prof->extra_samples, p.views[v].expect->extra) << where;
    }
    e.free(p.cmd);
    p = Pending{};
  };
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const std::uint32_t slot = std::uint32_t(i % F);
    if (pending[slot].cmd != VK_NULL_HANDLE) {
      e.signal(timeline, i - F + 1);  // release the slot's frame, then wait for it
      e.wait_and_reset(fences[slot]);
      check(pending[slot]);
    }
    ASSERT_TRUE(aa.begin_frame(slot).ok());
    Pending& p = pending[slot];
    p.cmd = e.begin();
    p.frame = i + 1;
    p.slot = slot;
    p.views = frames[i];
    for (std::size_t v = 0; v < frames[i].size(); ++v) {
      const View& view = frames[i][v];
      vk::AdaptiveFrame f = view.in->frame;
      f.render_size = view.size;
      f.output = view.output;
      Result<vk::AdaptiveOutput> r = aa.record(p.cmd, f);
      ASSERT_TRUE(r.ok()) << r.status().message;
      EXPECT_EQ(r->view, v);
      EXPECT_EQ(r->frame_slot, slot);
      for (std::size_t s = 0; s < 3; ++s) {  // what the record left them in, for the next
        view.in->frame.gbuffer[s].layout = r->gbuffer_layout[s];
        view.in->frame.gbuffer[s].stage = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
        view.in->frame.gbuffer[s].access = 0;
      }
      p.colour.push_back(e.record_read(p.cmd, r->colour, r->render_size));
      p.counts.push_back(e.record_read(p.cmd, r->sample_counts, r->render_size));
    }
    e.submit(p.cmd, timeline, i + 1, fences[slot]);
    // Held behind the semaphore: the frame's profile is not there yet.
    Result<vk::AdaptiveProfile> early = aa.read_profile(slot, 0);
    ASSERT_FALSE(early.ok());
    EXPECT_NE(early.status().message.find("has not completed"), std::string::npos)
        << early.status().message;
  }
  e.signal(timeline, frames.size());
  for (std::size_t k = 0; k < F; ++k) {
    const std::uint32_t slot = std::uint32_t((frames.size() + k) % F);
    if (pending[slot].cmd == VK_NULL_HANDLE) continue;
    e.wait_and_reset(fences[slot]);
    check(pending[slot]);
  }
  const VkDevice dev = e.context().device;
  for (VkFence f : fences) vkDestroyFence(dev, f, nullptr);
  vkDestroySemaphore(dev, timeline, nullptr);
}

/// F frames in flight x V views, each view its own G-buffer (the view's G-buffer changes every
/// frame), against each G-buffer run alone.
void views_in_flight(Engine& e, std::uint32_t F, int V, int frame_count) {
  const SceneGBuffer base = scene_gbuffer(16, 12, 2);
  auto o = scene_options<vk::AdaptiveSupersamplerOptions>(base);
  const int K = V + 1;
  std::vector<std::unique_ptr<Uploaded>> gbuffers;
  std::vector<VkFrameOut> alone;
  for (int k = 0; k < K; ++k) {
    const SceneGBuffer g = variant(base, k);
    alone.push_back(run_vk(e, o, g, Which::adaptive));
    gbuffers.push_back(upload(e, g));
  }
  ASSERT_NE(alone[0].colour, alone[1].colour);  // the views differ
  o.frames_in_flight = F;
  o.profile = true;
  auto aa = vk::AdaptiveSupersampler::create(e.context(), o);
  ASSERT_TRUE(aa.ok()) << aa.status().message;
  std::vector<std::vector<View>> frames;
  for (int i = 0; i < frame_count; ++i) {
    std::vector<View>& views = frames.emplace_back();
    for (int v = 0; v < V; ++v) {
      const std::size_t k = std::size_t((i + v) % K);
      views.push_back({gbuffers[k].get(), {0, 0}, &alone[k]});
    }
  }
  frame_loop(e, **aa, F, frames);
  aa->reset();
  for (auto& u : gbuffers) destroy(e, *u);
}

TEST_F(VkFrames, TwoFramesInFlightThreeViews) { views_in_flight(*engine_, 2, 3, 6); }

TEST_F(VkFrames, ThreeFramesInFlightThreeViews) { views_in_flight(*engine_, 3, 3, 7); }

// More views in one frame than one descriptor pool holds (8 sets): the slot grows.
TEST_F(VkFrames, MoreViewsThanAPool) { views_in_flight(*engine_, 2, 10, 3); }

/// A new render size every frame (2 frames in flight), the G-buffer rendered at that size into
/// the top-left of max-size images padded with other values, against a component created for
/// that size with a G-buffer of exactly that size.
TEST_F(VkFrames, DynamicResolutionEveryFrame) {
  const int W = 24, H = 16, m = 2;
  const std::vector<VkExtent2D> sizes = {{24, 16}, {17, 11}, {20, 13}, {12, 8}, {24, 16}, {9, 7}};
  std::vector<std::unique_ptr<Uploaded>> gbuffers;
  std::vector<VkFrameOut> alone;
  std::vector<std::vector<View>> frames;
  for (const VkExtent2D& s : sizes) {
    const SceneGBuffer g = scene_gbuffer(int(s.width), int(s.height), m);
    alone.push_back(
        run_vk(*engine_, scene_options<vk::AdaptiveSupersamplerOptions>(g), g, Which::adaptive));
    gbuffers.push_back(upload(*engine_, g, W * m, H * m));
  }
  for (std::size_t i = 0; i < sizes.size(); ++i) {
    frames.push_back({{gbuffers[i].get(), sizes[i], &alone[i]}});
  }
  SceneGBuffer largest;
  largest.w = W;
  largest.h = H;
  largest.m = m;
  auto o = scene_options<vk::AdaptiveSupersamplerOptions>(largest);
  o.profile = true;
  auto aa = vk::AdaptiveSupersampler::create(engine_->context(), o);
  ASSERT_TRUE(aa.ok()) << aa.status().message;
  frame_loop(*engine_, **aa, 2, frames);
  aa->reset();
  for (auto& u : gbuffers) destroy(*engine_, *u);
}

/// The engine's own output image (larger than the render size): the same image as the
/// component's own, and the texels beyond the render size kept.
TEST_F(VkFrames, EngineOwnedOutput) {
  const SceneGBuffer g = scene_gbuffer(16, 12, 2);
  auto o = scene_options<vk::AdaptiveSupersamplerOptions>(g);
  const VkFrameOut alone = run_vk(*engine_, o, g, Which::adaptive);
  std::unique_ptr<Uploaded> in = upload(*engine_, g);
  const std::vector<float> fill(20 * 14 * 4, 0.625f);
  EngineImage out =
      engine_->upload_rgba(VK_FORMAT_R32G32B32A32_SFLOAT, 20, 14, fill,
                           VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
  auto aa = vk::AdaptiveSupersampler::create(engine_->context(), o);
  ASSERT_TRUE(aa.ok()) << aa.status().message;
  ASSERT_TRUE((*aa)->begin_frame(0).ok());
  VkCommandBuffer cmd = engine_->begin();
  vk::AdaptiveFrame f = in->frame;
  f.output = out.resource;
  Result<vk::AdaptiveOutput> r = (*aa)->record(cmd, f);
  ASSERT_TRUE(r.ok()) << r.status().message;
  EXPECT_EQ(r->colour.image, out.image);
  engine_->submit_and_wait(cmd);
  const std::vector<float> whole = engine_->read_back(r->colour);
  std::vector<float> region;
  std::size_t kept = 0;
  for (std::size_t y = 0; y < 14; ++y) {
    for (std::size_t x = 0; x < 20; ++x) {
      const float* t = &whole[(y * 20 + x) * 4];
      if (x < 16 && y < 12) {
        region.insert(region.end(), t, t + 4);
      } else {
        kept += t[0] == 0.625f && t[3] == 0.625f ? 1 : 0;
      }
    }
  }
  EXPECT_EQ(region, alone.colour);
  EXPECT_EQ(kept, std::size_t(20 * 14 - 16 * 12));
  aa->reset();
  engine_->destroy(out);
  destroy(*engine_, *in);
}

/// The k maps of a device without shaderFloat64 (the feature not enabled) against the double
/// path's, on two scenes at m = 4 and m = 2.
TEST_F(VkFrames, WithoutFloat64KMapsAgree) {
  const std::array<SceneGBuffer, 2> scenes = {scene_gbuffer(64, 48, 4), scene_gbuffer(96, 64, 2)};
  std::array<VkFrameOut, 2> with, without;
  for (std::size_t i = 0; i < scenes.size(); ++i) {
    with[i] = run_vk(*engine_, scene_options<vk::AdaptiveSupersamplerOptions>(scenes[i]), scenes[i],
                     Which::adaptive);
  }
  TearDown();
  EngineOptions eo;
  eo.float64 = false;
  make_engine(eo);
  ASSERT_FALSE(engine_->context().enabled_features.shaderFloat64);
  {
    auto o = scene_options<vk::AdaptiveSupersamplerOptions>(scenes[0]);
    auto c = vk::AdaptiveSupersampler::create(engine_->context(), o);
    ASSERT_TRUE(c.ok()) << c.status().message;
    EXPECT_FALSE((*c)->float64());
  }
  for (std::size_t i = 0; i < scenes.size(); ++i) {
    without[i] = run_vk(*engine_, scene_options<vk::AdaptiveSupersamplerOptions>(scenes[i]),
                        scenes[i], Which::adaptive);
    const double same = same_fraction(with[i].counts, without[i].counts);
    std::printf("scene %zu: k maps %.4f %% identical, %llu vs %llu extra samples\n", i,
                100.0 * same, (unsigned long long)with[i].extra,
                (unsigned long long)without[i].extra);
    EXPECT_GE(same, 0.999) << "scene " << i;
    EXPECT_GT(with[i].extra, 0u);  // the metrics ask for samples: there is something to compare
  }
}

/// Shaders ahead of time: the shader binary of one component given to the next (no GLSL
/// compiled) and the engine's VkPipelineCache, filled, saved and loaded: the same image; a
/// binary for other options or truncated is refused in one line.
TEST_F(VkFrames, ShaderBinaryAndPipelineCache) {
  const SceneGBuffer g = scene_gbuffer(16, 12, 2);
  auto o = scene_options<vk::AdaptiveSupersamplerOptions>(g);
  const VkFrameOut compiled = run_vk(*engine_, o, g, Which::adaptive);
  const VkDevice dev = engine_->context().device;
  VkPipelineCacheCreateInfo ci{};
  ci.sType = VK_STRUCTURE_TYPE_PIPELINE_CACHE_CREATE_INFO;
  VkPipelineCache cache = VK_NULL_HANDLE;
  ASSERT_EQ(vkCreatePipelineCache(dev, &ci, nullptr, &cache), VK_SUCCESS);
  std::vector<std::uint8_t> binary;
  {
    o.pipeline_cache = cache;
    auto c = vk::AdaptiveSupersampler::create(engine_->context(), o);
    ASSERT_TRUE(c.ok()) << c.status().message;
    binary = (*c)->shader_binary();
  }
  ASSERT_GT(binary.size(), 1000u);
  std::size_t bytes = 0;
  ASSERT_EQ(vkGetPipelineCacheData(dev, cache, &bytes, nullptr), VK_SUCCESS);
  std::vector<std::uint8_t> data(bytes);
  ASSERT_EQ(vkGetPipelineCacheData(dev, cache, &bytes, data.data()), VK_SUCCESS);
  vkDestroyPipelineCache(dev, cache, nullptr);
  // The cache's header names this device (lavapipe keeps no pipeline data: the header alone).
  ASSERT_GE(bytes, 32u);
  std::uint32_t header[4];
  std::memcpy(header, data.data(), sizeof header);
  VkPhysicalDeviceProperties props{};
  vkGetPhysicalDeviceProperties(engine_->context().physical_device, &props);
  EXPECT_EQ(header[0], 32u);
  EXPECT_EQ(header[1], std::uint32_t(VK_PIPELINE_CACHE_HEADER_VERSION_ONE));
  EXPECT_EQ(header[2], props.vendorID);
  EXPECT_EQ(header[3], props.deviceID);
  // The next run of the engine: its saved cache and the binary.
  ci.initialDataSize = data.size();
  ci.pInitialData = data.data();
  ASSERT_EQ(vkCreatePipelineCache(dev, &ci, nullptr, &cache), VK_SUCCESS);
  o.pipeline_cache = cache;
  o.shader_binary = binary;
  const VkFrameOut loaded = run_vk(*engine_, o, g, Which::adaptive);
  EXPECT_EQ(loaded.colour, compiled.colour);
  EXPECT_EQ(loaded.counts, compiled.counts);
  // Refused: other options (another hook, another m), a truncated or foreign binary.
  auto other = o;
  other.hook.source += "\n// another hook\n";
  auto c = vk::AdaptiveSupersampler::create(engine_->context(), other);
  ASSERT_FALSE(c.ok());
  EXPECT_EQ(c.status().code, ErrorCode::invalid_argument);
  EXPECT_NE(c.status().message.find("shader_binary: made for other options"), std::string::npos)
      << c.status().message;
  other = o;
  other.m = 4;
  EXPECT_FALSE(vk::AdaptiveSupersampler::create(engine_->context(), other).ok());
  other = o;
  other.shader_binary.resize(other.shader_binary.size() / 2);
  c = vk::AdaptiveSupersampler::create(engine_->context(), other);
  ASSERT_FALSE(c.ok());
  EXPECT_EQ(c.status().code, ErrorCode::corrupt_data) << c.status().message;
  other.shader_binary = {'P', 'N', 'G', 0, 1, 2, 3, 4};
  c = vk::AdaptiveSupersampler::create(engine_->context(), other);
  ASSERT_FALSE(c.ok());
  EXPECT_NE(c.status().message.find("not a tessera shader binary"), std::string::npos);
  EXPECT_EQ(c.status().message.find('\n'), std::string::npos);
  vkDestroyPipelineCache(dev, cache, nullptr);
}

/// The offline path: a shader binary compiled without a device for two device kinds (this one,
/// and the same without shaderFloat64) loads on both and gives the runtime-compiled images; one
/// made for this device alone is refused by the device without fp64.
TEST_F(VkFrames, ShaderBinaryCompiledWithoutADevice) {
  const SceneGBuffer g = scene_gbuffer(16, 12, 2);
  const auto o = scene_options<vk::AdaptiveSupersamplerOptions>(g);
  Result<vk::AdaptiveShaderTarget> here =
      vk::AdaptiveSupersampler::shader_target(engine_->context());
  ASSERT_TRUE(here.ok()) << here.status().message;
  ASSERT_TRUE(here->float64);
  vk::AdaptiveShaderTarget no_fp64 = *here;
  no_fp64.float64 = false;
  using Binary = Result<std::vector<std::uint8_t>>;
  const Binary both = vk::AdaptiveSupersampler::compile_shader_binary(o, {*here, no_fp64, *here});
  const Binary alone = vk::AdaptiveSupersampler::compile_shader_binary(o, {*here});
  ASSERT_TRUE(both.ok()) << both.status().message;
  ASSERT_TRUE(alone.ok()) << alone.status().message;
  EXPECT_GT(both->size(), alone->size() + alone->size() / 2);  // two entries (one per kind)
  const Binary none = vk::AdaptiveSupersampler::compile_shader_binary(o, {});
  ASSERT_FALSE(none.ok());
  EXPECT_EQ(none.status().code, ErrorCode::invalid_argument);
  auto bad_hook = o;
  bad_hook.hook.source += "\nvoid broken( {}\n";
  const Binary bad = vk::AdaptiveSupersampler::compile_shader_binary(bad_hook, {*here});
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.status().message.find("scene_hook:"), std::string::npos) << bad.status().message;

  auto loaded = o;
  loaded.shader_binary = *both;
  const VkFrameOut compiled = run_vk(*engine_, o, g, Which::adaptive);
  const VkFrameOut from_both = run_vk(*engine_, loaded, g, Which::adaptive);
  EXPECT_EQ(from_both.colour, compiled.colour);
  EXPECT_EQ(from_both.counts, compiled.counts);

  TearDown();
  EngineOptions eo;
  eo.float64 = false;
  make_engine(eo);
  Result<vk::AdaptiveShaderTarget> small =
      vk::AdaptiveSupersampler::shader_target(engine_->context());
  ASSERT_TRUE(small.ok());
  EXPECT_FALSE(small->float64);
  const VkFrameOut compiled_float = run_vk(*engine_, o, g, Which::adaptive);
  const VkFrameOut loaded_float = run_vk(*engine_, loaded, g, Which::adaptive);
  EXPECT_EQ(loaded_float.colour, compiled_float.colour);
  EXPECT_EQ(loaded_float.counts, compiled_float.counts);
  auto wrong = o;
  wrong.shader_binary = *alone;
  auto c = vk::AdaptiveSupersampler::create(engine_->context(), wrong);
  ASSERT_FALSE(c.ok());
  EXPECT_EQ(c.status().code, ErrorCode::invalid_argument);
  EXPECT_NE(c.status().message.find("shader_binary: made for other options"), std::string::npos)
      << c.status().message;
}

}  // namespace
}  // namespace tessera::vk_test
