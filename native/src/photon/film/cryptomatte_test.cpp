#include "photon/film/cryptomatte.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <vector>

namespace photon {
namespace cryptomatte_test {
namespace {

float id_from_bits(uint32_t u) {
  float f;
  std::memcpy(&f, &u, sizeof f);
  return f;
}

TEST(Cryptomatte, LayersHoldTwoRanksEach) {
  EXPECT_EQ(cryptomatte_layers(6), 3);
  EXPECT_EQ(cryptomatte_layers(5), 3);
  EXPECT_EQ(cryptomatte_layers(2), 1);
  EXPECT_EQ(cryptomatte_layers(0), 0);
}

// Blender's IDs for the Cornell box's 'Floor' and 'ShortBox' (MurmurHash3 of the names).
const float kFloor = id_from_bits(0x6a2fb16e);
const float kShortBox = id_from_bits(0x6bba7a62);
const float kBack = id_from_bits(0x5050d6fb);

TEST(Cryptomatte, RanksIdsByTheirShareOfTheSamples) {
  CryptomatteRow row(2, 6);
  // Pixel 0: 5 samples on the short box, 2 on the floor, 1 on the background (not added).
  for (int i = 0; i < 2; ++i) row.add(0, kFloor, 1.0f);
  for (int i = 0; i < 5; ++i) row.add(0, kShortBox, 1.0f);
  std::vector<float> out(12, -1.0f);
  row.write(0, 8, out.data());
  EXPECT_EQ(std::memcmp(&out[0], &kShortBox, 4), 0);
  EXPECT_FLOAT_EQ(out[1], 5.0f / 8.0f);
  EXPECT_EQ(std::memcmp(&out[2], &kFloor, 4), 0);
  EXPECT_FLOAT_EQ(out[3], 2.0f / 8.0f);
  for (int i = 4; i < 12; ++i) EXPECT_EQ(out[i], 0.0f) << i;
  // Pixel 1 saw nothing: all zero.
  row.write(1, 8, out.data());
  for (float v : out) EXPECT_EQ(v, 0.0f);
}

TEST(Cryptomatte, KeepsOnlyTheDeepestRanksAndBreaksTiesByIdBits) {
  CryptomatteRow row(1, 2);
  row.add(0, kBack, 1.0f);
  row.add(0, kFloor, 1.0f);
  row.add(0, kShortBox, 2.0f);
  std::vector<float> out(4);
  row.write(0, 4, out.data());
  EXPECT_EQ(std::memcmp(&out[0], &kShortBox, 4), 0);
  EXPECT_FLOAT_EQ(out[1], 0.5f);
  // Back (0x5050d6fb) and Floor (0x6a2fb16e) tie: the lower bits win, so the order of the
  // samples cannot change the image.
  EXPECT_EQ(std::memcmp(&out[2], &kBack, 4), 0);
  EXPECT_FLOAT_EQ(out[3], 0.25f);
  CryptomatteRow reversed(1, 2);
  reversed.add(0, kShortBox, 2.0f);
  reversed.add(0, kFloor, 1.0f);
  reversed.add(0, kBack, 1.0f);
  std::vector<float> again(4);
  reversed.write(0, 4, again.data());
  EXPECT_EQ(std::memcmp(out.data(), again.data(), 16), 0);
}

TEST(Cryptomatte, ClearForgetsTheRowAndBadWeightsAreIgnored) {
  CryptomatteRow row(1, 2);
  row.add(0, kFloor, 1.0f);
  row.add(0, kBack, -1.0f);
  row.add(0, kBack, std::nanf(""));
  row.add(5, kBack, 1.0f);  // no such pixel
  std::vector<float> out(4);
  row.write(0, 1, out.data());
  EXPECT_FLOAT_EQ(out[1], 1.0f);
  EXPECT_EQ(out[2], 0.0f);
  row.clear();
  row.write(0, 1, out.data());
  EXPECT_EQ(out[0], 0.0f);
  EXPECT_EQ(out[1], 0.0f);
}

}  // namespace
}  // namespace cryptomatte_test
}  // namespace photon
