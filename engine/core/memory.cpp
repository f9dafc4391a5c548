// scansurf: available host memory (Linux: /proc/meminfo, cgroup v2 and v1, rlimits).
#include "core/memory.h"

#include <sys/resource.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

namespace scansurf {
namespace {

// The first number in a file (a cgroup value), or nothing for "max" or a missing file.
bool readNumber(const char* path, std::uint64_t& value) {
  std::ifstream in(path);
  std::string text;
  if (!(in >> text) || text == "max") return false;
  try {
    std::size_t used = 0;
    value = std::stoull(text, &used);
    return used == text.size();
  } catch (...) {
    return false;
  }
}

bool memAvailable(std::uint64_t& bytes) {
  std::ifstream in("/proc/meminfo");
  std::string key, unit;
  std::uint64_t kib = 0;
  while (in >> key >> kib) {
    std::getline(in, unit);
    if (key == "MemAvailable:") return bytes = kib * 1024, true;
  }
  return false;
}

void lowerTo(HostMemory& memory, std::uint64_t bytes, const char* source) {
  if (memory.bytes == 0 || bytes < memory.bytes) memory = {bytes, source};
}

// Current virtual size and data segment of this process, for the rlimits.
std::uint64_t processVirtualBytes() {
  std::ifstream in("/proc/self/statm");
  std::uint64_t pages = 0;
  in >> pages;
  return pages * static_cast<std::uint64_t>(sysconf(_SC_PAGESIZE));
}

void lowerToRlimit(HostMemory& memory, int resource, const char* source) {
  rlimit limit{};
  if (getrlimit(resource, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY) return;
  const std::uint64_t used = processVirtualBytes();
  lowerTo(memory, limit.rlim_cur > used ? limit.rlim_cur - used : 0, source);
}

}  // namespace

HostMemory availableHostMemory() {
  HostMemory memory;
  std::uint64_t bytes = 0, used = 0;
  if (memAvailable(bytes)) lowerTo(memory, bytes, "the system's available memory");
  if (readNumber("/sys/fs/cgroup/memory.max", bytes) && readNumber("/sys/fs/cgroup/memory.current", used))
    lowerTo(memory, bytes > used ? bytes - used : 0, "the cgroup's memory.max");
  else if (readNumber("/sys/fs/cgroup/memory/memory.limit_in_bytes", bytes) &&
           readNumber("/sys/fs/cgroup/memory/memory.usage_in_bytes", used) && bytes < (std::uint64_t{1} << 60))
    lowerTo(memory, bytes > used ? bytes - used : 0, "the cgroup's memory limit");
  lowerToRlimit(memory, RLIMIT_AS, "the address-space limit (ulimit -v)");
  lowerToRlimit(memory, RLIMIT_DATA, "the data-segment limit (ulimit -d)");
  return memory;
}

std::string formatBytes(std::uint64_t bytes) {
  static constexpr const char* kUnits[] = {"B", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
  double value = static_cast<double>(bytes);
  int unit = 0;
  while (value >= 1024 && unit < 6) value /= 1024, ++unit;
  char text[32];
  std::snprintf(text, sizeof text,
                unit == 0 || value >= 100 ? "%.0f %s"
                : value >= 10             ? "%.1f %s"
                                          : "%.2f %s",
                value, kUnits[unit]);
  return text;
}

}  // namespace scansurf
