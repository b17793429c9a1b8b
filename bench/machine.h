// Facts about the machine and build, printed with every benchmark result.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace bluetile::bench {

// (name, value) pairs in display order: CPU, cores, threads used, OS, compiler, build type,
// CGAL, Vulkan devices and drivers (Mesa version for lavapipe).
std::vector<std::pair<std::string, std::string>> machine_facts();

}  // namespace bluetile::bench
