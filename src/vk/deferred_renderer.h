// Internal to src/vk: the Vulkan twin of gl::DeferredRenderer (tessera/gl_deferred.h), the
// renderer behind the AA experiment's Vulkan backend (aa_backend.cpp), on a HeadlessDevice of
// tessera's own. Built from a scene::Scene exactly as the GL one (deferred/gpu_host.h: the CPU
// texture chains as RGBA32F arrays, the material, light and wave buffers, clip positions
// computed on the CPU), it
//  * rasterises the enlarged G-buffer ((m*w) x (m*h), three RGBA32F colour targets + D32 depth)
//    with the shipped deferred_gbuffer.vert/.frag compiled with VULKAN (clip z remapped to
//    Vulkan's [0, w] on the CPU; y as the shaders' comments say: row 0 = the top grid row);
//  * shades it with vk::AdaptiveSupersampler (adaptive, reference, 1 spp at m >= 2) with
//    deferred_shading.glsl as its hook and the deferred resources in the engine-side descriptor
//    set 0, and with deferred_passes.comp (FXAA, the edge-per-sample baseline, m = 1) in the
//    same set (bindings: the comments of deferred_shading.glsl and deferred_passes.comp).
// Every submission waits for its fence; each deferred_passes.comp pass is its own submission
// (its wall time from submit to fence, its GPU time from two timestamps), the component's passes
// share one (their GPU times from its profile; the submission's wall time split between them
// by those).
// Files: deferred_renderer_scene.cpp (scene upload, size check), deferred_renderer_gbuffer.cpp
// (geometry pass), deferred_renderer_set.cpp (descriptor set, buffers, deferred_passes.comp),
// deferred_renderer_shade.cpp (the shading calls, the component).
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "adaptive/adaptive_host.h"
#include "deferred/gpu_host.h"
#include "tessera/experiments/aa_backend.h"
#include "tessera/vk_adaptive.h"
#include "vk/headless_device.h"

namespace tessera::vk {

class DeferredRenderer {
 public:
  /// Uploads the scene to `device` (which must outlive the renderer) and makes the geometry
  /// pass; one-line errors (too_large for more than 8 texture sizes, Vulkan failures).
  static Result<std::unique_ptr<DeferredRenderer>> create(HeadlessDevice& device,
                                                          const scene::Scene& scene);
  ~DeferredRenderer();
  DeferredRenderer(const DeferredRenderer&) = delete;
  DeferredRenderer& operator=(const DeferredRenderer&) = delete;

  /// As gl::DeferredRenderer::check_size, against maxImageDimension2D and
  /// maxFramebufferWidth/Height; allocates nothing.
  Status check_size(int width, int height, int m) const;
  /// The geometry pass (pass "gbuffer"); the G-buffer is reallocated when the size changes.
  Result<PassTime> render_gbuffer(const scene::Camera& camera, int width, int height, int m);

  Result<deferred::ShadeResult> shade_reference(const deferred::ShadingOptions& shading);
  Result<deferred::ShadeResult> shade_default(const deferred::ShadingOptions& shading);
  Result<deferred::ShadeResult> shade_adaptive(const deferred::ShadingOptions& shading,
                                               const AdaptiveThresholds& adaptive);
  Result<deferred::ShadeResult> shade_edge_per_sample(const deferred::ShadingOptions& shading,
                                                      const deferred::EdgePerSampleOptions& edge);
  /// 1 spp, sRGB8, FXAA 3.11 (passes "first", "srgb8", "fxaa"); the result in `image`.
  Result<deferred::FxaaResult> shade_default_fxaa(const deferred::ShadingOptions& shading,
                                                  const deferred::FxaaOptions& fxaa);

  struct State;

 private:
  DeferredRenderer() = default;
  std::unique_ptr<State> state_;
};

/// A sampled RGBA32F 2D array image with its mip chain (one texture-size class).
struct TextureArray {
  RawImage image;
  Memory memory;
  ImageView view;
};

struct DeferredMesh {
  Buffer dynamic, statics, indices;  // host-visible: clip xyzw + depth; normal + uv; uint32
  std::size_t vertices = 0, index_count = 0;
  int material = 0;
};

/// The storage buffers of deferred_passes.comp's SSBO 3..8 (bindings 8..13 of the set).
inline constexpr int kPassBuffers = 6;

struct DeferredRenderer::State {
  HeadlessDevice* device = nullptr;
  const Api* api = nullptr;
  const scene::Scene* scene = nullptr;
  std::vector<texture::Texture> cpu_textures;
  std::vector<TextureArray> arrays;  // >= 1 (a 1x1 dummy without textures)
  Sampler texture_sampler, gbuffer_sampler;
  Buffer materials;
  std::vector<DeferredMesh> meshes;
  std::vector<float> scratch;
  RenderPass render_pass;
  PipelineLayout gbuffer_layout;
  Pipeline gbuffer_pipeline;
  QueryPool queries;  // two timestamps per submission

  // The G-buffer of the last render_gbuffer and the layout its colour images are in.
  int w = 0, h = 0, m = 0;
  std::array<Image, 3> g;
  Image depth;
  Framebuffer framebuffer;
  VkImageLayout g_layout = VK_IMAGE_LAYOUT_UNDEFINED;
  deferred::GpuCamera camera;

  // The deferred descriptor set (deferred_shading.glsl's bindings, then deferred_passes.comp's).
  SetLayout set_layout;
  PipelineLayout passes_layout;
  DescriptorPool pool;
  VkDescriptorSet set = VK_NULL_HANDLE;
  bool set_written = false;
  Buffer params, lights, waves;           // host-visible, rewritten before each call
  std::array<Buffer, kPassBuffers> pass;  // S, terms, k, out, rgba8, rgba8 out
  Buffer readback;                        // host-visible, w*h*20 bytes
  int buffers_w = 0, buffers_h = 0;
  std::map<std::string, Pipeline> programs;  // deferred_passes.comp by preamble

  // vk::AdaptiveSupersampler for m >= 2, made again when (w, h, m) change.
  std::unique_ptr<AdaptiveSupersampler> component;
  std::array<int, 3> component_key{};
};

/// A device object made by `create` (an Api member such as &Api::CreateSampler) from `info`, in
/// its owner; vk_error "deferred VK: `what`: VK_ERROR_..." on failure.
template <class Owner, class Info, class Create>
Result<Owner> make_owned(const Api& api, Create create, const Info& info, const char* what) {
  decltype(Owner().get()) raw = VK_NULL_HANDLE;
  if (VkResult r = (api.*create)(api.device(), &info, api.alloc(), &raw); r != VK_SUCCESS) {
    return vk_error(std::string("deferred VK: ") + what, r);
  }
  return Owner(api, raw);
}

/// `owner` = the result of make_owned, or its error.
template <class Owner>
Status assign(Owner& owner, Result<Owner>&& made) {
  if (!made) return made.status();
  owner = std::move(*made);
  return Status::success();
}

// deferred_renderer_gbuffer.cpp
/// The geometry pass's pipeline layout (a fragment push constant) and pipeline (at create).
Status create_gbuffer_pipeline(DeferredRenderer::State& st);

// deferred_renderer_set.cpp
/// The descriptor set layout, pool and set, the pass pipeline layout (at create).
Status create_deferred_set(DeferredRenderer::State& st);
/// Writes the parameters, lights and waves; (re)allocates the per-pixel buffers and rewrites
/// the set when needed.
Status bind_deferred_inputs(DeferredRenderer::State& st, const deferred::ShadingOptions& shading,
                            const AdaptiveThresholds* adaptive,
                            const deferred::EdgePerSampleOptions* edge);
/// Records a barrier making the G-buffer readable by compute shaders (from `g_layout`).
void record_gbuffer_readable(DeferredRenderer::State& st, VkCommandBuffer cmd);
/// Everything earlier in submission order before everything in `cmd` (each submission opens
/// with it).
void record_full_barrier(const Api& api, VkCommandBuffer cmd);
/// Transfer writes visible to the host (closes every read-back).
void record_host_read_barrier(const Api& api, VkCommandBuffer cmd);
/// One deferred_passes.comp pass over w x h pixels in a submission of its own, timed.
Status run_deferred_pass(DeferredRenderer::State& st, const std::string& name,
                         const std::vector<std::string>& defines, std::vector<PassTime>& passes);
/// Copies `bytes` of pass buffer `index` (0 = S ... 5 = rgba8 out) to the host.
Status read_pass_buffer(DeferredRenderer::State& st, int index, std::size_t bytes, void* out);
/// Timestamp `query` (0: opens a submission's timed work, resetting the pool; 1: closes it);
/// nothing where the queue family has no timestamps.
void record_timestamp(DeferredRenderer::State& st, VkCommandBuffer cmd, std::uint32_t query);
/// Timestamps 0 to 1 of the last completed submission in milliseconds (NaN without them).
double timestamp_ms(const DeferredRenderer::State& st);

// deferred_renderer_shade.cpp
/// The component's image and, for `mode` adaptive, its sample counts (m >= 2).
Status shade_with_component(DeferredRenderer::State& st, adaptive::Mode mode,
                            const AdaptiveThresholds* adaptive, deferred::ShadeResult& out);

}  // namespace tessera::vk
