// Label volumes as NIfTI, read back with the NIfTI reference library: header, affine, voxels,
// the ITK-SNAP label table.
#include <gtest/gtest.h>
#include <nifti1_io.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "scansurf/outputs.h"
#include "scansurf/palette.h"
#include "support/scratch_dir_test.h"

namespace scansurf {
namespace {

namespace fs = std::filesystem;

using VolumeFormats = test::ScratchDirTest;

std::string readFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

struct NimDeleter {
  void operator()(nifti_image* nim) const { nifti_image_free(nim); }
};
using Nim = std::unique_ptr<nifti_image, NimDeleter>;

// Two features: "outer" with its own colour, and one whose name holds quotes (palette colour).
ContourSet twoFeatures() {
  ContourSet set;
  set.source = "hand-made";
  set.features.resize(2);
  set.features[0].name = "outer";
  set.features[0].color = Rgb{200, 10, 10};
  set.features[1].name = "in \"side\"";
  return set;
}

// 4 x 3 x 3 voxels at LPS origin (-10, 20, 5) with steps 0.5, 0.75, 2.5 mm; labels 0..2.
LabelVolume handVolume() {
  LabelVolume v;
  v.grid.nx = 4, v.grid.ny = 3, v.grid.nz = 3;
  v.grid.originX = -10, v.grid.originY = 20;
  v.grid.spacingX = 0.5, v.grid.spacingY = 0.75;
  v.grid.layerZ = {5, 7.5, 10};
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 4; ++i) v.labels.push_back(static_cast<Label>((i + 2 * j + k) % 3));
  return v;
}

// ---------------------------------------------------------------------------------------
// NIfTI

TEST_F(VolumeFormats, NiftiGzipHasTheRasAffineTheLabelsAndAnItkSnapTable) {
  const ContourSet set = twoFeatures();
  const LabelVolume v = handVolume();
  const fs::path path = dir_ / "labels.nii.gz";
  ASSERT_TRUE(writeLabelVolume(path, set, v));
  const std::string bytes = readFile(path);
  ASSERT_GE(bytes.size(), 2u);
  EXPECT_EQ(static_cast<unsigned char>(bytes[0]), 0x1f) << "gzip";
  EXPECT_EQ(static_cast<unsigned char>(bytes[1]), 0x8b) << "gzip";

  Nim nim(nifti_image_read(path.c_str(), 1));
  ASSERT_TRUE(nim && nim->data);
  EXPECT_EQ(nim->nifti_type, NIFTI_FTYPE_NIFTI1_1);
  EXPECT_EQ(nim->ndim, 3);
  EXPECT_EQ(nim->nx, 4);
  EXPECT_EQ(nim->ny, 3);
  EXPECT_EQ(nim->nz, 3);
  EXPECT_EQ(nim->datatype, DT_UINT8);
  EXPECT_FLOAT_EQ(nim->dx, 0.5f);
  EXPECT_FLOAT_EQ(nim->dy, 0.75f);
  EXPECT_FLOAT_EQ(nim->dz, 2.5f);
  EXPECT_EQ(nim->xyz_units, NIFTI_UNITS_MM);
  EXPECT_EQ(nim->intent_code, NIFTI_INTENT_LABEL);
  EXPECT_FLOAT_EQ(nim->cal_min, 0);
  EXPECT_FLOAT_EQ(nim->cal_max, 2);
  EXPECT_EQ(nim->qform_code, NIFTI_XFORM_SCANNER_ANAT);
  EXPECT_EQ(nim->sform_code, NIFTI_XFORM_SCANNER_ANAT);
  // RAS = diag(-1, -1, 1) * LPS: x and y steps and origin negated.
  const double expected[3][4] = {{-0.5, 0, 0, 10}, {0, -0.75, 0, -20}, {0, 0, 2.5, 5}};
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) {
      EXPECT_NEAR(nim->sto_xyz.m[r][c], expected[r][c], 1e-5) << "sform " << r << "," << c;
      EXPECT_NEAR(nim->qto_xyz.m[r][c], expected[r][c], 1e-5) << "qform " << r << "," << c;
    }
  const auto* data = static_cast<const std::uint8_t*>(nim->data);
  EXPECT_EQ(std::vector<Label>(data, data + nim->nvox), v.labels);

  // A known point: the LPS centre of voxel (3, 1, 2) is (-8.5, 20.75, 10), RAS (8.5, -20.75, 10).
  const float ras[3] = {8.5f, -20.75f, 10.0f};
  int ijk[3];
  for (int r = 0; r < 3; ++r) {
    const float* row = nim->sto_ijk.m[r];
    ijk[r] = static_cast<int>(std::lround(row[0] * ras[0] + row[1] * ras[1] + row[2] * ras[2] + row[3]));
  }
  EXPECT_EQ(ijk[0], 3);
  EXPECT_EQ(ijk[1], 1);
  EXPECT_EQ(ijk[2], 2);
  EXPECT_EQ(data[ijk[0] + 4 * (ijk[1] + 3 * ijk[2])], v.at(3, 1, 2));

  // The ITK-SNAP label description beside it.
  const std::string table = readFile(dir_ / "labels.label.txt");
  EXPECT_NE(table.find("# ITK-SnAP Label Description File"), std::string::npos);
  std::map<int, std::string> lines;
  std::istringstream in(table);
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    int idx = -1;
    std::istringstream(line) >> idx;
    lines[idx] = line;
  }
  ASSERT_EQ(lines.size(), 3u);
  auto fields = [&](int idx) {
    int i, r, g, b, vis, msh;
    double a;
    std::istringstream f(lines[idx]);
    f >> i >> r >> g >> b >> a >> vis >> msh;
    std::string rest;
    std::getline(f, rest);
    return std::make_tuple(r, g, b, a, vis, msh, rest.substr(rest.find('"')));
  };
  EXPECT_EQ(fields(0), std::make_tuple(0, 0, 0, 0.0, 0, 0, std::string("\"Clear Label\"")));
  EXPECT_EQ(fields(1), std::make_tuple(200, 10, 10, 1.0, 1, 1, std::string("\"outer\"")));
  const Rgb second = featureColors(set)[1];
  EXPECT_EQ(fields(2), std::make_tuple(int{second[0]}, int{second[1]}, int{second[2]}, 1.0, 1, 1, std::string("\"in 'side'\"")));
}

TEST_F(VolumeFormats, NiftiUncompressedUint16OnUnevenLayersIsResampled) {
  LabelVolume v;
  v.grid.nx = 2, v.grid.ny = 1, v.grid.nz = 3;
  v.grid.spacingX = 1, v.grid.spacingY = 1;
  v.grid.layerZ = {0, 1, 3};
  v.labels = {0, 300, 1, 2, 3, 4};
  ContourSet set;
  set.features.resize(300);
  for (std::size_t f = 0; f < set.features.size(); ++f) set.features[f].name = "f" + std::to_string(f);
  const fs::path path = dir_ / "wide.nii";
  ASSERT_TRUE(writeLabelVolume(path, set, v));
  const std::string bytes = readFile(path);
  ASSERT_GE(bytes.size(), 352u);
  EXPECT_EQ(bytes.substr(344, 4), std::string("n+1\0", 4)) << "single-file NIfTI-1 magic";
  Nim nim(nifti_image_read(path.c_str(), 1));
  ASSERT_TRUE(nim && nim->data);
  EXPECT_EQ(nim->datatype, DT_UINT16);
  EXPECT_EQ(nim->nz, 4);  // z = 0, 1, 2, 3: the smallest gap
  EXPECT_FLOAT_EQ(nim->dz, 1.0f);
  const auto* data = static_cast<const std::uint16_t*>(nim->data);
  EXPECT_EQ(std::vector<Label>(data, data + nim->nvox), (std::vector<Label>{0, 300, 1, 2, 1, 2, 3, 4}));
  EXPECT_TRUE(fs::exists(dir_ / "wide.label.txt"));
}

TEST_F(VolumeFormats, OutputChecksKnowTheVolumeExtensions) {
  for (const char* name : {"a.nrrd", "a.seg.nrrd", "a.nii", "a.nii.gz", "A.NII.GZ"}) {
    OutputPlan plan;
    plan.labelVolume = dir_ / name;
    EXPECT_TRUE(checkOutputs(plan)) << name;
  }
  OutputPlan plan;
  plan.labelVolume = dir_ / "a.mha";
  auto r = checkOutputs(plan);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().code, Errc::InvalidArgument);
  EXPECT_NE(r.error().message.find("known: .nrrd, .seg.nrrd, .nii, .nii.gz"), std::string::npos) << r.error().message;
  EXPECT_FALSE(writeLabelVolume(dir_ / "a.vtk", twoFeatures(), handVolume()));
  EXPECT_EQ(labelTablePathFor("x/a.nii.gz", VolumeFormat::Nifti), fs::path("x/a.label.txt"));
  EXPECT_EQ(labelTablePathFor("x/a.seg.nrrd", VolumeFormat::Nrrd), fs::path("x/a.seg.ctbl"));

  EXPECT_EQ(fileCount(), 0u) << "checks write nothing";
}

}  // namespace
}  // namespace scansurf
