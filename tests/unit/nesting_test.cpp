// computeNesting / isInside: containment, parents, order, determinism, scale.
#include "scansurf/nesting.h"

#include <gtest/gtest.h>

#include <chrono>

#include "support/shapes.h"

namespace scansurf {
namespace {

Contour square(double cx, double cy, double half) {
  return Contour{{{cx - half, cy - half}, {cx + half, cy - half}, {cx + half, cy + half}, {cx - half, cy + half}}};
}

Feature squareFeature(std::string name, double cx, double cy, double half, std::vector<double> zs = {0, 1}) {
  Feature f{std::move(name), std::nullopt, {}};
  for (double z : zs) f.slices.push_back(FeatureSlice{z, {square(cx, cy, half)}});
  return f;
}

ContourSet setOf(std::vector<Feature> features) {
  ContourSet set;
  set.source = "test";
  set.features = std::move(features);
  return set;
}

TEST(Nesting, NestedSpheres) {
  const Nesting n = computeNesting(nestedSpheresContours());
  EXPECT_EQ(n.parent, (std::vector<int>{-1, 0}));
  EXPECT_EQ(n.order, (std::vector<int>{1, 0}));
  EXPECT_FALSE(n.userOrder);
  EXPECT_TRUE(isInside(n, 1, 0));
  EXPECT_FALSE(isInside(n, 0, 1));
  EXPECT_FALSE(isInside(n, 0, 0));
}

TEST(Nesting, SiblingsKeepInputOrder) {
  const Nesting n =
      computeNesting(setOf({squareFeature("a", 0, 0, 1), squareFeature("b", 5, 0, 1), squareFeature("c", -5, 0, 1)}));
  EXPECT_EQ(n.parent, (std::vector<int>{-1, -1, -1}));
  EXPECT_EQ(n.order, (std::vector<int>{0, 1, 2}));
}

TEST(Nesting, AbuttingSiblingsAreNotNested) {
  const Nesting n = computeNesting(abuttingContours());
  EXPECT_EQ(n.parent, (std::vector<int>{-1, -1}));
  EXPECT_EQ(n.order, (std::vector<int>{0, 1}));
}

TEST(Nesting, ThreeLevels) {
  // Input outermost first; inner ones must come first in the order.
  const Nesting n = computeNesting(setOf({squareFeature("skin", 0, 0, 10), squareFeature("organ", 2, 0, 5),
                                          squareFeature("target", 3, 0, 1), squareFeature("other", -6, 0, 2)}));
  EXPECT_EQ(n.parent, (std::vector<int>{-1, 0, 1, 0}));
  EXPECT_EQ(n.order, (std::vector<int>{2, 1, 3, 0}));
  EXPECT_TRUE(isInside(n, 2, 0));
  EXPECT_TRUE(isInside(n, 2, 1));
  EXPECT_FALSE(isInside(n, 3, 1));
}

TEST(Nesting, NotContainedWhenMissingFromASlice) {
  // The inner square appears on a slice the outer one lacks.
  const Nesting n = computeNesting(setOf({squareFeature("outer", 0, 0, 10, {0, 1}), squareFeature("inner", 0, 0, 1, {0, 1, 2})}));
  EXPECT_EQ(n.parent, (std::vector<int>{-1, -1}));
}

TEST(Nesting, HoleIsOutside) {
  // A ring (square with a square hole) does not contain what sits in its hole.
  Feature ring{"ring", std::nullopt, {}};
  ring.slices.push_back(FeatureSlice{0, {square(0, 0, 10), square(0, 0, 5)}});
  Feature inHole = squareFeature("in_hole", 0, 0, 1, {0});
  Feature inRing = squareFeature("in_ring", 7, 0, 1, {0});
  const Nesting n = computeNesting(setOf({ring, inHole, inRing}));
  EXPECT_EQ(n.parent, (std::vector<int>{-1, -1, 0}));
}

TEST(Nesting, AFeatureFillingAHoleAlongItsOutlineIsOutside) {
  // Drawn on the ring's hole outline: every point on the ring's boundary, its region the hole.
  Feature ring{"ring", std::nullopt, {}};
  ring.slices.push_back(FeatureSlice{0, {square(0, 0, 10), square(0, 0, 5)}});
  Feature hole = squareFeature("hole", 0, 0, 5, {0});
  Feature alongTheOutside = squareFeature("inside along the outer outline", 0, 0, 10, {0});
  const Nesting n = computeNesting(setOf({ring, hole}));
  EXPECT_EQ(n.parent, (std::vector<int>{-1, -1}));
  // A feature drawn along the outer outline, its region the ring's and the hole's, is not
  // inside the ring either; one drawn inside along the outline is (the ring holds its side).
  Feature band{"band", std::nullopt, {}};
  band.slices.push_back(FeatureSlice{0, {square(0, 0, 10), square(0, 0, 8)}});
  EXPECT_EQ(computeNesting(setOf({ring, band})).parent, (std::vector<int>{-1, 0}));
  EXPECT_EQ(computeNesting(setOf({ring, alongTheOutside})).parent[0], 1);
}

TEST(Nesting, IdenticalFeaturesDoNotCycle) {
  const Nesting n =
      computeNesting(setOf({squareFeature("a", 0, 0, 3), squareFeature("b", 0, 0, 3), squareFeature("c", 0, 0, 3)}));
  // The lower index is the inner one.
  EXPECT_EQ(n.parent, (std::vector<int>{1, 2, -1}));
  EXPECT_EQ(n.order, (std::vector<int>{0, 1, 2}));
  EXPECT_TRUE(isInside(n, 0, 2));
  EXPECT_FALSE(isInside(n, 2, 0));
}

TEST(Nesting, SmallestContainerIsParent) {
  const Nesting n =
      computeNesting(setOf({squareFeature("small", 0, 0, 1), squareFeature("big", 0, 0, 9), squareFeature("mid", 0, 0, 4)}));
  EXPECT_EQ(n.parent, (std::vector<int>{2, -1, 1}));
  EXPECT_EQ(n.order, (std::vector<int>{0, 2, 1}));
}

TEST(Nesting, UserOrderIsKeptParentsStillComputed) {
  ContourSet set = nestedSpheresContours();
  set.order = {0, 1};  // deliberately outer first
  const Nesting n = computeNesting(set);
  EXPECT_TRUE(n.userOrder);
  EXPECT_EQ(n.order, (std::vector<int>{0, 1}));
  EXPECT_EQ(n.parent, (std::vector<int>{-1, 0}));
}

TEST(Nesting, Phantom) {
  const ContourSet set = phantomContours();
  // BODY, prostate, rectum, target, vessel, vertebra
  const Nesting n = computeNesting(set);
  EXPECT_EQ(n.parent, (std::vector<int>{-1, 0, 0, 1, 0, 0}));
  EXPECT_EQ(n.order, (std::vector<int>{3, 1, 2, 4, 5, 0}));
}

TEST(Nesting, DeterministicAndOrderIsAPermutation) {
  ShapeRng rng(3);
  std::vector<Feature> features;
  for (int i = 0; i < 60; ++i) {
    // std::string("f"), not "f": GCC 12 warns -Wrestrict in error on "f" + std::string here (GCC bug 105329).
    Feature f{std::string("f") + std::to_string(i), std::nullopt, {}};
    const Point2 c{rng.uniform(0, 50), rng.uniform(0, 50)};
    const double r = rng.uniform(1, 15);
    for (int z = 0; z < 3; ++z) f.slices.push_back(FeatureSlice{double(z), {randomPolygon(rng, c, r * 0.8, r, 10)}});
    features.push_back(f);
  }
  const ContourSet set = setOf(features);
  const Nesting a = computeNesting(set);
  const Nesting b = computeNesting(set);
  EXPECT_EQ(a.order, b.order);
  EXPECT_EQ(a.parent, b.parent);
  std::vector<int> sorted = a.order;
  std::sort(sorted.begin(), sorted.end());
  for (int i = 0; i < 60; ++i) EXPECT_EQ(sorted[i], i);
  // Every feature comes before its parent; parent links are acyclic.
  std::vector<int> position(60);
  for (int i = 0; i < 60; ++i) position[a.order[i]] = i;
  for (int f = 0; f < 60; ++f) {
    if (a.parent[f] >= 0) {
      EXPECT_LT(position[f], position[a.parent[f]]);
    }
    EXPECT_FALSE(isInside(a, f, f));
  }
}

TEST(Nesting, TwoThousandFeaturesRunFast) {
  // A 40 x 50 grid of small squares inside one big body, each with a nested dot.
  std::vector<Feature> features;
  features.push_back(squareFeature("body", 500, 500, 600, {0, 1, 2}));
  for (int i = 0; i < 1998 / 2; ++i) {
    const double cx = (i % 40) * 25, cy = (i / 40) * 25;
    features.push_back(squareFeature("organ" + std::to_string(i), cx, cy, 10, {0, 1, 2}));
    features.push_back(squareFeature("dot" + std::to_string(i), cx, cy, 2, {1}));
  }
  ASSERT_EQ(features.size(), 1999u);
  features.push_back(squareFeature("last", 2000, 2000, 1, {0}));
  const ContourSet set = setOf(std::move(features));
  const auto start = std::chrono::steady_clock::now();
  const Nesting n = computeNesting(set);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_LT(seconds, 5.0);
  EXPECT_EQ(n.parent[1], 0);
  EXPECT_EQ(n.parent[2], 1);
  EXPECT_EQ(n.parent[1999], -1);
  EXPECT_EQ(n.order.front(), 2);
  EXPECT_EQ(n.order[1998], 0);  // depth 0, then input order
  EXPECT_EQ(n.order.back(), 1999);
}

// Issue 15: 2000 concentric squares, each inside the next: a chain 2000 deep. Containment is
// found smallest container first and closed under transitivity, so this takes one polygon
// test per feature, not one per pair (minutes before); the chain and the order are exact.
TEST(Nesting, ChainTwoThousandDeep) {
  constexpr int kDepth = 2000;
  std::vector<Feature> features;
  for (int i = 0; i < kDepth; ++i) features.push_back(squareFeature("ring" + std::to_string(i), 0, 0, 1 + i, {0, 1}));
  const Nesting n = computeNesting(setOf(std::move(features)));
  for (int i = 0; i + 1 < kDepth; ++i) ASSERT_EQ(n.parent[static_cast<std::size_t>(i)], i + 1) << i;
  EXPECT_EQ(n.parent.back(), -1);
  for (int i = 0; i < kDepth; ++i) EXPECT_EQ(n.order[static_cast<std::size_t>(i)], i);
  EXPECT_TRUE(isInside(n, 0, kDepth - 1));
}

}  // namespace
}  // namespace scansurf
