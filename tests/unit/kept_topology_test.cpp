// Between two planes every label keeps the slab rule's topology (kept_topology.h): what the
// interpolation invents (islands, bubbles, handles) goes; caps, shifts and branchings stay.
#include "geometry/interpolation/kept_topology.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace scansurf {
namespace {

constexpr int kN = 5;

// Words of the pair's layers m = 0 .. factor-1 from pictures of kN rows of kN characters ('.'
// background, digits labels), each with clearance 7.
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

Label labelAt(const std::vector<std::uint32_t>& words, int m, int x, int y) {
  return static_cast<Label>(words[static_cast<std::size_t>(m * kN * kN + y * kN + x)] & 0xFFFFu);
}

// The labels of the pair's lower plane: its words' first layer.
std::vector<Label> planeAOf(const std::vector<std::uint32_t>& words) {
  std::vector<Label> labels;
  for (int i = 0; i < kN * kN; ++i) labels.push_back(static_cast<Label>(words[static_cast<std::size_t>(i)] & 0xFFFFu));
  return labels;
}

const std::vector<std::string> kBlock = {".....", ".111.", ".111.", ".111.", "....."};
const std::vector<std::string> kEmpty = {".....", ".....", ".....", ".....", "....."};

TEST(KeptTopology, WhatMatchesTheSlabRuleStays) {
  std::vector<std::uint32_t> words = wordsOf({kBlock, kBlock, kBlock});
  const std::vector<std::uint32_t> before = words;
  EXPECT_EQ(keepSlabTopology(words.data(), planeAOf(words).data(), labelsOf(kBlock).data(), kN, kN, 3, 16), 0u);
  EXPECT_EQ(words, before);
}

TEST(KeptTopology, ASpeckOfAnotherLabelGoes) {
  std::vector<std::uint32_t> words = wordsOf({kBlock, kBlock, {".....", ".111.", ".121.", ".111.", "....."}});
  EXPECT_EQ(keepSlabTopology(words.data(), planeAOf(words).data(), labelsOf(kBlock).data(), kN, kN, 3, 16), 1u);
  EXPECT_EQ(words[2 * 25 + 2 * 5 + 2], 1u | (16u << 16));
}

TEST(KeptTopology, ABubbleOfBackgroundIsFilled) {
  std::vector<std::uint32_t> words = wordsOf({kBlock, {".....", ".111.", ".1.1.", ".111.", "....."}});
  EXPECT_EQ(keepSlabTopology(words.data(), planeAOf(words).data(), labelsOf(kBlock).data(), kN, kN, 2, 16), 1u);
  EXPECT_EQ(labelAt(words, 1, 2, 2), 1);
}

TEST(KeptTopology, AHandleThroughTheStructureIsClosed) {
  // A tunnel of background through the block from one side to the other, between the planes.
  std::vector<std::uint32_t> words = wordsOf({kBlock, kBlock, {".....", ".111.", ".....", ".111.", "....."}, kBlock});
  const std::size_t kept = keepSlabTopology(words.data(), planeAOf(words).data(), labelsOf(kBlock).data(), kN, kN, 4, 16);
  EXPECT_GE(kept, 1u);  // at least one voxel of the tunnel keeps the block's label
  int open = 0;
  for (int x = 1; x <= 3; ++x) open += labelAt(words, 2, x, 2) == 0;
  EXPECT_LT(open, 3);
}

TEST(KeptTopology, ACapShrinkingTowardsItsEndStays) {
  std::vector<std::uint32_t> words = wordsOf({{".....", ".222.", ".222.", ".222.", "....."},
                                              {".....", ".222.", ".222.", ".222.", "....."},
                                              {".....", ".....", "..2..", ".....", "....."}});
  const std::vector<std::uint32_t> before = words;
  EXPECT_EQ(keepSlabTopology(words.data(), planeAOf(words).data(), labelsOf(kEmpty).data(), kN, kN, 3, 16), 0u);
  EXPECT_EQ(words, before);
}

TEST(KeptTopology, AStructureShiftingAlongTheCellDiagonalStaysOnePart) {
  std::vector<std::uint32_t> words = wordsOf({{"3....", ".....", ".....", ".....", "....."},
                                              {".....", ".3...", ".....", ".....", "....."},
                                              {".....", ".....", "..3..", ".....", "....."},
                                              {".....", ".....", ".....", "...3.", "....."}});
  const std::vector<std::uint32_t> before = words;
  EXPECT_EQ(keepSlabTopology(words.data(), planeAOf(words).data(), labelsOf({".....", ".....", ".....", ".....", "....3"}).data(),
                             kN, kN, 4, 16),
            0u);
  EXPECT_EQ(words, before);
}

TEST(KeptTopology, ABranchingThePlanesImplyStays) {
  // One part on A, two on B: the split may happen anywhere between them.
  const std::vector<std::string> one = {".....", ".111.", ".111.", ".111.", "....."};
  const std::vector<std::string> two = {".....", ".1.1.", ".1.1.", ".1.1.", "....."};
  std::vector<std::uint32_t> words = wordsOf({one, one, two, two});
  const std::vector<std::uint32_t> before = words;
  EXPECT_EQ(keepSlabTopology(words.data(), planeAOf(words).data(), labelsOf(two).data(), kN, kN, 4, 16), 0u);
  EXPECT_EQ(words, before);
}

TEST(KeptTopology, NoLayersBetweenNothingToDo) {
  std::vector<std::uint32_t> words = wordsOf({kBlock});
  EXPECT_EQ(keepSlabTopology(words.data(), planeAOf(words).data(), labelsOf(kBlock).data(), kN, kN, 1, 16), 0u);
}

}  // namespace
}  // namespace scansurf
