// Write-to-temporary-then-rename, the POSIX way to replace a file atomically.
#include "io/atomic_file.h"

#include <fstream>
#include <sstream>

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <string>
#include <system_error>
#include <utility>

namespace scansurf {
namespace {

std::string systemError(int err) { return std::error_code(err, std::generic_category()).message(); }

// pid and a process-wide counter keep concurrent writers (threads or processes) apart.
std::string uniqueSuffix() {
  static std::atomic<unsigned> counter{0};
  return std::to_string(::getpid()) + "-" + std::to_string(counter++);
}

Unexpected ioError(const std::string& what, const std::filesystem::path& path, const std::string& why) {
  return makeError(Errc::Io, what + " '" + path.string() + "': " + why);
}

thread_local bool syncDeferred = false;

// fsync unless a DeferredSync on this thread promised one sync for all.
bool syncUnlessDeferred(int fd) { return syncDeferred || ::fsync(fd) == 0; }

}  // namespace

DeferredSync::DeferredSync() : previous_(std::exchange(syncDeferred, true)) {}
DeferredSync::~DeferredSync() { syncDeferred = previous_; }

Result<void> syncFileSystemOf(const std::filesystem::path& directory) {
  errno = 0;
  const int fd = ::open(directory.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  const bool synced = fd >= 0 && ::syncfs(fd) == 0 && ::fsync(fd) == 0;
  const int err = errno;
  if (fd >= 0) ::close(fd);
  if (!synced) return ioError("cannot sync", directory, systemError(err));
  return {};
}

AtomicFile::AtomicFile(std::filesystem::path target, std::filesystem::path temp, std::FILE* file)
    : target_(std::move(target)), temp_(std::move(temp)), file_(file) {}

AtomicFile::AtomicFile(AtomicFile&& other) noexcept
    : target_(std::move(other.target_)), temp_(std::exchange(other.temp_, {})), file_(std::exchange(other.file_, nullptr)) {}

AtomicFile& AtomicFile::operator=(AtomicFile&& other) noexcept {
  if (this != &other) {
    discard();
    target_ = std::move(other.target_);
    temp_ = std::exchange(other.temp_, {});
    file_ = std::exchange(other.file_, nullptr);
  }
  return *this;
}

AtomicFile::~AtomicFile() { discard(); }

void AtomicFile::discard() {
  if (file_) std::fclose(file_);
  file_ = nullptr;
  if (!temp_.empty()) {
    std::error_code ec;
    std::filesystem::remove(temp_, ec);
    temp_.clear();
  }
}

Result<AtomicFile> AtomicFile::create(const std::filesystem::path& target) {
  std::filesystem::path temp = target;
  temp += ".tmp-" + uniqueSuffix();
  errno = 0;
  std::FILE* file = std::fopen(temp.c_str(), "wbx");  // x: never clobber an existing file
  if (!file) return ioError("cannot create a temporary file for", target, temp.string() + ": " + systemError(errno));
  return AtomicFile(target, std::move(temp), file);
}

Result<void> AtomicFile::write(const void* data, std::size_t size) {
  if (!file_) return ioError("write after close of", target_, "file is not open");
  if (size == 0) return {};
  errno = 0;
  if (std::fwrite(data, 1, size, file_) != size) {
    const int err = errno;
    return ioError("cannot write", temp_, err ? systemError(err) : "short write");
  }
  return {};
}

Result<void> AtomicFile::commit() {
  if (!file_) return ioError("commit after close of", target_, "file is not open");
  errno = 0;
  const bool flushed = std::fflush(file_) == 0 && syncUnlessDeferred(::fileno(file_));
  const int flushError = errno;
  const bool closed = std::fclose(file_) == 0;
  const int closeError = errno;
  file_ = nullptr;
  if (!flushed || !closed) {
    const std::filesystem::path temp = temp_;
    discard();
    return ioError("cannot write", temp, systemError(!flushed ? flushError : closeError));
  }
  std::error_code ec;
  std::filesystem::rename(temp_, target_, ec);
  if (ec) {
    discard();
    return ioError("cannot replace", target_, ec.message());
  }
  temp_.clear();  // now the target: nothing to remove
  return {};
}

Result<void> writeFileAtomically(const std::filesystem::path& target,
                                 const std::function<Result<void>(AtomicFile& file)>& writeContents) {
  SCANSURF_ASSIGN_OR_RETURN(AtomicFile file, AtomicFile::create(target));
  SCANSURF_TRY(writeContents(file));
  return file.commit();
}

Result<void> writeFileAtomically(const std::filesystem::path& target, const void* data, std::size_t size) {
  return writeFileAtomically(target, [&](AtomicFile& file) { return file.write(data, size); });
}

Result<void> writeThroughTemporaryPath(const std::filesystem::path& target, const std::string& suffix,
                                       const std::function<Result<void>(const std::filesystem::path& temporary)>& write) {
  const std::filesystem::path parent = target.has_parent_path() ? target.parent_path() : std::filesystem::path(".");
  std::string name = ".";
  name += target.filename().string();
  name += ".tmp-";
  name += uniqueSuffix();
  name += suffix;
  const std::filesystem::path temp = parent / name;
  auto removeTemp = [&] {
    std::error_code ignored;
    std::filesystem::remove(temp, ignored);
  };
  Result<void> written = write(temp);
  if (!written) {
    removeTemp();
    return written;
  }
  errno = 0;
  const int fd = ::open(temp.c_str(), O_RDONLY | O_CLOEXEC);
  const bool synced = fd >= 0 && syncUnlessDeferred(fd);
  const int syncError = errno;
  if (fd >= 0) ::close(fd);
  if (!synced) {
    removeTemp();
    return ioError("cannot write", temp, systemError(syncError));
  }
  std::error_code ec;
  std::filesystem::rename(temp, target, ec);
  if (ec) {
    removeTemp();
    return ioError("cannot replace", target, ec.message());
  }
  return {};
}

Result<void> ensureWritableDirectory(const std::filesystem::path& directory) {
  std::error_code ec;
  if (std::filesystem::exists(directory, ec) && !std::filesystem::is_directory(directory, ec))
    return ioError("output directory", directory, "exists and is not a directory");
  std::filesystem::create_directories(directory, ec);
  if (ec) return ioError("cannot create output directory", directory, ec.message());
  // Probe by creating (and removing) a file: permission bits alone miss read-only mounts and ACLs.
  Result<AtomicFile> probe = AtomicFile::create(directory / ".scansurf-probe");
  if (!probe) return ioError("output directory", directory, "is not writable: " + probe.error().message);
  return {};
}

}  // namespace scansurf

namespace scansurf {

Result<std::string> readWholeFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return makeError(Errc::Io, path.string() + ": cannot open the file");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) return makeError(Errc::Io, path.string() + ": read error");
  return text.str();
}

}  // namespace scansurf
