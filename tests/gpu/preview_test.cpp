// The preview picture on lavapipe with validation on: the expected size, not blank, every
// feature's colour visible, and each view preset framing the surfaces.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <memory>

#include "gpu_test_env.h"
#include "scansurf/palette.h"
#include "support/shapes.h"

namespace scansurf::test {
namespace {

using PreviewTest = EngineTest;

// Pixels whose hue is close to `c` (shading scales the colour, so compare directions).
std::size_t pixelsOfColor(const PreviewImage& img, Rgb c) {
  std::size_t n = 0;
  const double cl =
      std::sqrt(static_cast<double>(c[0]) * c[0] + static_cast<double>(c[1]) * c[1] + static_cast<double>(c[2]) * c[2]);
  for (std::size_t p = 0; p < img.rgba.size(); p += 4) {
    const double r = img.rgba[p], g = img.rgba[p + 1], b = img.rgba[p + 2];
    const double l = std::sqrt(r * r + g * g + b * b);
    if (l < 20) continue;
    const double cosine = (r * c[0] + g * c[1] + b * c[2]) / (l * cl);
    if (cosine > 0.9995) ++n;
  }
  return n;
}

std::size_t nonBackground(const PreviewImage& img, Rgb bg) {
  std::size_t n = 0;
  for (std::size_t p = 0; p < img.rgba.size(); p += 4)
    n += img.rgba[p] != bg[0] || img.rgba[p + 1] != bg[1] || img.rgba[p + 2] != bg[2];
  return n;
}

TEST_F(PreviewTest, SideBySideFeaturesShowTheirColoursAtTheRequestedSize) {
  auto built = engine_->build(abuttingContours(10, 6, 2.5), {});
  ASSERT_TRUE(built) << built.error().message;
  PreviewOptions options;
  options.width = 200;
  options.height = 150;
  options.colors = {Rgb{220, 40, 40}, Rgb{40, 60, 220}};
  options.view = ViewPreset::Front;
  auto img = engine_->renderPreview(built->surfaces, options);
  ASSERT_TRUE(img) << img.error().message;
  EXPECT_EQ(img->width, 200u);
  EXPECT_EQ(img->height, 150u);
  ASSERT_EQ(img->rgba.size(), 200u * 150u * 4u);
  const std::size_t covered = nonBackground(*img, options.background);
  EXPECT_GT(covered, 200u * 150u / 10) << "the surfaces fill a good part of the picture";
  EXPECT_LT(covered, 200u * 150u) << "with background around them";
  EXPECT_GT(pixelsOfColor(*img, options.colors[0]), 500u);
  EXPECT_GT(pixelsOfColor(*img, options.colors[1]), 500u);
  // Seen from the front, x grows to the right: "left" (x < 0) on the left half.
  std::size_t leftRed = 0, rightRed = 0;
  for (std::uint32_t y = 0; y < img->height; ++y)
    for (std::uint32_t x = 0; x < img->width; ++x) {
      const std::uint8_t* p = &img->rgba[4 * (y * img->width + x)];
      if (p[0] > 2 * p[2] && p[0] > 60) (x < img->width / 2 ? leftRed : rightRed)++;
    }
  EXPECT_GT(leftRed, 10 * (rightRed + 1));
}

TEST_F(PreviewTest, TranslucentOuterFeatureShowsWhatItEncloses) {
  const ContourSet set = nestedSpheresContours(20, 8, 2.5);
  BuildOptions buildOptions;
  buildOptions.grid.voxelSize = 1.0;
  auto built = engine_->build(set, buildOptions);
  ASSERT_TRUE(built) << built.error().message;
  PreviewOptions options;
  options.width = 160;
  options.height = 160;
  options.colors = featureColors(set);
  for (ViewPreset view : {ViewPreset::Oblique, ViewPreset::Top, ViewPreset::Left}) {
    options.view = view;
    options.opacity = {1.0f, 1.0f};
    auto opaque = engine_->renderPreview(built->surfaces, options);
    ASSERT_TRUE(opaque) << opaque.error().message;
    EXPECT_EQ(pixelsOfColor(*opaque, options.colors[1]), 0u) << "hidden inside the opaque outer sphere";
    options.opacity = {0.3f, 1.0f};
    auto seeThrough = engine_->renderPreview(built->surfaces, options);
    ASSERT_TRUE(seeThrough) << seeThrough.error().message;
    EXPECT_GT(nonBackground(*seeThrough, options.background), 160u * 160u / 4);
    // The inner sphere's colour blended with the outer one differs from the outer alone.
    std::size_t differing = 0;
    for (std::size_t p = 0; p < opaque->rgba.size(); ++p) differing += opaque->rgba[p] != seeThrough->rgba[p];
    EXPECT_GT(differing, 1000u);
  }
}

TEST_F(PreviewTest, ZeroSizeIsRefused) {
  auto built = engine_->build(sphereContours(5, 1), {});
  ASSERT_TRUE(built);
  PreviewOptions options;
  options.width = 0;
  auto img = engine_->renderPreview(built->surfaces, options);
  ASSERT_FALSE(img);
  EXPECT_EQ(img.error().code, Errc::InvalidArgument);
}

// A picture that needs more host memory than allowed is refused before anything is allocated.
TEST_F(PreviewTest, APictureOverTheMemoryLimitIsRefused) {
  auto built = engine_->build(sphereContours(5, 1), {});
  ASSERT_TRUE(built);
  PreviewOptions options;
  options.width = options.height = 4096;
  options.memoryLimit = estimatePreviewBytes(options) - 1;
  auto img = engine_->renderPreview(built->surfaces, options);
  ASSERT_FALSE(img);
  EXPECT_EQ(img.error().code, Errc::ResourceLimit);
  EXPECT_NE(img.error().message.find("a 4096 x 4096 picture needs about"), std::string::npos) << img.error().message;
  options.width = options.height = 64;
  EXPECT_TRUE(engine_->renderPreview(built->surfaces, options));
}

}  // namespace
}  // namespace scansurf::test
