// Parts of a label between two planes that reach neither are relabelled (invented_islands.h);
// what the planes imply stays: caps, shifts, branches.
#include "geometry/interpolation/invented_islands.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace scansurf {
namespace {

constexpr int kN = 5;

// Words of `factor` layers from pictures of kN rows of kN characters ('.' background, digits
// labels), each with clearance 7.
std::vector<std::uint32_t> wordsOf(const std::vector<std::vector<std::string>>& layers) {
  std::vector<std::uint32_t> words;
  for (const auto& layer : layers)
    for (const std::string& row : layer)
      for (char c : row) words.push_back((c == '.' ? 0u : static_cast<std::uint32_t>(c - '0')) | (7u << 16));
  return words;
}

std::vector<Label> labelsOf(const std::vector<std::string>& layer) {
  std::vector<Label> labels;
  for (const std::string& row : layer)
    for (char c : row) labels.push_back(c == '.' ? 0 : static_cast<Label>(c - '0'));
  return labels;
}

const std::vector<std::string> kBlock = {".....", ".111.", ".111.", ".111.", "....."};

TEST(InventedIslands, ASpeckOfAnotherLabelTakesTheLabelAroundIt) {
  std::vector<std::uint32_t> words = wordsOf({kBlock, kBlock, {".....", ".111.", ".121.", ".111.", "....."}});
  const std::vector<Label> b = labelsOf(kBlock);
  EXPECT_EQ(removeInventedIslands(words.data(), b.data(), kN, kN, 3, 16), 1u);
  EXPECT_EQ(words[2 * 25 + 2 * 5 + 2], 1u | (16u << 16));
  EXPECT_EQ(removeInventedIslands(words.data(), b.data(), kN, kN, 3, 16), 0u);
}

TEST(InventedIslands, ABubbleOfBackgroundIsFilled) {
  std::vector<std::uint32_t> words = wordsOf({kBlock, {".....", ".111.", ".1.1.", ".111.", "....."}});
  const std::vector<Label> b = labelsOf(kBlock);
  EXPECT_EQ(removeInventedIslands(words.data(), b.data(), kN, kN, 2, 16), 1u);
  EXPECT_EQ(words[25 + 2 * 5 + 2] & 0xFFFFu, 1u);
}

TEST(InventedIslands, ACapReachingItsPlaneStays) {
  // Label 2 on plane A only, shrinking to a point between the planes.
  std::vector<std::uint32_t> words =
      wordsOf({{".....", ".222.", ".222.", ".222.", "....."}, {".....", ".....", "..2..", ".....", "....."}});
  const std::vector<Label> b = labelsOf({".....", ".....", ".....", ".....", "....."});
  const std::vector<std::uint32_t> before = words;
  EXPECT_EQ(removeInventedIslands(words.data(), b.data(), kN, kN, 2, 16), 0u);
  EXPECT_EQ(words, before);
}

TEST(InventedIslands, AStructureShiftingDiagonallyStaysOnePart) {
  // One voxel of label 3 moving a pixel diagonally per layer from A to B: 26-adjacent throughout.
  std::vector<std::uint32_t> words = wordsOf({{"3....", ".....", ".....", ".....", "....."},
                                              {".....", ".3...", ".....", ".....", "....."},
                                              {".....", ".....", "..3..", ".....", "....."},
                                              {".....", ".....", ".....", "...3.", "....."}});
  const std::vector<Label> b = labelsOf({".....", ".....", ".....", ".....", "....3"});
  const std::vector<std::uint32_t> before = words;
  EXPECT_EQ(removeInventedIslands(words.data(), b.data(), kN, kN, 4, 16), 0u);
  EXPECT_EQ(words, before);
}

TEST(InventedIslands, NoLayersBetweenNothingToDo) {
  std::vector<std::uint32_t> words = wordsOf({kBlock});
  const std::vector<Label> b = labelsOf(kBlock);
  EXPECT_EQ(removeInventedIslands(words.data(), b.data(), kN, kN, 1, 16), 0u);
}

}  // namespace
}  // namespace scansurf
