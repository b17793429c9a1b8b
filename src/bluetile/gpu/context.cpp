#include "bluetile/gpu/context.h"

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <thread>

#include "bluetile/core/error.h"
#include "bluetile/gpu/raster_layout.h"
#include "bluetile/core/process_limits.h"
#include "bluetile/core/text.h"

namespace bluetile::gpu {
namespace {

std::atomic<std::size_t> validation_errors{0};

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

VKAPI_ATTR VkBool32 VKAPI_CALL on_validation_message(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                     VkDebugUtilsMessageTypeFlagsEXT,
                                                     const VkDebugUtilsMessengerCallbackDataEXT* data, void*) {
  if (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) {
    ++validation_errors;
    std::fprintf(stderr, "bluetile: vulkan validation error: %s\n", data->pMessage);
  }
  return VK_FALSE;
}

bool validation_wanted() {
  const char* env = std::getenv("BLUETILE_VALIDATION");
  return env && std::strcmp(env, "0") != 0 && *env != '\0';
}

bool layer_available(const char* name) {
  std::uint32_t count = 0;
  if (vkEnumerateInstanceLayerProperties(&count, nullptr) != VK_SUCCESS) return false;
  std::vector<VkLayerProperties> layers(count);
  if (vkEnumerateInstanceLayerProperties(&count, layers.data()) != VK_SUCCESS) return false;
  return std::any_of(layers.begin(), layers.end(), [&](const VkLayerProperties& l) { return std::strcmp(l.layerName, name) == 0; });
}

VkInstance create_instance(bool validation) {
  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "bluetile";
  app.applicationVersion = VK_MAKE_VERSION(0, 1, 0);
  app.pEngineName = "bluetile";
  app.apiVersion = VK_API_VERSION_1_2;
  const char* layers[] = {kValidationLayer};
  const char* extensions[] = {VK_EXT_DEBUG_UTILS_EXTENSION_NAME};
  VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  info.pApplicationInfo = &app;
  if (validation) {
    info.enabledLayerCount = 1;
    info.ppEnabledLayerNames = layers;
    info.enabledExtensionCount = 1;
    info.ppEnabledExtensionNames = extensions;
  }
  VkInstance instance = VK_NULL_HANDLE;
  VkResult result = vkCreateInstance(&info, nullptr, &instance);
  if (result == VK_ERROR_INCOMPATIBLE_DRIVER || result == VK_ERROR_INITIALIZATION_FAILED) {
    throw Error(std::string("no Vulkan driver found (") + vk_result_name(result) +
                "); install one, for example Mesa's lavapipe (Debian: mesa-vulkan-drivers)");
  }
  if (result == VK_ERROR_OUT_OF_HOST_MEMORY) {
    // The loader answers a malformed driver manifest this way too; a real lack of memory this
    // early is unlikely, so name the manifests rather than blame --resolution.
    std::string manifests;
    for (const char* variable : {"VK_DRIVER_FILES", "VK_ICD_FILENAMES"})
      if (const char* value = std::getenv(variable)) manifests += std::string(variable) + "=" + value + " ";
    throw Error("cannot create a Vulkan instance (VK_ERROR_OUT_OF_HOST_MEMORY), which the Vulkan loader also "
                "reports for a malformed driver manifest: check " +
                (manifests.empty() ? std::string("/usr/share/vulkan/icd.d/*.json") : manifests.substr(0, manifests.size() - 1)));
  }
  BLUETILE_VK_CHECK(result);
  return instance;
}

std::string type_name(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return "cpu";
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return "integrated-gpu";
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return "discrete-gpu";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return "virtual-gpu";
    default: return "other";
  }
}

std::optional<std::uint32_t> graphics_compute_family(VkPhysicalDevice device) {
  std::uint32_t count = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(device, &count, nullptr);
  std::vector<VkQueueFamilyProperties> families(count);
  vkGetPhysicalDeviceQueueFamilyProperties(device, &count, families.data());
  for (std::uint32_t i = 0; i < count; ++i) {
    VkQueueFlags need = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
    if ((families[i].queueFlags & need) == need) return i;
  }
  return std::nullopt;
}

DeviceInfo describe(VkPhysicalDevice device, std::size_t index) {
  DeviceInfo info;
  info.index = index;
  VkPhysicalDeviceDriverProperties driver{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
  VkPhysicalDeviceProperties2 properties{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
  VkPhysicalDeviceProperties basic;
  vkGetPhysicalDeviceProperties(device, &basic);
  if (basic.apiVersion >= VK_API_VERSION_1_2) properties.pNext = &driver;
  vkGetPhysicalDeviceProperties2(device, &properties);
  const auto& p = properties.properties;
  info.name = p.deviceName;
  info.type = type_name(p.deviceType);
  info.api_version = std::to_string(VK_API_VERSION_MAJOR(p.apiVersion)) + "." +
                     std::to_string(VK_API_VERSION_MINOR(p.apiVersion)) + "." +
                     std::to_string(VK_API_VERSION_PATCH(p.apiVersion));
  info.driver = basic.apiVersion >= VK_API_VERSION_1_2
                    ? std::string(driver.driverName) + " (" + driver.driverInfo + ")"
                    : "unknown";

  std::vector<std::string> missing;
  if (p.apiVersion < VK_API_VERSION_1_2) missing.push_back("Vulkan 1.2");
  VkPhysicalDeviceVulkan12Features f12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
  VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
  if (p.apiVersion >= VK_API_VERSION_1_2) features.pNext = &f12;
  vkGetPhysicalDeviceFeatures2(device, &features);
  if (!features.features.shaderInt64) missing.push_back("shaderInt64");
  if (!features.features.shaderClipDistance) missing.push_back("shaderClipDistance");
  if (!f12.shaderBufferInt64Atomics) missing.push_back("shaderBufferInt64Atomics");
  if (!graphics_compute_family(device)) missing.push_back("a graphics+compute queue");
  VkFormatProperties format;
  vkGetPhysicalDeviceFormatProperties(device, VK_FORMAT_R32_UINT, &format);
  if (!(format.optimalTilingFeatures & VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT)) missing.push_back("R32_UINT attachments");
  if (!(format.optimalTilingFeatures & VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT)) missing.push_back("R32_UINT storage images");
  vkGetPhysicalDeviceFormatProperties(device, VK_FORMAT_D32_SFLOAT, &format);
  if (!(format.optimalTilingFeatures & VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT)) missing.push_back("D32_SFLOAT depth");
  info.float64 = features.features.shaderFloat64 == VK_TRUE;
  info.large_points = features.features.largePoints == VK_TRUE;
  info.suitable = missing.empty();
  for (std::size_t i = 0; i < missing.size(); ++i) info.missing += (i ? ", " : "") + missing[i];
  return info;
}

std::vector<VkPhysicalDevice> physical_devices(VkInstance instance) {
  std::uint32_t count = 0;
  BLUETILE_VK_CHECK(vkEnumeratePhysicalDevices(instance, &count, nullptr));
  std::vector<VkPhysicalDevice> devices(count);
  BLUETILE_VK_CHECK(vkEnumeratePhysicalDevices(instance, &count, devices.data()));
  devices.resize(count);
  return devices;
}

std::size_t pick_device(const std::vector<DeviceInfo>& infos, const std::string& wanted) {
  if (infos.empty()) {
    throw Error("the Vulkan loader found no device; install a driver, for example Mesa's lavapipe (Debian: mesa-vulkan-drivers)");
  }
  auto check = [&](std::size_t i) {
    if (!infos[i].suitable)
      throw Error("Vulkan device " + std::to_string(i) + " '" + infos[i].name + "' lacks " + infos[i].missing);
    return i;
  };
  if (wanted.empty()) {
    for (std::size_t i = 0; i < infos.size(); ++i)
      if (infos[i].suitable && infos[i].type == "cpu") return i;
    for (std::size_t i = 0; i < infos.size(); ++i)
      if (infos[i].suitable) return i;
    return check(0);
  }
  if (std::all_of(wanted.begin(), wanted.end(), [](char c) { return std::isdigit(static_cast<unsigned char>(c)); })) {
    std::size_t i = std::stoul(wanted);
    if (i >= infos.size())
      throw Error("device " + wanted + ": there are only " + std::to_string(infos.size()) + " Vulkan devices (see 'bluetile devices')");
    return check(i);
  }
  for (std::size_t i = 0; i < infos.size(); ++i)
    if (lower_case(infos[i].name).find(lower_case(wanted)) != std::string::npos) return check(i);
  throw Error("device '" + wanted + "': no Vulkan device has that name (see 'bluetile devices')");
}

}  // namespace

const char* vk_result_name(VkResult result) {
  switch (result) {
#define BLUETILE_NAME(r) case r: return #r;
    BLUETILE_NAME(VK_SUCCESS)
    BLUETILE_NAME(VK_NOT_READY)
    BLUETILE_NAME(VK_TIMEOUT)
    BLUETILE_NAME(VK_INCOMPLETE)
    BLUETILE_NAME(VK_ERROR_OUT_OF_HOST_MEMORY)
    BLUETILE_NAME(VK_ERROR_OUT_OF_DEVICE_MEMORY)
    BLUETILE_NAME(VK_ERROR_INITIALIZATION_FAILED)
    BLUETILE_NAME(VK_ERROR_DEVICE_LOST)
    BLUETILE_NAME(VK_ERROR_MEMORY_MAP_FAILED)
    BLUETILE_NAME(VK_ERROR_LAYER_NOT_PRESENT)
    BLUETILE_NAME(VK_ERROR_EXTENSION_NOT_PRESENT)
    BLUETILE_NAME(VK_ERROR_FEATURE_NOT_PRESENT)
    BLUETILE_NAME(VK_ERROR_INCOMPATIBLE_DRIVER)
    BLUETILE_NAME(VK_ERROR_TOO_MANY_OBJECTS)
    BLUETILE_NAME(VK_ERROR_FORMAT_NOT_SUPPORTED)
    BLUETILE_NAME(VK_ERROR_FRAGMENTED_POOL)
    BLUETILE_NAME(VK_ERROR_UNKNOWN)
    BLUETILE_NAME(VK_ERROR_OUT_OF_POOL_MEMORY)
#undef BLUETILE_NAME
    default: return "VK_RESULT_UNKNOWN";
  }
}

void throw_vk_error(const char* call, const char* file, int line, VkResult result) {
  std::string what = std::string("Vulkan call ") + call + " failed with " + vk_result_name(result) + " at " + file + ":" +
                     std::to_string(line);
  if (result == VK_ERROR_OUT_OF_DEVICE_MEMORY || result == VK_ERROR_OUT_OF_HOST_MEMORY)
    what += " (out of memory: try a smaller resolution or fewer sets)";
  if (result == VK_ERROR_DEVICE_LOST) what += " (the device was lost)";
  throw Error(what);
}

std::size_t validation_error_count() { return validation_errors.load(); }

std::vector<DeviceInfo> list_devices() {
  std::vector<DeviceInfo> infos;
  try {
    VkInstance instance = create_instance(false);
    try {
      auto devices = physical_devices(instance);
      for (std::size_t i = 0; i < devices.size(); ++i) infos.push_back(describe(devices[i], i));
    } catch (...) {
      vkDestroyInstance(instance, nullptr);
      throw;
    }
    vkDestroyInstance(instance, nullptr);
  } catch (const Error& e) {
    // Listing loads the driver but makes no device, so it fits limits that Context refuses up
    // front; under a tighter one the loader fails in ways that name no memory (no driver, a
    // failed enumeration): say which limit is the likelier cause.
    const std::optional<ProcessLimit> limit = address_space_limit();
    if (!limit || limit->left() >= driver_address_space_needed()) throw;
    throw Error("the Vulkan driver did not load under the limit (ulimit -v " + std::to_string(limit->limit >> 10) +
                "), which leaves " + std::to_string(limit->left() >> 20) + " MiB of address space, less than it may need (about " +
                std::to_string(driver_address_space_needed() >> 20) + " MiB): raise the limit (" + e.what() + ")");
  }
  return infos;
}

std::size_t driver_address_space_needed() {
  std::size_t threads = std::max(1u, std::thread::hardware_concurrency());
  if (const char* env = std::getenv("LP_NUM_THREADS")) {
    char* end = nullptr;
    unsigned long n = std::strtoul(env, &end, 10);
    if (end != env && *end == '\0') threads = std::max<std::size_t>(1, n);
  }
  constexpr std::size_t kMiB = std::size_t{1} << 20;
  return (512 + 144 * std::min<std::size_t>(threads, 6) + 12 * (threads > 6 ? threads - 6 : 0)) * kMiB;
}

void check_address_space(std::size_t bytes, const std::string& what) {
  const std::optional<ProcessLimit> limit = address_space_limit();
  if (!limit || limit->left() >= bytes) return;
  auto mib = [](std::uint64_t b) { return std::to_string((b + (1u << 20) - 1) >> 20); };
  throw Error(what + " needs about " + mib(bytes) + " MiB of address space but the limit (ulimit -v " +
              std::to_string(limit->limit >> 10) + ") leaves " + mib(limit->left()) +
              " MiB; raise the limit or use the exact engine");
}

Context::Context(const std::string& wanted_device) {
  check_address_space(driver_address_space_needed(), "the Vulkan driver");
  bool validation = validation_wanted();
  if (validation && !layer_available(kValidationLayer)) {
    std::fprintf(stderr, "bluetile: warning: BLUETILE_VALIDATION is set but %s is not installed\n", kValidationLayer);
    validation = false;
  }
  instance_ = create_instance(validation);
  try {
    if (validation) {
      auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
          vkGetInstanceProcAddr(instance_, "vkCreateDebugUtilsMessengerEXT"));
      VkDebugUtilsMessengerCreateInfoEXT info{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
      info.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT;
      info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT;
      info.pfnUserCallback = on_validation_message;
      if (create) BLUETILE_VK_CHECK(create(instance_, &info, nullptr, &messenger_));
    }

    auto devices = physical_devices(instance_);
    std::vector<DeviceInfo> infos;
    for (std::size_t i = 0; i < devices.size(); ++i) infos.push_back(describe(devices[i], i));
    std::size_t chosen = pick_device(infos, wanted_device);
    physical_ = devices[chosen];
    info_ = infos[chosen];
    vkGetPhysicalDeviceProperties(physical_, &properties_);
    vkGetPhysicalDeviceMemoryProperties(physical_, &memory_properties_);
    VkDeviceSize biggest_heap = 0;
    for (std::uint32_t i = 0; i < memory_properties_.memoryHeapCount; ++i)
      biggest_heap = std::max(biggest_heap, memory_properties_.memoryHeaps[i].size);
    memory_budget_ = biggest_heap / 2;
    queue_family_ = *graphics_compute_family(physical_);

    float priority = 1.0f;
    VkDeviceQueueCreateInfo queue_info{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    queue_info.queueFamilyIndex = queue_family_;
    queue_info.queueCount = 1;
    queue_info.pQueuePriorities = &priority;
    VkPhysicalDeviceVulkan12Features f12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
    f12.shaderBufferInt64Atomics = VK_TRUE;
    VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    features.pNext = &f12;
    features.features.shaderInt64 = VK_TRUE;
    features.features.shaderFloat64 = info_.float64 ? VK_TRUE : VK_FALSE;
    features.features.largePoints = info_.large_points ? VK_TRUE : VK_FALSE;
    features.features.shaderClipDistance = VK_TRUE;
    VkDeviceCreateInfo device_info{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
    device_info.pNext = &features;
    device_info.queueCreateInfoCount = 1;
    device_info.pQueueCreateInfos = &queue_info;
    BLUETILE_VK_CHECK(vkCreateDevice(physical_, &device_info, nullptr, &device_));
    vkGetDeviceQueue(device_, queue_family_, 0, &queue_);

    VkCommandPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pool_info.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    pool_info.queueFamilyIndex = queue_family_;
    BLUETILE_VK_CHECK(vkCreateCommandPool(device_, &pool_info, nullptr, &pool_));
    VkFenceCreateInfo fence_info{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    BLUETILE_VK_CHECK(vkCreateFence(device_, &fence_info, nullptr, &fence_));
  } catch (...) {
    release();
    throw;
  }
}

Context::~Context() { release(); }

void Context::release() {
  if (device_) {
    vkDeviceWaitIdle(device_);
    if (fence_) vkDestroyFence(device_, fence_, nullptr);
    if (pool_) vkDestroyCommandPool(device_, pool_, nullptr);
    vkDestroyDevice(device_, nullptr);
    device_ = VK_NULL_HANDLE;
  }
  if (messenger_) {
    auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
    if (destroy) destroy(instance_, messenger_, nullptr);
    messenger_ = VK_NULL_HANDLE;
  }
  if (instance_) vkDestroyInstance(instance_, nullptr);
  instance_ = VK_NULL_HANDLE;
}

std::uint32_t Context::memory_type(std::uint32_t allowed, VkMemoryPropertyFlags required,
                                   VkMemoryPropertyFlags preferred) const {
  std::uint32_t fallback = UINT32_MAX;
  for (std::uint32_t i = 0; i < memory_properties_.memoryTypeCount; ++i) {
    if (!(allowed & (1u << i))) continue;
    const VkMemoryPropertyFlags flags = memory_properties_.memoryTypes[i].propertyFlags;
    if ((flags & required) != required) continue;
    if ((flags & preferred) == preferred) return i;
    if (fallback == UINT32_MAX) fallback = i;
  }
  if (fallback != UINT32_MAX) return fallback;
  throw Error("the Vulkan device '" + info_.name + "' has no memory type with the needed properties");
}

VkDeviceMemory Context::allocate(const VkMemoryRequirements& requirements, VkMemoryPropertyFlags required,
                                 VkMemoryPropertyFlags preferred, bool& host_visible) {
  VkMemoryAllocateInfo info{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  info.allocationSize = requirements.size;
  info.memoryTypeIndex = memory_type(requirements.memoryTypeBits, required, preferred);
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkResult result = vkAllocateMemory(device_, &info, nullptr, &memory);
  const VkMemoryPropertyFlags flags = memory_properties_.memoryTypes[info.memoryTypeIndex].propertyFlags;
  if (result == VK_ERROR_OUT_OF_DEVICE_MEMORY && (flags & preferred) == preferred && preferred != required) {
    // The preferred type may sit in a small heap (host-visible device memory without
    // resizable BAR is 256 MiB): retry without the preference.
    info.memoryTypeIndex = memory_type(requirements.memoryTypeBits, required, required);
    result = vkAllocateMemory(device_, &info, nullptr, &memory);
  }
  BLUETILE_VK_CHECK(result);
  const VkMemoryPropertyFlags coherent = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
  host_visible = (memory_properties_.memoryTypes[info.memoryTypeIndex].propertyFlags & coherent) == coherent;
  return memory;
}

Buffer Context::create_buffer(VkDeviceSize size, VkBufferUsageFlags usage, MemoryUse use) {
  size = std::max<VkDeviceSize>(size, 16);
  if ((usage & VK_BUFFER_USAGE_STORAGE_BUFFER_BIT) && size > properties_.limits.maxStorageBufferRange)
    throw Error("a buffer of " + std::to_string(size >> 20) + " MiB exceeds the device's maxStorageBufferRange of " +
                std::to_string(properties_.limits.maxStorageBufferRange >> 20) + " MiB (" + info_.name +
                "); use a smaller resolution or fewer sets");
  Buffer b;
  b.size = size;
  VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  info.size = size;
  info.usage = usage;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  BLUETILE_VK_CHECK(vkCreateBuffer(device_, &info, nullptr, &b.buffer));
  try {
    VkMemoryRequirements requirements;
    vkGetBufferMemoryRequirements(device_, b.buffer, &requirements);
    const VkMemoryPropertyFlags coherent = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
    bool host_visible = false;
    if (use == MemoryUse::device) {
      b.memory = allocate(requirements, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT | coherent,
                          host_visible);
    } else {
      b.memory = allocate(requirements, coherent, coherent | VK_MEMORY_PROPERTY_HOST_CACHED_BIT, host_visible);
    }
    BLUETILE_VK_CHECK(vkBindBufferMemory(device_, b.buffer, b.memory, 0));
    if (host_visible) BLUETILE_VK_CHECK(vkMapMemory(device_, b.memory, 0, VK_WHOLE_SIZE, 0, &b.mapped));
  } catch (...) {
    destroy(b);
    throw;
  }
  return b;
}

void Context::destroy(Buffer& b) {
  if (b.buffer) vkDestroyBuffer(device_, b.buffer, nullptr);
  if (b.memory) vkFreeMemory(device_, b.memory, nullptr);  // unmaps too
  b = Buffer{};
}

Image Context::create_image(std::uint32_t width, std::uint32_t height, VkFormat format, VkImageUsageFlags usage,
                            VkImageAspectFlags aspect) {
  Image image;
  image.width = width;
  image.height = height;
  VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  info.imageType = VK_IMAGE_TYPE_2D;
  info.format = format;
  info.extent = {width, height, 1};
  info.mipLevels = 1;
  info.arrayLayers = 1;
  info.samples = VK_SAMPLE_COUNT_1_BIT;
  info.tiling = VK_IMAGE_TILING_OPTIMAL;
  info.usage = usage;
  info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  BLUETILE_VK_CHECK(vkCreateImage(device_, &info, nullptr, &image.image));
  try {
    VkMemoryRequirements requirements;
    vkGetImageMemoryRequirements(device_, image.image, &requirements);
    bool host_visible = false;
    image.memory = allocate(requirements, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, host_visible);
    BLUETILE_VK_CHECK(vkBindImageMemory(device_, image.image, image.memory, 0));
    VkImageViewCreateInfo view{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    view.image = image.image;
    view.viewType = VK_IMAGE_VIEW_TYPE_2D;
    view.format = format;
    view.subresourceRange = {aspect, 0, 1, 0, 1};
    BLUETILE_VK_CHECK(vkCreateImageView(device_, &view, nullptr, &image.view));
  } catch (...) {
    destroy(image);
    throw;
  }
  return image;
}

void Context::destroy(Image& image) {
  if (image.view) vkDestroyImageView(device_, image.view, nullptr);
  if (image.image) vkDestroyImage(device_, image.image, nullptr);
  if (image.memory) vkFreeMemory(device_, image.memory, nullptr);
  image = Image{};
}

VkShaderModule Context::create_shader(std::span<const std::uint32_t> spirv) {
  VkShaderModuleCreateInfo info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
  info.codeSize = spirv.size_bytes();
  info.pCode = spirv.data();
  VkShaderModule module = VK_NULL_HANDLE;
  BLUETILE_VK_CHECK(vkCreateShaderModule(device_, &info, nullptr, &module));
  return module;
}

void Context::submit_and_wait(VkCommandBuffer commands) {
  VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &commands;
  BLUETILE_VK_CHECK(vkResetFences(device_, 1, &fence_));
  BLUETILE_VK_CHECK(vkQueueSubmit(queue_, 1, &submit, fence_));
  BLUETILE_VK_CHECK(vkWaitForFences(device_, 1, &fence_, VK_TRUE, UINT64_MAX));
}

}  // namespace bluetile::gpu
