#include "io/ply_writer.h"

#include <gtest/gtest.h>

#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include "io/atomic_file.h"
#include "support/scratch_dir_test.h"

namespace scansurf {
namespace {

namespace fs = std::filesystem;

using PlyTest = test::ScratchDirTest;

// The tiny reader: binary little-endian PLY with float xyz, a uchar/int face list and
// optional ushort face properties.
struct PlyData {
  std::vector<std::string> comments;
  std::vector<float> positions;
  std::vector<std::uint32_t> triangles;
  std::vector<std::uint16_t> faceExtras;  // per face, in header order
  int extrasPerFace = 0;
};

template <typename T>
T readLe(const std::string& bytes, std::size_t& at) {
  T v;
  std::memcpy(&v, bytes.data() + at, sizeof(T));  // the test host is little-endian
  at += sizeof(T);
  return v;
}

PlyData readPly(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::size_t end = bytes.find("end_header\n");
  EXPECT_NE(end, std::string::npos);
  std::istringstream header(bytes.substr(0, end));
  PlyData d;
  std::string line;
  std::size_t vertices = 0, faces = 0;
  std::getline(header, line);
  EXPECT_EQ(line, "ply");
  std::getline(header, line);
  EXPECT_EQ(line, "format binary_little_endian 1.0");
  std::vector<std::string> vertexProps;
  bool inFace = false;
  while (std::getline(header, line)) {
    std::istringstream ls(line);
    std::string word;
    ls >> word;
    if (word == "comment") {
      d.comments.push_back(line);
    } else if (word == "element") {
      std::string name;
      ls >> name;
      inFace = name == "face";
      if (inFace) {
        ls >> faces;
      } else {
        ls >> vertices;
      }
    } else if (word == "property") {
      std::string type, name;
      ls >> type >> name;
      if (!inFace) {
        EXPECT_EQ(type, "float");
        vertexProps.push_back(name);
      } else if (type == "list") {
        EXPECT_NE(line.find("list uchar int vertex_indices"), std::string::npos);
      } else {
        EXPECT_EQ(type, "ushort");
        ++d.extrasPerFace;
      }
    }
  }
  EXPECT_EQ(vertexProps, (std::vector<std::string>{"x", "y", "z"}));
  std::size_t at = end + std::strlen("end_header\n");
  for (std::size_t i = 0; i < 3 * vertices; ++i) d.positions.push_back(readLe<float>(bytes, at));
  for (std::size_t f = 0; f < faces; ++f) {
    EXPECT_EQ(readLe<std::uint8_t>(bytes, at), 3);
    for (int c = 0; c < 3; ++c) d.triangles.push_back(static_cast<std::uint32_t>(readLe<std::int32_t>(bytes, at)));
    for (int e = 0; e < d.extrasPerFace; ++e) d.faceExtras.push_back(readLe<std::uint16_t>(bytes, at));
  }
  EXPECT_EQ(at, bytes.size());
  return d;
}

// Two triangles of a multi-label mesh over 5 vertices; vertex 2 unused by feature 0's surface.
MultiLabelMesh smallMesh() {
  MultiLabelMesh m;
  m.positions = {0, 0, 0, 1.5f, 0, 0, 9, 9, 9, 0, 2.25f, 0, -1, -2, 3.125f};
  m.triangles = {0, 1, 3, 1, 4, 3, 2, 4, 0};
  m.labels = {1, 2, 0, 1, 0, 2};
  return m;
}

TEST_F(PlyTest, MultiLabelRoundTrip) {
  const MultiLabelMesh mesh = smallMesh();
  const fs::path path = dir_ / "all.ply";
  ASSERT_TRUE(writeMultiLabelPly(path, mesh));
  const PlyData d = readPly(path);
  EXPECT_EQ(d.positions, mesh.positions);
  EXPECT_EQ(d.triangles, mesh.triangles);
  EXPECT_EQ(d.extrasPerFace, 2);
  EXPECT_EQ(d.faceExtras, (std::vector<std::uint16_t>{1, 2, 0, 1, 0, 2}));
  ASSERT_FALSE(d.comments.empty());
  bool units = false, labels = false;
  for (const auto& c : d.comments) {
    units |= c.find("units") != std::string::npos;
    labels |= c.find("label_inside") != std::string::npos;
  }
  EXPECT_TRUE(units && labels);
  EXPECT_EQ(fileCount(), 1u);  // no temporary left behind
}

TEST_F(PlyTest, SurfaceCompactsVerticesInOrder) {
  const MultiLabelMesh mesh = smallMesh();
  FeatureSurface s;
  s.feature = 0;
  s.triangles = {0, 1, 3, 1, 4, 3};  // uses 0, 1, 3, 4
  const fs::path path = dir_ / "feature.ply";
  ASSERT_TRUE(writeSurfacePly(path, mesh, s));
  const PlyData d = readPly(path);
  EXPECT_EQ(d.positions, (std::vector<float>{0, 0, 0, 1.5f, 0, 0, 0, 2.25f, 0, -1, -2, 3.125f}));
  EXPECT_EQ(d.triangles, (std::vector<std::uint32_t>{0, 1, 2, 1, 3, 2}));
  EXPECT_EQ(d.extrasPerFace, 0);
}

TEST_F(PlyTest, EmptySurface) {
  const MultiLabelMesh mesh = smallMesh();
  FeatureSurface s;
  s.feature = 3;
  ASSERT_TRUE(writeSurfacePly(dir_ / "empty.ply", mesh, s));
  const PlyData d = readPly(dir_ / "empty.ply");
  EXPECT_TRUE(d.positions.empty());
  EXPECT_TRUE(d.triangles.empty());
}

TEST_F(PlyTest, UnwritableTargetIsIoErrorAndLeavesNothing) {
  // The "directory" is a regular file, so even root cannot create anything under it.
  const fs::path blocker = dir_ / "blocker";
  std::ofstream(blocker) << "x";
  const fs::path target = blocker / "out.ply";
  const Result<void> r = writeMultiLabelPly(target, smallMesh());
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().code, Errc::Io);
  EXPECT_NE(r.error().message.find(target.string()), std::string::npos) << r.error().message;
  EXPECT_EQ(fileCount(), 1u);  // only the blocker

  const Result<void> dirCheck = ensureWritableDirectory(blocker);
  ASSERT_FALSE(dirCheck);
  EXPECT_EQ(dirCheck.error().code, Errc::Io);
  EXPECT_NE(dirCheck.error().message.find(blocker.string()), std::string::npos);
}

TEST_F(PlyTest, ExistingFileReplacedOnlyOnCommit) {
  const fs::path target = dir_ / "keep.ply";
  std::ofstream(target) << "old";
  {
    Result<AtomicFile> f = AtomicFile::create(target);
    ASSERT_TRUE(f);
    ASSERT_TRUE(f->write("new!", 4));
    EXPECT_EQ(fileCount(), 2u);  // target and temporary
    std::ifstream in(target);
    std::string content((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_EQ(content, "old");
    const std::string temp = f->temporaryPath().filename().string();
    EXPECT_EQ(temp.rfind("keep.ply.tmp-" + std::to_string(::getpid()) + "-", 0), 0u) << temp;
  }  // dropped without commit
  EXPECT_EQ(fileCount(), 1u);
  {
    std::ifstream in(target);
    std::string content((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_EQ(content, "old");
  }
  Result<AtomicFile> f = AtomicFile::create(target);
  ASSERT_TRUE(f);
  ASSERT_TRUE(f->write("new!", 4));
  ASSERT_TRUE(f->commit());
  EXPECT_EQ(fileCount(), 1u);
  std::ifstream in(target);
  std::string content((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(content, "new!");
  EXPECT_FALSE(f->commit());  // already closed
}

TEST_F(PlyTest, EnsureWritableDirectoryCreatesIt) {
  const fs::path out = dir_ / "a" / "b";
  ASSERT_TRUE(ensureWritableDirectory(out));
  EXPECT_TRUE(fs::is_directory(out));
  EXPECT_TRUE(fs::is_empty(out));  // the probe is gone
  ASSERT_TRUE(ensureWritableDirectory(out));
}

TEST_F(PlyTest, MovedFromFileDoesNotRemoveTheTemporary) {
  const fs::path target = dir_ / "moved.bin";
  Result<AtomicFile> f = AtomicFile::create(target);
  ASSERT_TRUE(f);
  AtomicFile moved = std::move(*f);
  ASSERT_TRUE(moved.write("abc", 3));
  ASSERT_TRUE(moved.commit());
  EXPECT_TRUE(fs::exists(target));
  EXPECT_EQ(fileCount(), 1u);
}

}  // namespace
}  // namespace scansurf
