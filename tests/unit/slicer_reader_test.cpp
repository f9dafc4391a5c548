// 3D Slicer planar-contour segmentations (slicer_reader.h): hand-written files in the three
// encodings VTK writes (ascii, binary, zlib-compressed binary), and the shared SlicerRT
// segmentation when ../shared is there.
#include "io/slicer_reader.h"

#include <openssl/evp.h>
#include <zlib.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "scansurf/input.h"
#include "support/scratch_dir_test.h"

namespace scansurf::test {
namespace {

std::string base64(const std::string& bytes) {
  std::string out(4 * ((bytes.size() + 2) / 3) + 1, '\0');
  const int n = EVP_EncodeBlock(reinterpret_cast<unsigned char*>(out.data()),
                                reinterpret_cast<const unsigned char*>(bytes.data()), static_cast<int>(bytes.size()));
  out.resize(static_cast<std::size_t>(n));
  return out;
}

template <typename T>
std::string bytesOf(const std::vector<T>& values) {
  return std::string(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
}

std::string word32(std::uint32_t v) { return std::string(reinterpret_cast<const char*>(&v), 4); }

enum class Encoding { Ascii, Binary, Zlib };

// An array's element: its attributes and text in the encoding.
template <typename T>
std::string dataArray(const std::string& attributes, const std::vector<T>& values, Encoding e) {
  std::string text;
  if (e == Encoding::Ascii) {
    for (const T& v : values) text += std::to_string(v) + " ";
  } else if (e == Encoding::Binary) {
    const std::string bytes = bytesOf(values);
    text = base64(word32(static_cast<std::uint32_t>(bytes.size())) + bytes);
  } else {
    const std::string bytes = bytesOf(values);
    uLongf size = compressBound(static_cast<uLong>(bytes.size()));
    std::string packed(size, '\0');
    compress(reinterpret_cast<Bytef*>(packed.data()), &size, reinterpret_cast<const Bytef*>(bytes.data()),
             static_cast<uLong>(bytes.size()));
    packed.resize(size);
    const auto n = static_cast<std::uint32_t>(bytes.size());
    text = base64(word32(1) + word32(32768) + word32(n) + word32(static_cast<std::uint32_t>(size))) + base64(packed);
  }
  return "<DataArray " + attributes + (e == Encoding::Ascii ? " format=\"ascii\">" : " format=\"binary\">") + text +
         "</DataArray>";
}

// One segment: two squares 10 mm a side on z = 0 and z = 2 (RAS, closing point repeated).
std::string segmentFile(const std::string& name, Encoding e) {
  std::vector<float> points;
  for (float z : {0.f, 2.f})
    for (auto [x, y] : std::vector<std::pair<float, float>>{{0, 0}, {10, 0}, {10, 10}, {0, 10}, {0, 0}})
      points.insert(points.end(), {x + 5, y + 7, z});
  const std::vector<std::int64_t> connectivity = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9}, offsets = {5, 10};
  const std::string nameBytes = name + '\0';  // VTK ends each string with a NUL
  std::string nameArray;
  if (e == Encoding::Ascii) {
    nameArray = "<Array type=\"String\" Name=\"Segment_Name\" NumberOfTuples=\"1\" format=\"ascii\">" + name + "</Array>";
  } else {
    std::vector<char> chars(nameBytes.begin(), nameBytes.end());
    nameArray = dataArray("type=\"String\" Name=\"Segment_Name\"", chars, e);
    nameArray.replace(0, 10, "<Array");
    nameArray.replace(nameArray.size() - 12, 12, "</Array>");
  }
  const std::string compressor = e == Encoding::Zlib ? " compressor=\"vtkZLibDataCompressor\"" : "";
  return "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"0.1\" byte_order=\"LittleEndian\" "
         "header_type=\"UInt32\"" +
         compressor + "><PolyData><FieldData>" + nameArray +
         dataArray("type=\"Float64\" Name=\"Segment_DefaultColor\" NumberOfComponents=\"3\"", std::vector<double>{1, 0.5, 0}, e) +
         "</FieldData><Piece NumberOfPoints=\"10\" NumberOfLines=\"2\"><Points>" +
         dataArray("type=\"Float32\" Name=\"Points\" NumberOfComponents=\"3\"", points, e) + "</Points><Lines>" +
         dataArray("type=\"Int64\" Name=\"connectivity\"", connectivity, e) +
         dataArray("type=\"Int64\" Name=\"offsets\"", offsets, e) + "</Lines></Piece></PolyData></VTKFile>\n";
}

class SlicerReader : public ScratchDirTest {
 protected:
  std::filesystem::path write(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name, std::ios::binary) << text;
    return dir_ / name;
  }
  // A .seg.vtm naming two segments' .vtp files in a subfolder, as SlicerRT saves them.
  std::filesystem::path writeTwoSegments(const std::string& a, const std::string& b) {
    std::filesystem::create_directories(dir_ / "seg");
    write("seg/a.vtp", segmentFile(a, Encoding::Zlib));
    write("seg/b.vtp", segmentFile(b, Encoding::Binary));
    return write("s.seg.vtm",
                 "<?xml version=\"1.0\"?><VTKFile type=\"vtkMultiBlockDataSet\" version=\"1.0\"><vtkMultiBlockDataSet>"
                 "<DataSet index=\"0\" file=\"seg/a.vtp\"/><DataSet index=\"1\" file=\"seg/b.vtp\"/>"
                 "</vtkMultiBlockDataSet></VTKFile>");
  }
};

TEST_F(SlicerReader, ReadsEachEncodingInLps) {
  for (const Encoding e : {Encoding::Ascii, Encoding::Binary, Encoding::Zlib}) {
    const auto path = write("seg.vtp", segmentFile("Lens", e));
    EXPECT_EQ(detectInputFormat(path), InputFormat::SlicerSegmentation);
    auto read = readSlicerSegmentation(path);
    ASSERT_TRUE(read) << read.error().message;
    ASSERT_EQ(read->features.size(), 1u);
    const Feature& f = read->features[0];
    EXPECT_EQ(f.name, "Lens");
    ASSERT_TRUE(f.color);
    EXPECT_EQ((*f.color)[0], 255);
    EXPECT_EQ((*f.color)[1], 128);
    EXPECT_EQ((*f.color)[2], 0);
    ASSERT_EQ(f.slices.size(), 2u);
    EXPECT_EQ(f.slices[1].z, 2);
    ASSERT_EQ(f.slices[0].contours.size(), 1u);
    const auto& pts = f.slices[0].contours[0].points;
    ASSERT_EQ(pts.size(), 4u);  // the repeated closing point dropped
    EXPECT_EQ(pts[0].x, -5);    // RAS x = 5 is LPS x = -5
    EXPECT_EQ(pts[0].y, -7);
  }
}

TEST_F(SlicerReader, AMultiblockFileReadsEverySegmentItNames) {
  const auto path = writeTwoSegments("A", "B");
  auto read = readContours(path);
  ASSERT_TRUE(read) << read.error().message;
  ASSERT_EQ(read->features.size(), 2u);
  EXPECT_EQ(read->features[1].name, "B");
  EXPECT_EQ(read->files.size(), 3u);  // the multiblock file and both blocks, for the report's hashes
}

// --roi selects segments as it selects an RTSTRUCT's ROIs: the file's extent kept (the default
// grid follows the whole file), a pattern that matches nothing refused naming the segments.
TEST_F(SlicerReader, RoiPatternsSelectSegments) {
  const auto path = writeTwoSegments("Orbit", "Optic Chiasm");
  ReadOptions options;
  options.roiPatterns = {"optic*"};
  auto read = readContours(path, options);
  ASSERT_TRUE(read) << read.error().message;
  ASSERT_EQ(read->features.size(), 1u);
  EXPECT_EQ(read->features[0].name, "Optic Chiasm");
  EXPECT_TRUE(read->fileExtent);
  options.roiPatterns = {"Lens*"};
  auto none = readContours(path, options);
  ASSERT_FALSE(none);
  EXPECT_EQ(none.error().code, Errc::InvalidArgument);
  EXPECT_NE(none.error().message.find("\"Orbit\", \"Optic Chiasm\""), std::string::npos) << none.error().message;
}

TEST_F(SlicerReader, FaultsNameTheFile) {
  const auto missing = write("m.seg.vtm",
                             "<?xml version=\"1.0\"?><VTKFile type=\"vtkMultiBlockDataSet\"><vtkMultiBlockDataSet>"
                             "<DataSet index=\"0\" file=\"gone.vtp\"/></vtkMultiBlockDataSet></VTKFile>");
  auto read = readContours(missing);
  ASSERT_FALSE(read);
  EXPECT_EQ(read.error().code, Errc::Io);
  EXPECT_NE(read.error().message.find("gone.vtp"), std::string::npos) << read.error().message;
  std::string broken = segmentFile("X", Encoding::Zlib);
  broken.replace(broken.find("eJ"), 2, "@@");  // not base64 any more
  auto bad = readContours(write("bad.vtp", broken));
  ASSERT_FALSE(bad);
  EXPECT_EQ(bad.error().code, Errc::InvalidInput);
  EXPECT_NE(bad.error().message.find("bad.vtp"), std::string::npos) << bad.error().message;
}

TEST(SlicerSharedSet, EclipseSegmentationReadsItsSixteenSegments) {
  const std::filesystem::path path = SCANSURF_SHARED "/data/slicer/EclipseEnt_Structures.seg.vtm";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "the shared Slicer segmentation is absent (" << path << ")";
  auto read = readContours(path);
  ASSERT_TRUE(read) << read.error().message;
  ASSERT_EQ(read->features.size(), 16u);
  std::vector<std::string> names;
  for (const Feature& f : read->features) {
    names.push_back(f.name);
    EXPECT_TRUE(f.color) << f.name;
  }
  EXPECT_NE(std::find(names.begin(), names.end(), "optOptic"), names.end());
  EXPECT_NE(std::find(names.begin(), names.end(), "Lens - left"), names.end());
}

}  // namespace
}  // namespace scansurf::test
