// The Vulkan test engine's forward pass (vk_draw.h).
#include "vk_draw.h"

#include <shaderc/shaderc.h>

#include <cstring>
#include <memory>

#include "vk_pipelines.h"  // examples/common: the forward pipeline engine_ptex_vk draws with

namespace tessera::vk_test {

Result<std::vector<std::uint32_t>> compile_glsl(VkShaderStageFlagBits stage,
                                                const std::string& text, const std::string& name) {
  shaderc_compiler_t compiler = shaderc_compiler_initialize();
  shaderc_compile_options_t options = shaderc_compile_options_initialize();
  shaderc_compile_options_set_target_env(options, shaderc_target_env_vulkan,
                                         shaderc_env_version_vulkan_1_1);
  const shaderc_shader_kind kind =
      stage == VK_SHADER_STAGE_VERTEX_BIT ? shaderc_vertex_shader : shaderc_fragment_shader;
  shaderc_compilation_result_t result = shaderc_compile_into_spv(
      compiler, text.data(), text.size(), kind, name.c_str(), "main", options);
  Result<std::vector<std::uint32_t>> out =
      Status::error(ErrorCode::invalid_argument, name + ": no result");
  if (result != nullptr) {
    if (shaderc_result_get_compilation_status(result) == shaderc_compilation_status_success) {
      std::vector<std::uint32_t> spirv(shaderc_result_get_length(result) / 4);
      std::memcpy(spirv.data(), shaderc_result_get_bytes(result), spirv.size() * 4);
      out = std::move(spirv);
    } else {
      out = Status::error(ErrorCode::invalid_argument, shaderc_result_get_error_message(result));
    }
    shaderc_result_release(result);
  }
  shaderc_compile_options_release(options);
  shaderc_compiler_release(compiler);
  return out;
}

namespace {

// Everything one draw creates, destroyed (after the queue is idle) in reverse: the depth
// target and the forward pass's objects (examples/common/vk_pipelines.h).
struct DrawObjects {
  VkDevice device = VK_NULL_HANDLE;
  VkImage depth = VK_NULL_HANDLE;
  VkDeviceMemory depth_memory = VK_NULL_HANDLE;
  VkImageView depth_view = VK_NULL_HANDLE;
  engine::ForwardObjects forward;
  ~DrawObjects() {
    if (device == VK_NULL_HANDLE) return;
    vkDeviceWaitIdle(device);
    forward.destroy(device);
    vkDestroyImageView(device, depth_view, nullptr);
    vkDestroyImage(device, depth, nullptr);
    vkFreeMemory(device, depth_memory, nullptr);
  }
};

void create_targets(const Engine& engine, DrawObjects& o, const EngineImage& colour, int w, int h) {
  const VkDevice dev = engine.context().device;
  engine::create_image(dev, engine.context().physical_device, VK_FORMAT_D32_SFLOAT,
                       std::uint32_t(w), std::uint32_t(h),
                       VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, VK_IMAGE_ASPECT_DEPTH_BIT,
                       &o.depth, &o.depth_memory, &o.depth_view);
  // The colour target arrives in TRANSFER_DST after its upload (the background) and is kept
  // (LOAD); depth is cleared. Left in COLOR_ATTACHMENT_OPTIMAL for read_back's barrier.
  VkSubpassDependency dep{};
  dep.srcSubpass = VK_SUBPASS_EXTERNAL;
  dep.dstSubpass = 0;
  dep.srcStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT;
  dep.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
  dep.dstStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT |
                     VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT |
                     VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
  dep.dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT |
                      VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT |
                      VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
  const VkImageView views[2] = {colour.view, o.depth_view};
  o.forward.create_pass(dev, VK_ATTACHMENT_LOAD_OP_LOAD, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                        VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, {dep}, views, w, h);
}

Status create_pipeline(VkDevice dev, DrawObjects& o, const DrawInput& in) {
  engine::ForwardPipelineDesc desc = engine::ForwardPipelineDesc::of(in);
  desc.cull_back = in.cull_back;
  if (VkResult r = o.forward.create_pipeline(dev, desc); r != VK_SUCCESS) {
    return Status::error(ErrorCode::unsupported,
                         std::string("vkCreateGraphicsPipelines: ") + vk::result_name(r));
  }
  return Status::success();
}

}  // namespace

Result<std::vector<float>> draw(Engine& engine, const DrawInput& in) {
  if (in.component_set < 1 || in.component_layout == VK_NULL_HANDLE || !in.bind_component) {
    return Status::error(ErrorCode::invalid_argument, "draw: no component set (index >= 1)");
  }
  const VkDevice dev = engine.context().device;
  EngineImage colour =
      engine.upload_rgba(VK_FORMAT_R32G32B32A32_SFLOAT, in.width, in.height, in.background,
                         VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
  EngineBuffer vbo = engine.host_buffer(in.vertex_bytes, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
  std::memcpy(vbo.data, in.vertices, in.vertex_bytes);
  EngineBuffer ibo = engine.host_buffer(in.indices.size() * 4, VK_BUFFER_USAGE_INDEX_BUFFER_BIT);
  std::memcpy(ibo.data, in.indices.data(), in.indices.size() * 4);
  EngineBuffer ubo = engine.host_buffer(in.frame.size(), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
  std::memcpy(ubo.data, in.frame.data(), in.frame.size());
  Result<std::vector<float>> out = Status::error(ErrorCode::unsupported, "draw: not drawn");
  {
    DrawObjects o;
    o.device = dev;
    create_targets(engine, o, colour, in.width, in.height);
    // Set 0: the frame block; 1 .. component_set - 1: empty; component_set: the component's.
    std::vector<VkDescriptorSetLayout> extra(in.component_set, VK_NULL_HANDLE);
    extra.back() = in.component_layout;
    o.forward.create_sets(dev, extra, ubo.buffer);
    if (Status s = create_pipeline(dev, o, in); !s.ok()) {
      out = s;
    } else {
      VkCommandBuffer cmd = engine.begin();
      VkClearValue clear[2]{};  // the colour is loaded (the background), depth cleared
      clear[1].depthStencil = {1.0f, 0};
      Status bound = in.before_pass ? in.before_pass(cmd) : Status::success();
      if (bound.ok()) {
        bound = o.forward.record(cmd, in.width, in.height, clear, vbo.buffer, ibo.buffer,
                                 std::uint32_t(in.indices.size()), in.bind_component);
      }
      engine.submit_and_wait(cmd);
      if (!bound.ok()) {
        out = bound;
      } else {
        vk::ImageResource r = colour.resource;
        r.layout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
        r.stage = VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT;
        r.access = VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT;
        out = engine.read_back(r);
      }
    }
  }
  engine.destroy(ubo);
  engine.destroy(ibo);
  engine.destroy(vbo);
  engine.destroy(colour);
  return out;
}

}  // namespace tessera::vk_test
