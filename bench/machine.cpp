#include "machine.h"

#include <cstdio>
#include <fstream>
#include <thread>

#include <sys/utsname.h>
#include <vulkan/vulkan.h>

#include "bluetile/core/parallel.h"

#ifdef BLUETILE_HAVE_CGAL
#include "cgal_reference.h"
#endif

namespace bluetile::bench {
namespace {

std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("model name", 0) == 0) {
      auto colon = line.find(':');
      if (colon != std::string::npos) return line.substr(line.find_first_not_of(' ', colon + 1));
    }
  return "unknown";
}

// Every Vulkan device with its driver's own name and version string ("llvmpipe ... / Mesa 22.3.6").
std::string vulkan_devices() {
  VkApplicationInfo app{};
  app.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO;
  app.pApplicationName = "bluetile_bench";
  app.apiVersion = VK_API_VERSION_1_2;
  VkInstanceCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO;
  info.pApplicationInfo = &app;
  VkInstance instance = VK_NULL_HANDLE;
  if (vkCreateInstance(&info, nullptr, &instance) != VK_SUCCESS) return "none (no Vulkan instance)";
  std::uint32_t count = 0;
  vkEnumeratePhysicalDevices(instance, &count, nullptr);
  std::vector<VkPhysicalDevice> devices(count);
  vkEnumeratePhysicalDevices(instance, &count, devices.data());
  std::string out;
  for (VkPhysicalDevice d : devices) {
    VkPhysicalDeviceDriverProperties driver{};
    driver.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES;
    VkPhysicalDeviceProperties2 props{};
    props.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2;
    props.pNext = &driver;
    vkGetPhysicalDeviceProperties2(d, &props);
    if (!out.empty()) out += "; ";
    out += props.properties.deviceName;
    if (driver.driverName[0]) out += std::string(" (") + driver.driverName + " " + driver.driverInfo + ")";
  }
  vkDestroyInstance(instance, nullptr);
  return out.empty() ? "none" : out;
}

// The source tree's commit, "-dirty" when it has uncommitted changes (read at run time, so a
// stale configure cannot mislabel results).
std::string source_revision() {
  std::string command = std::string("git -C '") + BLUETILE_SOURCE_DIR + "' describe --always --dirty 2>/dev/null";
  std::FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return "unknown";
  char buf[128] = {};
  std::string out = std::fgets(buf, sizeof buf, pipe) ? buf : "";
  pclose(pipe);
  while (!out.empty() && (out.back() == '\n' || out.back() == ' ')) out.pop_back();
  return out.empty() ? "unknown" : out;
}

}  // namespace

std::vector<std::pair<std::string, std::string>> machine_facts() {
  std::vector<std::pair<std::string, std::string>> facts;
  facts.emplace_back("CPU", cpu_model());
  facts.emplace_back("hardware threads", std::to_string(std::thread::hardware_concurrency()));
  facts.emplace_back("threads used by the exact engine", std::to_string(thread_count()));
  utsname u{};
  if (uname(&u) == 0) facts.emplace_back("OS", std::string(u.sysname) + " " + u.release + " " + u.machine);
#if defined(__clang__)
  facts.emplace_back("compiler", std::string("clang ") + __clang_version__);
#elif defined(__GNUC__)
  facts.emplace_back("compiler", std::string("g++ ") + __VERSION__);
#endif
  facts.emplace_back("build type", BLUETILE_BUILD_TYPE);
  facts.emplace_back("source revision", source_revision());
#ifdef BLUETILE_HAVE_CGAL
  facts.emplace_back("CGAL", cgal_version() + " (Epick kernel)");
#else
  facts.emplace_back("CGAL", "not found at configure time: CGAL rows skipped");
#endif
  facts.emplace_back("Vulkan devices", vulkan_devices());
  return facts;
}

}  // namespace bluetile::bench
