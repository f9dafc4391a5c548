// scansurf: how much host memory a run may use, and sizes written for people.
#pragma once

#include <cstdint>
#include <string>

namespace scansurf {

struct HostMemory {
  std::uint64_t bytes = 0;
  std::string source;  // where the figure comes from: "MemAvailable", "the cgroup's memory.max", ...
};

// The memory this process can still allocate without being killed: the kernel's MemAvailable,
// lowered by the cgroup's limit (v2 memory.max - memory.current, or v1 limit - usage) and by
// RLIMIT_DATA / RLIMIT_AS when set. Zero bytes when none of them can be read.
HostMemory availableHostMemory();

// "22.5 GiB", "640 MiB", "12.0 KiB": binary units, three significant digits.
std::string formatBytes(std::uint64_t bytes);

}  // namespace scansurf
