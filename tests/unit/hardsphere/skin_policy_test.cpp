// The hard-sphere skin policy (hardsphere/skin_policy.hpp) against the whole-run times it was
// fitted to and checked on (bench/RESULTS.md, "Hard-sphere neighbour skin": each bed run from
// the same checkpoint with the long skin, 8 steps, and the short one, 2 steps; best of three
// interleaved runs on one thread). The list sizes and event rates are those of the runs'
// checkpoints and series.csv:
//  - validation_40k at t = 0.4 s (2-D, settled bed): E(8) = 24.8, E(2) = 5.6 entries per particle,
//    0.19 events per particle per step, the long list serving 4 steps: the short skin was 1.7x
//    faster;
//  - segregation_beetstra at t = 0.13 s (3-D, the mixed bed falling): E(8) = 7.4, E(2) = 5.0,
//    0.33 events, the long list serving 5 steps: the long skin was 1.5x faster;
//  - single_bubble at t = 0.32 s (3-D, settling under the gas): E(8) = 38.1, E(2) = 9.6, 22 events
//    per particle per step, every list rebuilt after one step whatever its skin (the fastest
//    particles speed up): the short skin was 1.3x faster.
// The rule is a comparison of two estimated costs; each expectation below is the measured winner.
#include <gtest/gtest.h>

#include "hardsphere/skin_policy.hpp"

namespace fluidem::hardsphere {
namespace {

TEST(SkinPolicy, TheSettledTwoDimensionalBedTakesTheShortSkin) {
  const SkinProbe probe{100, 24.8, 5.6, 4};
  EXPECT_TRUE(short_skin_pays(probe, 0.19));
  EXPECT_EQ(skin_steps(probe, 101, 0.19), kShortSkinSteps);
}

TEST(SkinPolicy, TheFallingBedTakesTheLongSkin) {
  const SkinProbe probe{100, 7.4, 5.0, 5};
  EXPECT_FALSE(short_skin_pays(probe, 0.33));
  EXPECT_EQ(skin_steps(probe, 101, 0.33), kLongSkinSteps);
}

TEST(SkinPolicy, ABedWhoseListsLastOneStepTakesTheShortSkin) {
  // The long list served one step: it only costs more (any E(8) > E(2) decides), even with
  // few events.
  EXPECT_TRUE(short_skin_pays({100, 38.1, 9.6, 1}, 22.0));
  EXPECT_TRUE(short_skin_pays({100, 9.7, 9.6, 1}, 0.0));
  EXPECT_FALSE(short_skin_pays({100, 9.6, 9.6, 1}, 22.0)); // (equal costs: keep the long one)
}

TEST(SkinPolicy, WithoutAProbeOrAfterManyBuildsTheLongSkinProbesAgain) {
  const SkinProbe none;
  EXPECT_FALSE(short_skin_pays(none, 100.0));
  EXPECT_EQ(skin_steps(none, 0, 100.0), kLongSkinSteps);
  const SkinProbe probe{100, 24.8, 5.6, 4};
  EXPECT_EQ(skin_steps(probe, 100 + kProbeEvery - 1, 0.19), kShortSkinSteps);
  EXPECT_EQ(skin_steps(probe, 100 + kProbeEvery, 0.19), kLongSkinSteps);
}

TEST(SkinPolicy, AListStillServingCountsAsFourSteps) {
  // life = 0 (the probe's list has not been replaced yet): the nominal life of the long skin.
  EXPECT_EQ(short_skin_pays({100, 24.8, 5.6, 0}, 0.19), short_skin_pays({100, 24.8, 5.6, 4}, 0.19));
  EXPECT_EQ(short_skin_pays({100, 7.4, 5.0, 0}, 0.33), short_skin_pays({100, 7.4, 5.0, 4}, 0.33));
}

} // namespace
} // namespace fluidem::hardsphere
