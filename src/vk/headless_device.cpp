// vk::HeadlessDevice (headless_device.h): the experiments' own Vulkan instance and device, made
// from the caller's loader or libvulkan.so.1 opened at run time.
#include "vk/headless_device.h"

#include <dlfcn.h>

#include <algorithm>
#include <charconv>
#include <cstdlib>
#include <cstring>

namespace tessera::vk {

namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

Status unsupported(const std::string& what) {
  return Status::error(ErrorCode::unsupported, "vulkan: " + what);
}

template <class Fn>
Fn global_fn(PFN_vkGetInstanceProcAddr gipa, const char* name) {
  return reinterpret_cast<Fn>(gipa(VK_NULL_HANDLE, name));
}

template <class Fn>
Fn instance_fn(PFN_vkGetInstanceProcAddr gipa, VkInstance instance, const char* name) {
  return reinterpret_cast<Fn>(gipa(instance, name));
}

bool has_layer(PFN_vkGetInstanceProcAddr gipa, const char* name) {
  auto enumerate =
      global_fn<PFN_vkEnumerateInstanceLayerProperties>(gipa, "vkEnumerateInstanceLayerProperties");
  if (enumerate == nullptr) return false;
  std::uint32_t n = 0;
  if (enumerate(&n, nullptr) != VK_SUCCESS) return false;
  std::vector<VkLayerProperties> layers(n);
  if (enumerate(&n, layers.data()) != VK_SUCCESS) return false;
  return std::any_of(layers.begin(), layers.end(), [&](const VkLayerProperties& l) {
    return std::strcmp(l.layerName, name) == 0;
  });
}

VKAPI_ATTR VkBool32 VKAPI_CALL on_message(VkDebugUtilsMessageSeverityFlagBitsEXT,
                                          VkDebugUtilsMessageTypeFlagsEXT,
                                          const VkDebugUtilsMessengerCallbackDataEXT* data,
                                          void* user) {
  auto* log = static_cast<ValidationLog*>(user);
  if (log->messages.fetch_add(1) == 0) {
    std::lock_guard<std::mutex> lock(log->mutex);
    log->first = data != nullptr && data->pMessage != nullptr ? data->pMessage : "?";
  }
  return VK_FALSE;
}

constexpr const char* kDepthClipControl = "VK_EXT_depth_clip_control";

/// Whether `pd` offers VK_EXT_depth_clip_control with its feature (OpenGL's [-w, w] clip depth,
/// for the AA backend's G-buffer pass: the same depth values as OpenGL, bit for bit).
bool has_depth_clip_control(PFN_vkGetInstanceProcAddr gipa, VkInstance instance,
                            VkPhysicalDevice pd) {
  auto extensions = instance_fn<PFN_vkEnumerateDeviceExtensionProperties>(
      gipa, instance, "vkEnumerateDeviceExtensionProperties");
  auto features2 =
      instance_fn<PFN_vkGetPhysicalDeviceFeatures2>(gipa, instance, "vkGetPhysicalDeviceFeatures2");
  if (extensions == nullptr || features2 == nullptr) return false;
  std::uint32_t n = 0;
  if (extensions(pd, nullptr, &n, nullptr) != VK_SUCCESS) return false;
  std::vector<VkExtensionProperties> ext(n);
  if (extensions(pd, nullptr, &n, ext.data()) != VK_SUCCESS) return false;
  if (std::none_of(ext.begin(), ext.end(), [](const VkExtensionProperties& e) {
        return std::strcmp(e.extensionName, kDepthClipControl) == 0;
      })) {
    return false;
  }
  VkPhysicalDeviceDepthClipControlFeaturesEXT dcc{};
  dcc.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DEPTH_CLIP_CONTROL_FEATURES_EXT;
  VkPhysicalDeviceFeatures2 f2{};
  f2.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2;
  f2.pNext = &dcc;
  features2(pd, &f2);
  return dcc.depthClipControl == VK_TRUE;
}

/// Which of the devices with a graphics + compute family to take: `index`, else
/// $TESSERA_VK_DEVICE (a decimal index), else 0; invalid_argument naming a bad value.
Result<int> wanted_device(int index) {
  if (index >= 0) return index;
  const char* env = std::getenv("TESSERA_VK_DEVICE");
  if (env == nullptr || *env == '\0') return 0;
  int value = 0;
  const char* end = env + std::strlen(env);
  const auto [ptr, ec] = std::from_chars(env, end, value);
  if (ec != std::errc() || ptr != end || value < 0) {
    return Status::error(ErrorCode::invalid_argument, std::string("vulkan: TESSERA_VK_DEVICE '") +
                                                          env +
                                                          "': expected a device index (0, 1, ...)");
  }
  return value;
}

}  // namespace

Result<std::unique_ptr<HeadlessDevice>> HeadlessDevice::create(const HeadlessDeviceOptions& options,
                                                               std::shared_ptr<ValidationLog> log) {
  std::unique_ptr<HeadlessDevice> d(new HeadlessDevice());
  PFN_vkGetInstanceProcAddr gipa = options.get_instance_proc_addr;
  if (gipa == nullptr) {
    d->loader_ = dlopen("libvulkan.so.1", RTLD_NOW | RTLD_LOCAL);
    if (d->loader_ == nullptr) {
      return unsupported("no Vulkan loader (libvulkan.so.1; Debian: libvulkan1)");
    }
    gipa = reinterpret_cast<PFN_vkGetInstanceProcAddr>(dlsym(d->loader_, "vkGetInstanceProcAddr"));
    if (gipa == nullptr) return unsupported("libvulkan.so.1 has no vkGetInstanceProcAddr");
  }
  DeviceContext& ctx = d->api_.ctx;
  ctx.get_instance_proc_addr = gipa;
  if (Status s = d->create_instance(options, std::move(log)); !s.ok()) return s;
  if (Status s = d->create_device(options); !s.ok()) return s;
  Result<Api> api = load_api(ctx);
  if (!api) return api.status();
  d->api_ = std::move(*api);
  VkCommandPoolCreateInfo pi{};
  pi.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO;
  pi.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  pi.queueFamilyIndex = ctx.queue_family;
  if (VkResult r = d->api_.CreateCommandPool(ctx.device, &pi, ctx.allocator, &d->pool_);
      r != VK_SUCCESS) {
    return vk_error("vulkan: vkCreateCommandPool", r);
  }
  VkFenceCreateInfo fi{};
  fi.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO;
  if (VkResult r = d->api_.CreateFence(ctx.device, &fi, ctx.allocator, &d->fence_);
      r != VK_SUCCESS) {
    return vk_error("vulkan: vkCreateFence", r);
  }
  return d;
}

Status HeadlessDevice::create_instance(const HeadlessDeviceOptions& options,
                                       std::shared_ptr<ValidationLog> log) {
  DeviceContext& ctx = api_.ctx;
  PFN_vkGetInstanceProcAddr gipa = ctx.get_instance_proc_addr;
  if (options.validation && !has_layer(gipa, kValidationLayer)) {
    return unsupported(
        "no VK_LAYER_KHRONOS_validation for the validation asked for (Debian: "
        "vulkan-validationlayers)");
  }
  auto create = global_fn<PFN_vkCreateInstance>(gipa, "vkCreateInstance");
  if (create == nullptr) return unsupported("the loader has no vkCreateInstance");
  std::uint32_t loader_version = VK_API_VERSION_1_0;
  if (auto version =
          global_fn<PFN_vkEnumerateInstanceVersion>(gipa, "vkEnumerateInstanceVersion")) {
    version(&loader_version);
  }
  VkApplicationInfo app{};
  app.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO;
  app.pApplicationName = "tessera experiments";
  app.pEngineName = "tessera";
  app.apiVersion = std::min<std::uint32_t>(loader_version, VK_API_VERSION_1_3);
  if (options.validation) log_ = log ? std::move(log) : std::make_shared<ValidationLog>();
  VkDebugUtilsMessengerCreateInfoEXT mi{};
  mi.sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT;
  mi.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                       VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  mi.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                   VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                   VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
  mi.pfnUserCallback = &on_message;
  mi.pUserData = log_.get();
  const VkValidationFeatureEnableEXT sync =
      VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT;
  VkValidationFeaturesEXT vf{};
  vf.sType = VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT;
  vf.pNext = &mi;
  vf.enabledValidationFeatureCount = 1;
  vf.pEnabledValidationFeatures = &sync;
  const char* extension = VK_EXT_DEBUG_UTILS_EXTENSION_NAME;
  VkInstanceCreateInfo ii{};
  ii.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO;
  ii.pApplicationInfo = &app;
  if (options.validation) {
    ii.pNext = &vf;
    ii.enabledLayerCount = 1;
    ii.ppEnabledLayerNames = &kValidationLayer;
    ii.enabledExtensionCount = 1;
    ii.ppEnabledExtensionNames = &extension;
  }
  if (VkResult r = create(&ii, nullptr, &ctx.instance); r != VK_SUCCESS) {
    ctx.instance = VK_NULL_HANDLE;
    return vk_error("vulkan: vkCreateInstance", r);
  }
  if (options.validation) {
    auto create_messenger = instance_fn<PFN_vkCreateDebugUtilsMessengerEXT>(
        gipa, ctx.instance, "vkCreateDebugUtilsMessengerEXT");
    if (create_messenger == nullptr ||
        create_messenger(ctx.instance, &mi, nullptr, &messenger_) != VK_SUCCESS) {
      return unsupported("no debug-utils messenger for the validation layer");
    }
  }
  return Status::success();
}

Status HeadlessDevice::create_device(const HeadlessDeviceOptions& options) {
  DeviceContext& ctx = api_.ctx;
  PFN_vkGetInstanceProcAddr gipa = ctx.get_instance_proc_addr;
  auto enumerate =
      instance_fn<PFN_vkEnumeratePhysicalDevices>(gipa, ctx.instance, "vkEnumeratePhysicalDevices");
  auto properties = instance_fn<PFN_vkGetPhysicalDeviceProperties>(gipa, ctx.instance,
                                                                   "vkGetPhysicalDeviceProperties");
  auto families = instance_fn<PFN_vkGetPhysicalDeviceQueueFamilyProperties>(
      gipa, ctx.instance, "vkGetPhysicalDeviceQueueFamilyProperties");
  auto features = instance_fn<PFN_vkGetPhysicalDeviceFeatures>(gipa, ctx.instance,
                                                               "vkGetPhysicalDeviceFeatures");
  auto create = instance_fn<PFN_vkCreateDevice>(gipa, ctx.instance, "vkCreateDevice");
  ctx.get_device_proc_addr =
      instance_fn<PFN_vkGetDeviceProcAddr>(gipa, ctx.instance, "vkGetDeviceProcAddr");
  if (!enumerate || !properties || !families || !features || !create || !ctx.get_device_proc_addr) {
    return unsupported("the loader lacks a Vulkan 1.0 instance entry point");
  }
  std::uint32_t n = 0;
  enumerate(ctx.instance, &n, nullptr);
  std::vector<VkPhysicalDevice> devices(n);
  enumerate(ctx.instance, &n, devices.data());
  devices.resize(n);
  int usable = 0;
  const Result<int> wanted = wanted_device(options.device_index);
  if (!wanted) return wanted.status();
  const int want = *wanted;
  for (VkPhysicalDevice pd : devices) {
    std::uint32_t nf = 0;
    families(pd, &nf, nullptr);
    std::vector<VkQueueFamilyProperties> fams(nf);
    families(pd, &nf, fams.data());
    const VkQueueFlags need = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
    for (std::uint32_t f = 0; f < nf; ++f) {
      if ((fams[f].queueFlags & need) != need) continue;
      if (usable++ == want) {
        ctx.physical_device = pd;
        ctx.queue_family = f;
      }
      break;
    }
  }
  if (ctx.physical_device == VK_NULL_HANDLE) {
    if (usable == 0) {
      return unsupported(
          "no Vulkan device with a graphics + compute queue (Debian: mesa-vulkan-drivers for "
          "lavapipe)");
    }
    return Status::error(ErrorCode::invalid_argument, "vulkan: device " + std::to_string(want) +
                                                          " asked for ($TESSERA_VK_DEVICE "
                                                          "or device_index), " +
                                                          std::to_string(usable) + " usable");
  }
  VkPhysicalDeviceProperties props{};
  properties(ctx.physical_device, &props);
  ctx.api_version = std::min<std::uint32_t>(props.apiVersion, VK_API_VERSION_1_3);
  features(ctx.physical_device, &ctx.enabled_features);
  ctx.enabled_features.robustBufferAccess = VK_FALSE;  // costs speed; nothing here needs it
  VkPhysicalDeviceVulkan13Features f13{};
  f13.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES;
  f13.synchronization2 = VK_TRUE;  // required by every Vulkan 1.3 device
  ctx.synchronization2 = ctx.api_version >= VK_API_VERSION_1_3;
  const float priority = 1.0f;
  VkDeviceQueueCreateInfo qi{};
  qi.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO;
  qi.queueFamilyIndex = ctx.queue_family;
  qi.queueCount = 1;
  qi.pQueuePriorities = &priority;
  VkDeviceCreateInfo di{};
  di.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO;
  di.pNext = ctx.synchronization2 ? &f13 : nullptr;
  VkPhysicalDeviceDepthClipControlFeaturesEXT dcc{};
  dcc.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DEPTH_CLIP_CONTROL_FEATURES_EXT;
  dcc.depthClipControl = VK_TRUE;
  depth_clip_control_ = ctx.api_version >= VK_API_VERSION_1_1 &&
                        has_depth_clip_control(gipa, ctx.instance, ctx.physical_device);
  if (depth_clip_control_) {
    dcc.pNext = ctx.synchronization2 ? &f13 : nullptr;
    di.pNext = &dcc;
    di.enabledExtensionCount = 1;
    di.ppEnabledExtensionNames = &kDepthClipControl;
  }
  di.queueCreateInfoCount = 1;
  di.pQueueCreateInfos = &qi;
  di.pEnabledFeatures = &ctx.enabled_features;
  if (VkResult r = create(ctx.physical_device, &di, nullptr, &ctx.device); r != VK_SUCCESS) {
    ctx.device = VK_NULL_HANDLE;
    return vk_error("vulkan: vkCreateDevice", r);
  }
  auto get_queue = reinterpret_cast<PFN_vkGetDeviceQueue>(
      ctx.get_device_proc_addr(ctx.device, "vkGetDeviceQueue"));
  if (get_queue == nullptr) return unsupported("the device has no vkGetDeviceQueue");
  get_queue(ctx.device, ctx.queue_family, 0, &ctx.queue);
  return Status::success();
}

void HeadlessDevice::destroy() {
  DeviceContext& ctx = api_.ctx;
  PFN_vkGetInstanceProcAddr gipa = ctx.get_instance_proc_addr;
  if (ctx.device != VK_NULL_HANDLE) {
    auto wait = reinterpret_cast<PFN_vkDeviceWaitIdle>(
        ctx.get_device_proc_addr(ctx.device, "vkDeviceWaitIdle"));
    if (wait) wait(ctx.device);
    if (fence_ != VK_NULL_HANDLE) api_.DestroyFence(ctx.device, fence_, ctx.allocator);
    if (pool_ != VK_NULL_HANDLE) api_.DestroyCommandPool(ctx.device, pool_, ctx.allocator);
    auto destroy_device = reinterpret_cast<PFN_vkDestroyDevice>(
        ctx.get_device_proc_addr(ctx.device, "vkDestroyDevice"));
    if (destroy_device) destroy_device(ctx.device, nullptr);
    ctx.device = VK_NULL_HANDLE;
  }
  if (ctx.instance != VK_NULL_HANDLE) {
    if (messenger_ != VK_NULL_HANDLE) {
      auto destroy_messenger = instance_fn<PFN_vkDestroyDebugUtilsMessengerEXT>(
          gipa, ctx.instance, "vkDestroyDebugUtilsMessengerEXT");
      if (destroy_messenger) destroy_messenger(ctx.instance, messenger_, nullptr);
    }
    auto destroy_instance =
        instance_fn<PFN_vkDestroyInstance>(gipa, ctx.instance, "vkDestroyInstance");
    if (destroy_instance) destroy_instance(ctx.instance, nullptr);
    ctx.instance = VK_NULL_HANDLE;
  }
  if (loader_ != nullptr) dlclose(loader_);
  loader_ = nullptr;
}

HeadlessDevice::~HeadlessDevice() { destroy(); }

std::string HeadlessDevice::device_name() const { return api_.properties.deviceName; }

std::string HeadlessDevice::device_version() const {
  const std::uint32_t v = api_.properties.apiVersion;
  return "Vulkan " + std::to_string(VK_API_VERSION_MAJOR(v)) + "." +
         std::to_string(VK_API_VERSION_MINOR(v)) + "." + std::to_string(VK_API_VERSION_PATCH(v)) +
         ", driver " + std::to_string(api_.properties.driverVersion);
}

double HeadlessDevice::timestamp_ms_per_tick() const {
  if (api_.queue_family.timestampValidBits == 0) return 0.0;
  return double(api_.properties.limits.timestampPeriod) * 1e-6;
}

Result<VkCommandBuffer> HeadlessDevice::begin() {
  VkCommandBufferAllocateInfo ai{};
  ai.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO;
  ai.commandPool = pool_;
  ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  ai.commandBufferCount = 1;
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  if (VkResult r = api_.AllocateCommandBuffers(api_.device(), &ai, &cmd); r != VK_SUCCESS) {
    return vk_error("vulkan: vkAllocateCommandBuffers", r);
  }
  VkCommandBufferBeginInfo bi{};
  bi.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  if (VkResult r = api_.BeginCommandBuffer(cmd, &bi); r != VK_SUCCESS) {
    api_.FreeCommandBuffers(api_.device(), pool_, 1, &cmd);
    return vk_error("vulkan: vkBeginCommandBuffer", r);
  }
  return cmd;
}

Status HeadlessDevice::submit_and_wait(VkCommandBuffer cmd) {
  Status status = Status::success();
  if (VkResult e = api_.EndCommandBuffer(cmd); e != VK_SUCCESS) {
    status = vk_error("vulkan: vkEndCommandBuffer", e);
  } else {
    VkSubmitInfo si{};
    si.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
    si.commandBufferCount = 1;
    si.pCommandBuffers = &cmd;
    if (VkResult r = api_.QueueSubmit(api_.ctx.queue, 1, &si, fence_); r != VK_SUCCESS) {
      status = vk_error("vulkan: vkQueueSubmit", r);
    } else {
      if (VkResult w = api_.WaitForFences(api_.device(), 1, &fence_, VK_TRUE, UINT64_MAX);
          w != VK_SUCCESS) {
        status = vk_error("vulkan: vkWaitForFences", w);
      }
      api_.ResetFences(api_.device(), 1, &fence_);
    }
  }
  api_.FreeCommandBuffers(api_.device(), pool_, 1, &cmd);
  return status;
}

}  // namespace tessera::vk
