// The folded step (Simulation::step, integrate/simulation.cpp; integrate/drift_bound.hpp): when
// the last step bounds this one's drift within half the neighbour list's skin, the integrator's
// pass over the particles (the pending second half kick, its dissipation term, the first half
// kick, the drift, the packing of the contact loop's view) runs slab by slab inside the contact
// loop instead of before it. The reference is the integrator with the separate pass
// (set_folded_integration(false)), which decides its rebuilds after the drift, exactly:
//  (a) 600 particles in a closed box (below the threading threshold: the contact loop's single
//      batch), Hertz contacts with tangential history and rolling springs, random velocities of
//      0.8 m/s under gravity, 400 steps: positions, velocities, angular velocities, contact
//      forces and torques bitwise those of the separate pass, the same number of list builds
//      (a fold that skipped a due rebuild would change it), and the dissipated energy equal to
//      1e-12 of its value (summed per slab instead of per 512 particles). Most steps fold, but
//      not all: the steps near a rebuild and after the undeferred ones do not.
//  (b) 6000 particles (the threaded contact loop, pairs of slabs), linear springs, with the
//      collision record on (the per-slab batches): as (a), and the last step's record equal;
//      one, two and three threads give bitwise the same particles and dissipated energy.
//  (c) 40000 particles (groups of many slabs, each thread's slabs prepared in order): as (a)
//      with one and two threads.
//  (d) periodic x and y (the drift wraps the centres): as (a); a body-force field: no step folds
//      (the plain kick only; nor with gas forces, the same condition in Simulation::step).
//  (e) DriftBound: the bound's arithmetic against hand-computed values.
//  (f) Only beds with at least Simulation::fold_pairs_per_particle() neighbour-list pairs per
//      particle fold (3 by default; the tests above lower it, their beds being sparser).
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "../../common/fold_threshold.hpp"
#include "../../common/random_bed.hpp"
#include "integrate/drift_bound.hpp"
#include "integrate/simulation.hpp"
#include "io/case_reader.hpp"

namespace fluidem {
namespace {

struct Outcome {
  std::vector<double> q; // x y z vx vy vz wx wy wz per particle, then the contact sums
  std::vector<ContactSample> record;
  double dissipated = 0.0;
  long builds = 0, folded = 0;
  double pairs_per_particle = 0.0; // at the end
};

// min_pairs: Simulation::fold_pairs_per_particle for the run (these beds are sparser than the
// default's 3 pairs per particle; 0: every step that may fold does).
Outcome run(const std::string& text, long steps, bool fold, int threads = 1,
            double min_pairs = 0.0) {
  const test::FoldThreshold threshold(min_pairs);
  const int saved = omp_get_max_threads();
  omp_set_num_threads(threads);
  Simulation sim(read_case_string(text, "folded.toml"));
  sim.set_folded_integration(fold);
  sim.advance(steps);
  omp_set_num_threads(saved);
  const ParticleStore& p = sim.particles();
  Outcome r;
  for (std::size_t i = 0; i < p.size(); ++i)
    r.q.insert(r.q.end(),
               {p.x[i], p.y[i], p.z[i], p.vx[i], p.vy[i], p.vz[i], p.wx[i], p.wy[i], p.wz[i]});
  r.q.insert(r.q.end(), sim.contact_sums().begin(), sim.contact_sums().end());
  r.record = sim.contact_record().samples;
  r.dissipated = sim.dissipated_energy();
  r.builds = sim.neighbour_builds();
  r.folded = sim.folded_steps();
  r.pairs_per_particle = sim.neighbour_pairs_per_particle();
  return r;
}

std::size_t differing(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size()) return std::max(a.size(), b.size());
  std::size_t n = 0;
  for (std::size_t i = 0; i < a.size(); ++i) n += a[i] != b[i] ? 1 : 0; // bitwise (no NaN here)
  return n;
}

void expect_same_as_separate(const Outcome& folded, const Outcome& separate, long steps) {
  EXPECT_EQ(differing(folded.q, separate.q), 0u);
  EXPECT_EQ(folded.builds, separate.builds);
  EXPECT_GT(separate.builds, 2); // the particles moved far enough to rebuild the list
  EXPECT_GT(separate.dissipated, 0.0);
  EXPECT_NEAR(folded.dissipated, separate.dissipated, 1e-12 * separate.dissipated);
  EXPECT_EQ(separate.folded, 0);
  EXPECT_GT(folded.folded, steps / 2);
  EXPECT_LT(folded.folded, steps - 1);
}

TEST(FoldedStep, SmallBedEqualsTheSeparatePass) {
  const std::string text =
      test::random_bed(600, "[0.04, 0.04, 0.04]", "hertz", "rolling = \"spring_dashpot\"\n");
  const long steps = 400;
  expect_same_as_separate(run(text, steps, true), run(text, steps, false), steps);
}

TEST(FoldedStep, ThreadedBedEqualsTheSeparatePassWithAnyThreadCount) {
  const std::string text = test::random_bed(6000, "[0.08, 0.08, 0.06]", "linear",
                                            "stiffness = 2000.0\n[output]\ncollisions = true\n");
  const long steps = 200;
  const Outcome one = run(text, steps, true, 1);
  const Outcome separate = run(text, steps, false, 1);
  expect_same_as_separate(one, separate, steps);
  for (const int threads : {2, 3}) {
    const Outcome r = run(text, steps, true, threads);
    EXPECT_EQ(differing(r.q, one.q), 0u) << threads << " threads";
    EXPECT_EQ(r.dissipated, one.dissipated) << threads << " threads"; // bitwise: slab order
    EXPECT_EQ(r.folded, one.folded) << threads << " threads";
  }
  ASSERT_EQ(one.record.size(), separate.record.size());
  ASSERT_GT(one.record.size(), 100u);
  for (std::size_t k = 0; k < one.record.size(); ++k) {
    EXPECT_EQ(one.record[k].id_i, separate.record[k].id_i);
    EXPECT_EQ(one.record[k].id_j, separate.record[k].id_j);
    EXPECT_EQ(one.record[k].force.x, separate.record[k].force.x);
    EXPECT_EQ(one.record[k].overlap, separate.record[k].overlap);
  }
}

TEST(FoldedStep, LargeBedInSlabGroupsEqualsTheSeparatePass) {
  const std::string text = test::random_bed(40000, "[0.16, 0.16, 0.12]", "hertz", "");
  const long steps = 60;
  const Outcome one = run(text, steps, true, 1);
  const Outcome separate = run(text, steps, false, 2);
  EXPECT_EQ(differing(one.q, separate.q), 0u);
  EXPECT_EQ(one.builds, separate.builds);
  EXPECT_NEAR(one.dissipated, separate.dissipated, 1e-12 * separate.dissipated);
  EXPECT_GT(one.folded, steps / 2);
  const Outcome two = run(text, steps, true, 2);
  EXPECT_EQ(differing(two.q, one.q), 0u);
  EXPECT_EQ(two.dissipated, one.dissipated);
}

TEST(FoldedStep, PeriodicBedEqualsTheSeparatePass) {
  const std::string text =
      test::random_bed(600, "[0.04, 0.04, 0.04]\nperiodic = [true, true, false]", "hertz", "");
  const long steps = 400;
  expect_same_as_separate(run(text, steps, true), run(text, steps, false), steps);
}

TEST(FoldedStep, OnlyThePlainKickFolds) {
  const long steps = 50;
  // The reference: the same bed folds.
  EXPECT_GT(run(test::random_bed(300, "[0.04, 0.04, 0.04]", "hertz", ""), steps, true).folded,
            steps / 2);
  const std::string field =
      test::random_bed(300, "[0.04, 0.04, 0.04]", "hertz",
                       "[body_force]\ntype = \"sinusoidal_cube\"\namplitude = 2.0\n"
                       "wavelength = 0.04\n");
  EXPECT_EQ(run(field, steps, true).folded, 0);
}

// (f) The default threshold: a bed sparser than 3 neighbour-list pairs per particle runs the
// separate pass (where it was faster, integrate/simulation.cpp), the same bed with a threshold
// below its density folds; and a dense bed folds by default.
TEST(FoldedStep, OnlyBedsWithEnoughPairsPerParticleFold) {
  EXPECT_EQ(Simulation::fold_pairs_per_particle(), 3.0);
  const long steps = 50;
  const std::string sparse = test::random_bed(600, "[0.04, 0.04, 0.04]", "hertz", "");
  const Outcome by_default = run(sparse, steps, true, 1, Simulation::fold_pairs_per_particle());
  ASSERT_GT(by_default.pairs_per_particle, 0.0);
  ASSERT_LT(by_default.pairs_per_particle, 3.0);
  EXPECT_EQ(by_default.folded, 0);
  const Outcome below = run(sparse, steps, true, 1, 0.5 * by_default.pairs_per_particle);
  EXPECT_GT(below.folded, steps / 2);
  EXPECT_EQ(differing(below.q, by_default.q), 0u); // bitwise the same particles either way
  // The same bed with a skin of one diameter: its list holds ~4 pairs per particle (600 * 0.5
  // * 4/3 pi (6 mm)^3 / (40 mm)^3 = 4.2 for uniform positions; 3.98 measured; 0.53 with the
  // default skin), so it folds by default.
  const std::string wide =
      test::random_bed(600, "[0.04, 0.04, 0.04]", "hertz", "[neighbour]\nskin = 0.003\n");
  const Outcome dense = run(wide, steps, true, 1, Simulation::fold_pairs_per_particle());
  EXPECT_GE(dense.pairs_per_particle, 3.0);
  EXPECT_GT(dense.folded, steps / 2);
}

// (e) Hand-computed: dt = 1e-3 s, v_max = 2 m/s, E = 10 entries, F_max = 0.5 N, 1/m = 100 /kg,
// |g| = 10 m/s^2: a = 10 * 0.5 * 100 + 10 = 510 m/s^2, step = 1e-3 (2 + 1e-3 * 510) = 2.51e-3 m.
// With d_max = 1e-3 m the reach is 3.51e-3 m (+ the 1e-6 margin of the step).
TEST(DriftBound, ReachAgainstHalfTheSkin) {
  DriftBound b;
  EXPECT_FALSE(b.next_step_within(1e-3, 1.0, 0.25, 10, 100.0, 10.0)); // unknown: not folded
  b.v_max = 2.0;
  b.d_max = 1e-3;
  EXPECT_TRUE(b.next_step_within(1e-3, 3.52e-3, 0.25, 10, 100.0, 10.0));
  EXPECT_FALSE(b.next_step_within(1e-3, 3.50e-3, 0.25, 10, 100.0, 10.0));
  // The margin: a reach of exactly half the skin is refused.
  EXPECT_FALSE(b.next_step_within(1e-3, 3.51e-3, 0.25, 10, 100.0, 10.0));
  EXPECT_FALSE(
      b.next_step_within(1e-3, 3.52e-3, std::numeric_limits<double>::quiet_NaN(), 10, 100.0, 10.0));
  EXPECT_FALSE(
      b.next_step_within(1e-3, 3.52e-3, std::numeric_limits<double>::infinity(), 10, 100.0, 10.0));
  // A folded step with largest squared speed 9 m^2/s^2 moves no particle more than 3e-3 m.
  b.folded_step(1e-3, 9.0);
  EXPECT_DOUBLE_EQ(b.v_max, 3.0);
  EXPECT_NEAR(b.d_max, 4e-3, 1e-14);
  EXPECT_GE(b.d_max, 4e-3);
}

} // namespace
} // namespace fluidem
