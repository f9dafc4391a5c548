// Contour JSON reading, validation messages, writing and round trips.
#include "io/contours_json.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

#include "geometry/contours/validate.h"
#include "geometry/grid/coverage.h"
#include "scansurf/grid.h"
#include "scansurf/label_volume.h"
#include "scansurf/nesting.h"
#include "support/shapes.h"

namespace scansurf {
namespace {

namespace fs = std::filesystem;

constexpr const char* kGood = R"({
  "version": 1,
  "units": "mm",
  "comment": "unknown fields are ignored",
  "features": [
    { "name": "prostate", "color": [0, 200, 200],
      "slices": [
        { "z": 12.5, "contours": [ [[10.0, 4.0], [12.0, 4.0], [12.0, 7.5], [10.0, 7.5], [10.0, 4.0]] ] },
        { "z": 10, "contours": [ [[10, 4], [12, 4], [12, 4], [12, 7.5], [10, 7.5]] ] }
      ] },
    { "name": "skin", "extra": {"a": 1},
      "slices": [
        { "z": 10, "contours": [ [[0, 0], [20, 0], [20, 20], [0, 20]] ] },
        { "z": 12.5, "contours": [ [[0, 0], [20, 0], [20, 20], [0, 20]] ] },
        { "z": 12.5004, "contours": [ [[30, 0], [40, 0], [40, 10]] ] }
      ] }
  ],
  "order": ["prostate", "skin"]
})";

TEST(ContoursJson, ParsesGoodFile) {
  const auto r = parseContoursJson(kGood, "good.json");
  ASSERT_TRUE(r) << r.error().message;
  const ContourSet& set = *r;
  EXPECT_EQ(set.source, "good.json");
  EXPECT_EQ(set.units, "mm");
  ASSERT_EQ(set.features.size(), 2u);
  const Feature& p = set.features[0];
  EXPECT_EQ(p.name, "prostate");
  ASSERT_TRUE(p.color.has_value());
  EXPECT_EQ(*p.color, (Rgb{0, 200, 200}));
  // Slices sorted by z; closing point and consecutive duplicate dropped.
  ASSERT_EQ(p.slices.size(), 2u);
  EXPECT_EQ(p.slices[0].z, 10);
  EXPECT_EQ(p.slices[1].z, 12.5);
  EXPECT_EQ(p.slices[0].contours[0].points.size(), 4u);
  EXPECT_EQ(p.slices[1].contours[0].points.size(), 4u);
  EXPECT_EQ(p.slices[1].contours[0].points[2].y, 7.5);
  // skin: the slices at 12.5 and 12.5004 merged into one of two contours.
  const Feature& s = set.features[1];
  EXPECT_FALSE(s.color.has_value());
  ASSERT_EQ(s.slices.size(), 2u);
  EXPECT_EQ(s.slices[1].z, 12.5);
  EXPECT_EQ(s.slices[1].contours.size(), 2u);
  EXPECT_EQ(set.order, (std::vector<int>{0, 1}));
}

TEST(ContoursJson, UnitsDefaultAndOrderOptional) {
  const auto r = parseContoursJson(
      R"({"version":1,"features":[{"name":"a","slices":[{"z":0,"contours":[[[0,0],[1,0],[0,1]]]}]}]})", "min.json");
  ASSERT_TRUE(r) << r.error().message;
  EXPECT_EQ(r->units, "mm");
  EXPECT_TRUE(r->order.empty());
}

// Parses text and expects an InvalidInput error whose message contains every fragment.
void expectError(const std::string& text, std::vector<std::string> fragments) {
  const auto r = parseContoursJson(text, "bad.json");
  ASSERT_FALSE(r) << "accepted: " << text;
  EXPECT_EQ(r.error().code, Errc::InvalidInput);
  EXPECT_EQ(r.error().message.rfind("bad.json: ", 0), 0u) << r.error().message;
  for (const std::string& f : fragments)
    EXPECT_NE(r.error().message.find(f), std::string::npos) << "missing \"" << f << "\" in: " << r.error().message;
}

// A document with one feature "organ" (#0) preceded by a valid "skin" (#0) when `second`.
std::string doc(const std::string& feature, const std::string& tail = "") {
  return R"({"version":1,"features":[{"name":"skin","slices":[{"z":0,"contours":[[[-50,-50],[50,-50],[50,50],[-50,50]]]}]},)" +
         feature + "]" + tail + "}";
}

TEST(ContoursJson, MalformedJsonGivesBytePosition) {
  expectError(R"({"version": 1, "features": [})", {"not valid JSON", "byte 29"});
  expectError("", {"not valid JSON"});
  expectError("[1, 2]", {"must be a JSON object"});
}

TEST(ContoursJson, VersionErrors) {
  expectError(R"({"features": []})", {"missing \"version\""});
  expectError(R"({"version": 2, "features": []})", {"unsupported \"version\" 2"});
  expectError(R"({"version": "1", "features": []})", {"unsupported \"version\""});
}

TEST(ContoursJson, MissingFields) {
  expectError(R"({"version": 1})", {"missing \"features\""});
  expectError(R"({"version": 1, "features": {}})", {"\"features\" must be an array"});
  expectError(R"({"version": 1, "features": []})", {"no features"});
  expectError(doc(R"({"slices":[]})"), {"feature #1", "missing \"name\""});
  expectError(doc(R"({"name": 5, "slices":[]})"), {"feature #1", "\"name\" must be a string"});
  expectError(doc(R"({"name":"organ"})"), {"feature \"organ\" (#1)", "missing \"slices\""});
  expectError(doc(R"({"name":"organ","slices":[{"contours":[]}]})"), {"feature \"organ\" (#1)", "slice #0", "missing \"z\""});
  expectError(doc(R"({"name":"organ","slices":[{"z":"a","contours":[]}]})"),
              {"feature \"organ\" (#1)", "slice #0", "\"z\" must be a number"});
  expectError(doc(R"({"name":"organ","slices":[{"z":1},{"z":2.5}]})"),
              {"feature \"organ\" (#1)", "slice z=1 (#0)", "missing \"contours\""});
  expectError(doc(R"({"name":"organ","slices":[{"z":1,"contours":[]}]})"),
              {"feature \"organ\" (#1)", "slice z=1 (#0)", "no contours"});
}

TEST(ContoursJson, BadPointsAndContours) {
  expectError(doc(R"({"name":"organ","slices":[{"z":2.5,"contours":[[[0,0],[1,0],[0,1]],[[0,0],[1],[0,1]]]}]})"),
              {"feature \"organ\" (#1)", "slice z=2.5 (#0)", "contour 1", "point 1", "2 numbers"});
  expectError(doc(R"({"name":"organ","slices":[{"z":2.5,"contours":[[[0,0],[1,"x"],[0,1]]]}]})"),
              {"contour 0", "point 1", "2 numbers"});
  expectError(doc(R"({"name":"organ","slices":[{"z":2.5,"contours":[{"points":[]}]}]})"), {"contour 0", "array of points"});
  expectError(doc(R"({"name":"organ","slices":[{"z":0,"contours":[[[0,0],[1,0],[0,1]]]},
                     {"z":12.5,"contours":[[[0,0],[1,0],[0,1]],[[0,0],[1,0],[0,1]],[[3,3],[4,4],[4,4],[3,3]]]}]})"),
              {"feature \"organ\" (#1)", "slice z=12.5 (#1)", "contour 2", "fewer than 3 distinct points"});
}

TEST(ContoursJson, NonFiniteValues) {
  // JSON cannot spell NaN or infinity; an overflowing number is rejected by the parser.
  expectError(doc(R"({"name":"organ","slices":[{"z":3,"contours":[[[0,0],[1e999,0],[0,1]]]}]})"), {"not valid JSON", "1e999"});
  // Other readers can produce them: validation names the place.
  ContourSet set;
  set.source = "model";
  set.features.push_back(Feature{"organ", std::nullopt, {FeatureSlice{3, {Contour{{{0, 0}, {1, 0}, {0, 1}}}}}}});
  ContourSet infZ = set;
  infZ.features[0].slices.push_back(FeatureSlice{-std::numeric_limits<double>::infinity(), {}});
  auto r = validateAndNormalize(infZ);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().code, Errc::InvalidInput);
  EXPECT_EQ(r.error().message, "model: feature \"organ\" (#0), slice #1: non-finite z");
  ContourSet infX = set;
  infX.features[0].slices[0].contours[0].points[2].x = std::numeric_limits<double>::infinity();
  r = validateAndNormalize(infX);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().message, "model: feature \"organ\" (#0), slice z=3 (#0), contour 0, point 2: non-finite coordinate");
}

TEST(ContoursJson, NamesAndColours) {
  expectError(doc(R"({"name":"skin","slices":[{"z":0,"contours":[[[0,0],[1,0],[0,1]]]}]})"),
              {"feature \"skin\" (#1)", "duplicate name", "#0"});
  expectError(doc(R"({"name":"","slices":[{"z":0,"contours":[[[0,0],[1,0],[0,1]]]}]})"), {"feature #1", "empty name"});
  // A NUL would end the name early in the XML and DICOM writers' readers (VTK crashed on it).
  expectError(doc(R"({"name":"le\u0000ft","slices":[{"z":0,"contours":[[[0,0],[1,0],[0,1]]]}]})"),
              {"feature #1", "NUL character in its name"});
  expectError(doc(R"({"name":"organ","slices":[{"z":0,"contours":[[[0,0],[1,0],[0,1]]]}]})", R"(,"units":"m\u0000m")"),
              {"units hold a NUL character"});
  expectError(doc(R"({"name":"organ","color":[0,256,0],"slices":[]})"), {"feature \"organ\" (#1)", "color", "0..255"});
  expectError(doc(R"({"name":"organ","color":[0,-1,0],"slices":[]})"), {"feature \"organ\" (#1)", "color", "0..255"});
  expectError(doc(R"({"name":"organ","color":[0,1],"slices":[]})"), {"feature \"organ\" (#1)", "color"});
  expectError(doc(R"({"name":"organ","color":[0,1.5,2],"slices":[]})"), {"feature \"organ\" (#1)", "color"});
  expectError(doc(R"({"name":"organ","color":"red","slices":[]})"), {"feature \"organ\" (#1)", "color"});
}

TEST(ContoursJson, OrderErrors) {
  const std::string organ = R"({"name":"organ","slices":[{"z":0,"contours":[[[0,0],[1,0],[0,1]]]}]})";
  EXPECT_TRUE(parseContoursJson(doc(organ, R"(,"order":["organ","skin"])"), "ok.json"));
  expectError(doc(organ, R"(,"order":["organ"])"), {"feature \"skin\" (#0)", "missing from order"});
  expectError(doc(organ, R"(,"order":["organ","skin","organ"])"), {"feature \"organ\" (#1)", "more than once"});
  expectError(doc(organ, R"(,"order":["organ","liver"])"), {"unknown feature \"liver\""});
  expectError(doc(organ, R"(,"order":["organ",3])"), {"order", "entry 1"});
  expectError(doc(organ, R"(,"order":[])"), {"missing from order"});
}

TEST(Validate, ModelLevelErrorsNameEverything) {
  ContourSet set;
  set.source = "phantom.json";
  for (int i = 0; i < 4; ++i)
    set.features.push_back(
        Feature{"f" + std::to_string(i), std::nullopt, {FeatureSlice{0, {Contour{{{0, 0}, {1, 0}, {0, 1}}}}}}});
  set.features[3].name = "rectum";
  for (int s = 1; s <= 4; ++s) set.features[3].slices.push_back(FeatureSlice{s * 2.5 + 2.5, {Contour{{{0, 0}, {1, 0}, {0, 1}}}}});
  ContourSet nan = set;
  nan.features[3].slices[4].contours.push_back(Contour{{{0, 0}, {std::nan(""), 0}, {0, 1}}});
  auto r = validateAndNormalize(nan);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().message,
            "phantom.json: feature \"rectum\" (#3), slice z=12.5 (#4), contour 1, point 1: non-finite coordinate");
  ContourSet few = set;
  few.features[3].slices[4].contours.push_back(Contour{{{0, 0}, {1, 1}}});
  few.features[3].slices[4].contours.push_back(Contour{{{0, 0}, {1, 1}, {0, 0}}});
  r = validateAndNormalize(few);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().message,
            "phantom.json: feature \"rectum\" (#3), slice z=12.5 (#4), contour 1: fewer than 3 distinct points");
  ContourSet back = set;  // a, b, a, b: four points, two distinct
  back.features[0].slices[0].contours[0].points = {{0, 0}, {1, 1}, {0, 0}, {1, 1}};
  r = validateAndNormalize(back);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().message, "phantom.json: feature \"f0\" (#0), slice z=0 (#0), contour 0: fewer than 3 distinct points");
  ContourSet ok = set;
  EXPECT_TRUE(validateAndNormalize(ok));
  ContourSet tooMany;
  tooMany.source = "big.json";
  tooMany.features.resize(kMaxFeatures + 1);
  r = validateAndNormalize(tooMany);
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("more than"), std::string::npos);
  ContourSet badOrder = set;
  badOrder.order = {0, 1, 2, 7};
  EXPECT_FALSE(validateAndNormalize(badOrder));
}

TEST(ContoursJson, MissingFileIsIo) {
  const auto r = readContoursJson("/nonexistent/dir/contours.json");
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().code, Errc::Io);
  EXPECT_NE(r.error().message.find("/nonexistent/dir/contours.json"), std::string::npos);
}

fs::path tempDir() {
  const fs::path dir =
      fs::temp_directory_path() / ("scansurf_json_test_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()));
  fs::create_directories(dir);
  return dir;
}

void expectSameModel(const ContourSet& a, const ContourSet& b) {
  EXPECT_EQ(a.units, b.units);
  EXPECT_EQ(a.order, b.order);
  ASSERT_EQ(a.features.size(), b.features.size());
  for (std::size_t f = 0; f < a.features.size(); ++f) {
    EXPECT_EQ(a.features[f].name, b.features[f].name);
    EXPECT_EQ(a.features[f].color, b.features[f].color);
    ASSERT_EQ(a.features[f].slices.size(), b.features[f].slices.size());
    for (std::size_t s = 0; s < a.features[f].slices.size(); ++s) {
      const auto& sa = a.features[f].slices[s];
      const auto& sb = b.features[f].slices[s];
      EXPECT_EQ(sa.z, sb.z);
      ASSERT_EQ(sa.contours.size(), sb.contours.size());
      for (std::size_t c = 0; c < sa.contours.size(); ++c) {
        ASSERT_EQ(sa.contours[c].points.size(), sb.contours[c].points.size());
        for (std::size_t p = 0; p < sa.contours[c].points.size(); ++p) {
          EXPECT_EQ(sa.contours[c].points[p].x, sb.contours[c].points[p].x);
          EXPECT_EQ(sa.contours[c].points[p].y, sb.contours[c].points[p].y);
        }
      }
    }
  }
}

TEST(ContoursJson, WriteReadRoundTripIsExact) {
  const fs::path dir = tempDir();
  for (ContourSet set : {sphereContours(7.3, 1.1, {0.1, -3.7}), torusContours(20, 5, 1.7), yBranchContours(),
                         nestedSpheresContours(), abuttingContours(), phantomContours()}) {
    set.units = "cm";
    if (set.features.size() == 2) set.order = {1, 0};
    ASSERT_TRUE(validateAndNormalize(set)) << set.source;
    const fs::path path = dir / (set.source + ".json");
    const auto w = writeContoursJson(set, path);
    ASSERT_TRUE(w) << w.error().message;
    const auto r = readContoursJson(path);
    ASSERT_TRUE(r) << r.error().message;
    EXPECT_EQ(r->source, path.string());
    expectSameModel(set, *r);
    // Writing twice gives the same bytes, and no temporary file is left behind.
    EXPECT_EQ(formatContoursJson(*r), formatContoursJson(set));
  }
  for (const auto& entry : fs::directory_iterator(dir)) EXPECT_EQ(entry.path().extension(), ".json") << entry.path();
  fs::remove_all(dir);
}

TEST(ContoursJson, WriteRefusesNonFiniteAndReportsIo) {
  ContourSet set = sphereContours(3, 1);
  set.features[0].slices[0].contours[0].points[0].x = std::numeric_limits<double>::infinity();
  const fs::path dir = tempDir();
  const auto w = writeContoursJson(set, dir / "inf.json");
  ASSERT_FALSE(w);
  EXPECT_EQ(w.error().code, Errc::InvalidArgument);
  EXPECT_FALSE(fs::exists(dir / "inf.json"));
  const auto io = writeContoursJson(sphereContours(3, 1), "/nonexistent/dir/out.json");
  ASSERT_FALSE(io);
  EXPECT_EQ(io.error().code, Errc::Io);
  fs::remove_all(dir);
}

TEST(ContoursJson, BundledPhantomParsesAndValidates) {
  const fs::path path = fs::path(SCANSURF_EXAMPLES) / "phantom.json";
  const auto r = readContoursJson(path);
  ASSERT_TRUE(r) << r.error().message;
  ASSERT_EQ(r->features.size(), 6u);
  EXPECT_EQ(r->features[0].name, "BODY");
  EXPECT_LT(fs::file_size(path), 400u * 1024u);
  // The bundled file is what the generator makes today.
  ContourSet generated = phantomContours();
  ASSERT_TRUE(validateAndNormalize(generated));
  expectSameModel(generated, *r);
  // Every contour is large enough for the default grid, and the nesting is as designed.
  const auto grid = makeGrid(*r, GridOptions{});
  ASSERT_TRUE(grid);
  EXPECT_TRUE(findUncoveredContours(*r, *grid).empty());
  EXPECT_EQ(computeNesting(*r).parent, (std::vector<int>{-1, 0, 0, 1, 0, 0}));
}

// Coordinates of 1e300 or z at 1e308 (issue 15): refused, naming feature, slice and point.
TEST(ContoursJson, AstronomicalCoordinatesAreRefused) {
  const auto far = parseContoursJson(
      R"({"version": 1, "features": [{"name": "a", "slices": [{"z": 0, "contours": [[[0, 0], [1e300, 0], [0, 1]]]}]}]})",
      "far.json");
  ASSERT_FALSE(far);
  EXPECT_NE(far.error().message.find("feature \"a\""), std::string::npos) << far.error().message;
  EXPECT_NE(far.error().message.find("point 1"), std::string::npos) << far.error().message;
  EXPECT_NE(far.error().message.find("beyond"), std::string::npos) << far.error().message;
  const auto high = parseContoursJson(
      R"({"version": 1, "features": [{"name": "a", "slices": [{"z": 1e308, "contours": [[[0, 0], [1, 0], [0, 1]]]}]}]})",
      "high.json");
  ASSERT_FALSE(high);
  EXPECT_NE(high.error().message.find("z = 1e+308"), std::string::npos) << high.error().message;
}

// Hostile nesting (issue 15): 200 000 levels inside "version" or a point is refused while
// parsing, with a message, never a stack overflow; quoted values are cut short.
TEST(ContoursJson, DeepNestingIsRefusedNotFatal) {
  const std::string deep = std::string(200000, '[') + std::string(200000, ']');
  for (const std::string& doc : {"{\"version\": " + deep + ", \"features\": []}",
                                 "{\"version\": 1, \"features\": [{\"name\": \"a\", \"slices\": [{\"z\": 0, "
                                 "\"contours\": [[[0, 0], [1, 0], " +
                                     deep + "]]}]}]}"}) {
    const auto r = parseContoursJson(doc, "deep.json");
    ASSERT_FALSE(r);
    EXPECT_EQ(r.error().code, Errc::InvalidInput);
    EXPECT_NE(r.error().message.find("nested more than 64 deep"), std::string::npos) << r.error().message.substr(0, 200);
  }
  std::string wide = "[1";
  for (int i = 0; i < 50000; ++i) wide += ",1";
  wide += "]";
  const auto r = parseContoursJson("{\"version\": " + wide + ", \"features\": []}", "wide.json");
  ASSERT_FALSE(r);
  EXPECT_LT(r.error().message.size(), 200u) << "the value is quoted short";
}

}  // namespace
}  // namespace scansurf

namespace scansurf {
namespace {

// A contour repeated point for point on its slice (an exporter's duplicate, from any start
// point and in either direction) is dropped with a warning naming the place: the two copies
// would cancel by the even-odd rule and empty the feature there. A different contour stays.
// Planes are merged within a thousandth of the median spacing of each feature's own slices,
// across features, onto the lower plane's exact z, with a warning when distinct positions
// merge: 0.00005 mm sections stay apart, copies of a plane 1e-9 apart join.
TEST(Validation, SlicePlanesMergeRelativeToTheSpacing) {
  const Contour square{{{0, 0}, {4, 0}, {4, 4}, {0, 4}}};
  auto stack = [&](std::vector<double> zs) {
    Feature f{"organ", std::nullopt, {}};
    for (double z : zs) f.slices.push_back(FeatureSlice{z, {square}});
    return f;
  };
  ContourSet fine;
  fine.source = "fine";
  fine.features.push_back(stack({0, 0.00005, 0.0001, 0.00015}));
  ASSERT_TRUE(validateAndNormalize(fine));
  EXPECT_EQ(fine.features[0].slices.size(), 4u);
  EXPECT_NEAR(fine.planeTolerance, 5e-8, 1e-15);
  EXPECT_TRUE(fine.warnings.empty());
  GridOptions o;
  o.voxelSize = 1;
  const auto g = makeGrid(fine, o);
  ASSERT_TRUE(g) << g.error().message;
  EXPECT_EQ(g->nz, 6);

  ContourSet close;
  close.source = "close";
  close.features.push_back(stack({0, 1e-9, 2, 4, 6}));
  close.features.push_back(stack({2.0015, 4.5}));
  close.features[1].name = "other";
  ASSERT_TRUE(validateAndNormalize(close));
  EXPECT_DOUBLE_EQ(close.planeTolerance, 2e-3);
  ASSERT_EQ(close.features[0].slices.size(), 4u);
  EXPECT_EQ(close.features[0].slices[0].contours.size(), 1u) << "the copies meet on one plane; one is kept";
  EXPECT_EQ(close.features[1].slices[0].z, 2.0) << "moved onto the lower plane exactly";
  ASSERT_EQ(close.warnings.size(), 2u) << "the merge, then the copies dropped";
  EXPECT_EQ(close.warnings[0],
            "close: 2 slice position(s) within 0.002 mm (a thousandth of the median slice spacing) of a "
            "lower one were merged into its plane, e.g. z=1e-09 into z=0");
}

TEST(Validation, RepeatedContoursOfASliceAreDroppedWithAWarning) {
  const Contour square{{{0, 0}, {4, 0}, {4, 4}, {0, 4}}};
  const Contour rotatedReversed{{{4, 4}, {4, 0}, {0, 0}, {0, 4}}};
  const Contour hole{{{1, 1}, {3, 1}, {3, 3}, {1, 3}}};
  ContourSet set;
  set.source = "dup";
  set.features.push_back(
      Feature{"organ", std::nullopt, {FeatureSlice{2, {square, hole, rotatedReversed}}, FeatureSlice{4, {square}}}});
  ASSERT_TRUE(validateAndNormalize(set));
  ASSERT_EQ(set.features[0].slices[0].contours.size(), 2u) << "the square and its hole";
  ASSERT_EQ(set.warnings.size(), 1u);
  EXPECT_EQ(set.warnings[0],
            "dup: feature \"organ\" (#0), slice z=2 (#0): contour 2 repeats an earlier contour of the slice point "
            "for point; the copy is dropped (two copies would cancel by the even-odd rule)");
  EXPECT_EQ(set.features[0].slices[1].contours.size(), 1u);
}

}  // namespace
}  // namespace scansurf

namespace scansurf {
namespace {

// A grid finer than float32 vertices resolve at its coordinates (1/16 of a step) is refused, saying why:
// contours 1e-200 units wide, or 0.25-unit pixels 9.9e6 units from the origin.
TEST(GridPrecision, StepsFinerThanFloat32ResolvesAreRefused) {
  const auto squareAt = [](double x, double size) {
    ContourSet set;
    set.source = "far";
    const Contour c{{{x, 0}, {x + size, 0}, {x + size, size}, {x, size}}};
    set.features.push_back(Feature{"f", std::nullopt, {FeatureSlice{0, {c}}, FeatureSlice{1, {c}}}});
    return set;
  };
  GridOptions fine;
  fine.voxelSize = 0.25;
  auto far = makeGrid(squareAt(9.9e6, 10), fine);
  ASSERT_FALSE(far);
  EXPECT_EQ(far.error().code, Errc::InvalidInput);
  EXPECT_NE(far.error().message.find("finer than float32 surface vertices resolve"), std::string::npos) << far.error().message;
  EXPECT_FALSE(makeGrid(squareAt(0, 1e-200), {}));
  EXPECT_TRUE(makeGrid(squareAt(0, 10), fine));
  EXPECT_TRUE(makeGrid(squareAt(1e3, 10), fine)) << "0.25 units at 1000 units from the origin is resolved";
}

}  // namespace
}  // namespace scansurf

namespace scansurf {
namespace {

// A reference lattice far finer than the contours (a CT of 0.001 mm pixels under a 100 mm
// structure) is the data's fault: Errc::InvalidInput, naming the file.
TEST(GridPrecision, AReferenceLatticeTooFineNamesTheFile) {
  ContourSet set;
  set.source = "rt.dcm";
  const Contour c{{{0, 0}, {100, 0}, {100, 100}, {0, 100}}};
  set.features.push_back(Feature{"body", std::nullopt, {FeatureSlice{0, {c}}}});
  GridOptions o;
  GridReference ref;
  ref.spacingX = ref.spacingY = 0.001;
  ref.nx = ref.ny = 10;
  ref.sliceZ = {0};
  o.reference = ref;
  auto grid = makeGrid(set, o);
  ASSERT_FALSE(grid);
  EXPECT_EQ(grid.error().code, Errc::InvalidInput);
  EXPECT_EQ(grid.error().message.rfind("rt.dcm: on the reference lattice (0.001 mm pixels)", 0), 0u) << grid.error().message;
}

}  // namespace
}  // namespace scansurf
