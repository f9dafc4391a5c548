// scansurf: writing a run all or nothing (scansurf/outputs.h, OutputStaging): a lock per
// output directory, files staged in a hidden folder beside their targets, then renamed into
// place, the old files moved aside first and put back if any move fails.
#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstring>

#include "io/atomic_file.h"
#include "io/output_names.h"
#include "scansurf/outputs.h"

namespace fs = std::filesystem;

namespace scansurf {

namespace {
unsigned long nextStagingId() {
  static std::atomic<unsigned long> next{1};
  return next.fetch_add(1);
}
}  // namespace

// Staging folders of processes that died (killed during their write stage) are removed by
// the next run into the same place: the pid in the name is no longer alive.
void removeStaleStaging(const fs::path& parent) {
  constexpr std::string_view kPrefix = ".scansurf-staging-";
  std::error_code ec;
  for (fs::directory_iterator it(parent, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.rfind(kPrefix, 0) != 0) continue;
    const std::string rest = name.substr(kPrefix.size());
    const long pid = std::strtol(rest.c_str(), nullptr, 10);
    if (pid <= 0 || pid == ::getpid()) continue;
    if (::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH) {
      std::error_code ignored;
      fs::remove_all(it->path(), ignored);
    }
  }
}

constexpr const char* kLockName = ".scansurf.lock";

// Removes the lock file's name if it still is the file `fd` locked (a later run may have made a
// new one after an earlier removal).
void unlinkOwnLock(const fs::path& dir, int fd) {
  const fs::path file = dir / kLockName;
  struct stat held {
  }, named{};
  if (::fstat(fd, &held) == 0 && ::lstat(file.c_str(), &named) == 0 && held.st_ino == named.st_ino && held.st_dev == named.st_dev)
    ::unlink(file.c_str());
}

// Opens (or creates) the lock file itself, never what a link of that name points to: a link
// planted there must not let a run empty, overwrite or create a file elsewhere.
Result<int> openLockFile(const fs::path& file) {
  const int fd = ::open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW, 0644);
  if (fd < 0 && errno == ELOOP)
    return makeError(Errc::Io,
                     "the run lock '" + file.string() + "' is a symbolic link; scansurf never follows one there (remove it)");
  if (fd < 0) return makeError(Errc::Io, "cannot open the run lock '" + file.string() + "': " + std::strerror(errno));
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(fd);
    return makeError(Errc::Io, "the run lock '" + file.string() + "' is not a regular file (remove it)");
  }
  return fd;
}

OutputStaging::~OutputStaging() {
  discard();
  for (const auto& [dir, fd] : locks_) ::close(fd);  // releases the flock
}

Result<void> OutputStaging::lock(const fs::path& directory) {
  const fs::path dir = directory.empty() ? fs::path(".") : directory;
  for (const auto& held : locks_)
    if (held.first == dir) return {};
  const fs::path file = dir / kLockName;
  int fd = -1;
  bool busy = false;
  for (int attempt = 0; fd < 0 && attempt < 100; ++attempt) {
    SCANSURF_ASSIGN_OR_RETURN(fd, openLockFile(file));
    busy = ::flock(fd, LOCK_EX | LOCK_NB) != 0;
    struct stat held {
    }, named{};
    if (busy || (::fstat(fd, &held) == 0 && ::lstat(file.c_str(), &named) == 0 && held.st_ino == named.st_ino &&
                 held.st_dev == named.st_dev))
      break;      // held by another run, or locked and still the file of that name
    ::close(fd);  // its last holder unlinked it meanwhile: lock the new one
    fd = -1;
  }
  if (fd < 0) return makeError(Errc::Io, "cannot take the run lock '" + file.string() + "'");
  if (busy) {
    char pid[32] = {};
    const ssize_t n = ::pread(fd, pid, sizeof pid - 1, 0);
    ::close(fd);
    const std::string holder = n > 0 ? " (pid " + std::string(pid, static_cast<std::size_t>(n)) + ")" : "";
    return makeError(Errc::Io, "another scansurf run" + holder + " is writing into '" + dir.string() +
                                   "'; wait for it to finish or choose another output location");
  }
  const std::string self = std::to_string(::getpid());
  if (::ftruncate(fd, 0) != 0 || ::pwrite(fd, self.data(), self.size(), 0) < 0) {
    // The pid is only a courtesy for the message of a run that waits; the lock holds without it.
  }
  locks_.emplace_back(dir, fd);
  return {};
}

void OutputStaging::discard() noexcept {
  std::error_code ignored;
  for (const fs::path& dir : dirs_) fs::remove_all(dir, ignored);
  // Unlinked while still held, so nothing is left behind, also by an interrupted run, and a
  // run that opens the name next makes a fresh file (lock() checks it locked the named one).
  for (const auto& [dir, fd] : locks_) unlinkOwnLock(dir, fd);
}

namespace {

// A staged file is named by its index and the target's extensions (writers read ".nii.gz" and
// ".seg.nrrd" off the name), never its whole name: a 250-character file name plus a prefix
// was more than a file name may be.
std::string stagedSuffix(const fs::path& target) {
  const std::string last = target.extension().string();
  const std::string before = target.stem().extension().string();
  std::string suffix = (before.size() > 1 && before.size() <= 8 ? before : std::string()) + last;
  if (suffix.size() > 24) suffix.clear();
  return suffix;
}

}  // namespace

Result<fs::path> OutputStaging::reserve(const fs::path& target) {
  if (!targets_.insert(target).second)
    return makeError(Errc::InvalidArgument, "two outputs would be written to '" + target.string() + "'");
  const fs::path parent = target.has_parent_path() ? target.parent_path() : fs::path(".");
  // One folder per OutputStaging (pid and a process-wide count): two runs in one process
  // writing to one directory never share or remove each other's staged files.
  if (id_ == 0) id_ = nextStagingId();
  const fs::path dir = parent / (".scansurf-staging-" + std::to_string(::getpid()) + "-" + std::to_string(id_));
  if (std::find(dirs_.begin(), dirs_.end(), dir) == dirs_.end()) {
    SCANSURF_TRY(lock(parent));
    removeStaleStaging(parent);
    std::error_code ec;
    fs::remove_all(dir, ec);
    if (!fs::create_directory(dir, ec)) return makeError(Errc::Io, "cannot create " + dir.string() + ": " + ec.message());
    dirs_.push_back(dir);
  }
  fs::path staged = dir / (std::to_string(files_.size()) + stagedSuffix(target));
  files_.emplace_back(staged, target);
  return staged;
}

Result<void> OutputStaging::stage(const fs::path& target, const std::function<Result<void>(const fs::path& staged)>& write) {
  SCANSURF_ASSIGN_OR_RETURN(const fs::path staged, reserve(target));
  const DeferredSync oneSyncAtCommit;
  Result<void> written = write(staged);
  if (written) return written;
  // Name the file the user asked for, not the staging path.
  std::string message = written.error().message;
  for (std::size_t at; (at = message.find(staged.string())) != std::string::npos;)
    message.replace(at, staged.string().size(), target.string());
  return makeError(written.error().code, message);
}

std::vector<fs::path> OutputStaging::targets() const {
  std::vector<fs::path> out;
  for (const auto& f : files_) out.push_back(f.second);
  return out;
}

Result<std::vector<fs::path>> OutputStaging::commit() {
  std::vector<fs::path> written;
  std::error_code ec;
  // A target that is a directory would stop the moves half way: find it before any move.
  for (const auto& [staged, target] : files_)
    if (fs::is_directory(target, ec))
      return makeError(Errc::Io, "cannot write '" + target.string() + "': a directory is in the way; nothing was replaced");
  // Everything staged reaches the disk before the first move (one sync, not one per file).
  for (const fs::path& dir : dirs_) SCANSURF_TRY(syncFileSystemOf(dir));
  // All or nothing: every old file is moved aside into the staging folder first (same
  // directory, so a rename), then the new ones into place; a move that fails (an immutable
  // file, a mount point) puts back everything moved so far.
  std::vector<std::pair<fs::path, fs::path>> asideOf;  // target, where its old file went
  const auto undo = [&](std::size_t placed) {
    std::error_code ignored;
    for (std::size_t i = 0; i < placed; ++i) fs::rename(files_[i].second, files_[i].first, ignored);
    for (const auto& [target, aside] : asideOf) fs::rename(aside, target, ignored);
  };
  for (std::size_t i = 0; i < files_.size(); ++i) {
    const fs::path& target = files_[i].second;
    if (!fs::exists(fs::symlink_status(target, ec))) continue;
    const fs::path aside = files_[i].first.parent_path() / ("old-" + std::to_string(i));
    fs::rename(target, aside, ec);
    if (ec) {
      undo(0);
      return makeError(Errc::Io, "cannot replace '" + target.string() + "': " + ec.message() + "; nothing was replaced");
    }
    asideOf.emplace_back(target, aside);
  }
  for (std::size_t i = 0; i < files_.size(); ++i) {
    const auto& [staged, target] = files_[i];
    fs::rename(staged, target, ec);
    if (ec) {
      undo(i);
      return makeError(Errc::Io, "cannot move " + target.filename().string() + " into place at '" + target.string() +
                                     "': " + ec.message() + "; nothing was replaced");
    }
    written.push_back(target);
  }
  // The moves themselves: each destination directory's entries.
  for (const fs::path& dir : dirs_) SCANSURF_TRY(syncFileSystemOf(dir.parent_path()));
  return written;
}

}  // namespace scansurf
