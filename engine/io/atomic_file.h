// scansurf: files that appear complete or not at all.
#pragma once

#include <cstddef>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <string>

#include "scansurf/result.h"

namespace scansurf {

// Writes to `<target>.tmp-<pid>-<n>` beside the target and renames it over the target on
// commit(), so readers never see a partial file and a failed write leaves the old one intact.
// Destroyed without a successful commit, the temporary file is removed. Move-only.
class AtomicFile {
 public:
  // Opens the temporary file for binary writing. Errors (Errc::Io) name the path and the
  // system error, e.g. when the directory is missing or not writable.
  static Result<AtomicFile> create(const std::filesystem::path& target);

  AtomicFile(AtomicFile&& other) noexcept;
  AtomicFile& operator=(AtomicFile&& other) noexcept;
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;
  ~AtomicFile();

  // Appends size bytes. Errors: the file is closed or the write failed (disk full, ...).
  Result<void> write(const void* data, std::size_t size);
  // Flushes, syncs and closes the temporary file, then renames it over the target.
  // After an error the temporary file is removed and the target is untouched.
  Result<void> commit();

  const std::filesystem::path& target() const { return target_; }
  const std::filesystem::path& temporaryPath() const { return temp_; }

 private:
  AtomicFile(std::filesystem::path target, std::filesystem::path temp, std::FILE* file);
  void discard();

  std::filesystem::path target_;
  std::filesystem::path temp_;
  std::FILE* file_ = nullptr;
};

// Writes `target` through an AtomicFile: commits it when writeContents succeeds, else leaves
// the target as it was. Returns writeContents's error, or AtomicFile's (Errc::Io, naming the
// file). Every writer goes through here, so none can forget the commit.
Result<void> writeFileAtomically(const std::filesystem::path& target,
                                 const std::function<Result<void>(AtomicFile& file)>& writeContents);
// The same for contents already in memory: size bytes at data.
Result<void> writeFileAtomically(const std::filesystem::path& target, const void* data, std::size_t size);
// For writers whose library opens the file itself (by name): calls write(temporary) with a
// fresh path beside `target` whose name ends in `suffix` (libraries that choose the encoding by
// the name, such as nifti's ".nii.gz", need it), then syncs the file and renames it over
// `target`. After an error from write, the sync or the rename, the temporary file is removed
// and `target` is untouched. Errors: write's own, or Errc::Io naming the path.
Result<void> writeThroughTemporaryPath(const std::filesystem::path& target, const std::string& suffix,
                                       const std::function<Result<void>(const std::filesystem::path& temporary)>& write);

// While one lives on a thread, AtomicFile and writeThroughTemporaryPath on that thread skip
// their per-file fsync: OutputStaging writes many files and syncs them once, before its moves
// (thousands of features would otherwise spend minutes in fsync).
class DeferredSync {
 public:
  DeferredSync();
  ~DeferredSync();
  DeferredSync(const DeferredSync&) = delete;
  DeferredSync& operator=(const DeferredSync&) = delete;

 private:
  bool previous_;
};

// Makes everything written to the file system holding `directory` durable (syncfs), then the
// directory entry itself. Errors: Errc::Io naming the directory.
Result<void> syncFileSystemOf(const std::filesystem::path& directory);

// The whole file as bytes. Errors: Errc::Io naming the path ("cannot open the file", "read error").
Result<std::string> readWholeFile(const std::filesystem::path& path);

// Creates `directory` (and its parents) if missing and checks that files can be created in
// it, so a run fails before its work rather than after. Errors (Errc::Io) name the path.
Result<void> ensureWritableDirectory(const std::filesystem::path& directory);

}  // namespace scansurf
