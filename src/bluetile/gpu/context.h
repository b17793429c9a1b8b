// The Vulkan context: instance, one physical device, one logical device with one queue that
// does graphics and compute, a command pool, and small create/destroy helpers for buffers,
// images and shader modules. Headless (no surface). Everything here throws bluetile::Error
// with a readable reason on failure: no driver, no suitable device, out of memory, device lost.
//
// The CPU device (lavapipe) is preferred by default so that results are the same on every
// machine; another device is picked by name (substring, case-insensitive) or index.
// BLUETILE_VALIDATION=1 in the environment turns the Khronos validation layer on; its errors
// are printed on stderr and counted (validation_error_count()), which the tests check.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

namespace bluetile::gpu {

// Throws Error naming the call, file:line and the VkResult when `call` does not return VK_SUCCESS.
#define BLUETILE_VK_CHECK(call)                                                   \
  do {                                                                            \
    VkResult bluetile_vk_result_ = (call);                                        \
    if (bluetile_vk_result_ != VK_SUCCESS)                                        \
      ::bluetile::gpu::throw_vk_error(#call, __FILE__, __LINE__, bluetile_vk_result_); \
  } while (false)

[[noreturn]] void throw_vk_error(const char* call, const char* file, int line, VkResult result);
const char* vk_result_name(VkResult result);

struct DeviceInfo {
  std::size_t index = 0;
  std::string name;
  std::string type;    // "cpu", "integrated-gpu", "discrete-gpu", "virtual-gpu", "other"
  std::string driver;  // driver name and info, e.g. "llvmpipe (Mesa 22.3.6)"
  std::string api_version;
  bool suitable = false;    // has what the raster engine needs
  std::string missing;      // what it lacks when not suitable
  bool float64 = false;     // shaderFloat64: the exact boundary split runs in double precision
  bool large_points = false;  // largePoints: point primitives wider than one pixel
};

// Every Vulkan device the loader sees. Throws Error when there is no Vulkan at all.
std::vector<DeviceInfo> list_devices();

// Validation-layer errors reported so far in this process (0 when the layer is off).
std::size_t validation_error_count();

// Address space the Vulkan driver needs to start, in bytes: fitted to lavapipe's measured
// peak (Mesa 22.3: 635 MiB with one rasterizer thread, 740 with 2, 1090 with 4, 1480 with 16;
// glibc gives each driver thread its own 64 MiB malloc arena). Under a smaller `ulimit -v` the
// driver crashes inside vkCreateDevice or its threads, so Context checks this first.
std::size_t driver_address_space_needed();

// Throws Error when the process's address-space limit (ulimit -v) leaves less than `bytes`
// beyond what it already uses, saying what `what` needs and what the limit allows.
void check_address_space(std::size_t bytes, const std::string& what);

// Where a buffer lives. Memory types are picked by their properties, never assumed: on a
// device with one memory type for everything (lavapipe, most integrated GPUs) every buffer is
// mapped; on a discrete GPU `device` buffers are not, and data reach them through `staging`
// buffers and copies in the command buffer.
enum class MemoryUse {
  device,   // device-local; mapped too when the device-local memory is host-visible
  staging,  // host-visible and coherent, for uploads and readbacks
};

struct Buffer {
  VkBuffer buffer = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkDeviceSize size = 0;
  void* mapped = nullptr;  // persistently mapped when the memory is host-visible (and coherent)
};

struct Image {
  VkImage image = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkImageView view = VK_NULL_HANDLE;
  std::uint32_t width = 0, height = 0;
};

class Context {
 public:
  // `device`: empty for the default (the CPU device if any, else the first suitable one),
  // a decimal index into list_devices(), or a name substring.
  explicit Context(const std::string& device = "");
  ~Context();
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  VkDevice device() const { return device_; }
  VkPhysicalDevice physical_device() const { return physical_; }
  VkQueue queue() const { return queue_; }
  VkCommandPool command_pool() const { return pool_; }
  const VkPhysicalDeviceProperties& properties() const { return properties_; }
  const DeviceInfo& info() const { return info_; }
  // Largest total size of images and buffers we allow ourselves (half the biggest heap).
  VkDeviceSize memory_budget() const { return memory_budget_; }
  // Whether shaders may use 64-bit floats (enabled when the device has shaderFloat64).
  bool float64() const { return info_.float64; }
  // Largest point primitive side in pixels (1 without largePoints, which is enabled where present).
  float max_point_size() const { return info_.large_points ? properties_.limits.pointSizeRange[1] : 1.0f; }

  // A buffer of `size` bytes (at least 1), mapped for its whole life when its memory is
  // host-visible. Throws Error naming the limit when `size` exceeds the device's storage
  // buffer range and the buffer is a storage buffer.
  Buffer create_buffer(VkDeviceSize size, VkBufferUsageFlags usage, MemoryUse use = MemoryUse::device);
  void destroy(Buffer& buffer);
  // A 2D image with one mip level and a view of it.
  Image create_image(std::uint32_t width, std::uint32_t height, VkFormat format, VkImageUsageFlags usage,
                     VkImageAspectFlags aspect);
  void destroy(Image& image);
  VkShaderModule create_shader(std::span<const std::uint32_t> spirv);

  // Submits one command buffer and waits for it (one fence per submit).
  void submit_and_wait(VkCommandBuffer commands);

 private:
  void release();
  // A memory type among `allowed` with all of `required`, one with `preferred` too if any.
  std::uint32_t memory_type(std::uint32_t allowed, VkMemoryPropertyFlags required, VkMemoryPropertyFlags preferred) const;
  VkDeviceMemory allocate(const VkMemoryRequirements& requirements, VkMemoryPropertyFlags required,
                          VkMemoryPropertyFlags preferred, bool& host_visible);

  VkInstance instance_ = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
  VkPhysicalDevice physical_ = VK_NULL_HANDLE;
  VkDevice device_ = VK_NULL_HANDLE;
  VkQueue queue_ = VK_NULL_HANDLE;
  std::uint32_t queue_family_ = 0;
  VkCommandPool pool_ = VK_NULL_HANDLE;
  VkFence fence_ = VK_NULL_HANDLE;
  VkPhysicalDeviceProperties properties_{};
  VkPhysicalDeviceMemoryProperties memory_properties_{};
  VkDeviceSize memory_budget_ = 0;
  DeviceInfo info_;
};

}  // namespace bluetile::gpu
