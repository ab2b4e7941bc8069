// Insertion with a size distribution ([[insert]] size_distribution, docs/case-file.md): random
// placement places the block's drawn diameters (largest first) without overlap inside the region,
// each particle with its own radius and the species' density; lattice placement spaces the sites
// by the largest diameter; the same seed gives the same bed bit for bit, another seed another;
// a block without a distribution keeps the species' diameter and draws nothing more (its
// positions are those of the same block beside a distributed one).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "particles/insertion.hpp"
#include "particles/size_distribution.hpp"

namespace fluidem {
namespace {

CaseSpec bed(Placement placement, std::uint64_t seed, bool distributed) {
  CaseSpec spec;
  spec.domain.lo = {0, 0, 0};
  spec.domain.hi = {0.05, 0.05, 0.1};
  SpeciesSpec sp;
  sp.name = "glass", sp.diameter = 2e-3, sp.density = 2500.0;
  spec.species.push_back(sp);
  InsertSpec in;
  in.species = "glass", in.count = 400, in.placement = placement, in.seed = seed;
  in.region_lo = spec.domain.lo, in.region_hi = spec.domain.hi;
  if (distributed) {
    SizeDistributionSpec d;
    d.kind = SizeDistributionSpec::Kind::LogNormal, d.median = 2e-3, d.geometric_std = 1.3;
    d.min = 1e-3, d.max = 4e-3;
    in.size_distribution = d;
  }
  spec.inserts.push_back(in);
  return spec;
}

ParticleStore insert(const CaseSpec& spec) {
  ParticleStore p;
  insert_particles(spec, p);
  return p;
}

TEST(SizeDistributionInsertion, RandomPlacementOwnDiametersNoOverlap) {
  const CaseSpec spec = bed(Placement::Random, 5, true);
  const ParticleStore p = insert(spec);
  ASSERT_EQ(p.size(), 400u);
  double dmin = 1.0, dmax = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double d = 2.0 * p.radius[i];
    dmin = std::min(dmin, d), dmax = std::max(dmax, d);
    EXPECT_GE(d, 1e-3);
    EXPECT_LE(d, 4e-3);
    // Mass of a sphere of the particle's own diameter and the species' density.
    EXPECT_NEAR(p.mass[i], 2500.0 * std::numbers::pi / 6.0 * d * d * d, 1e-12 * p.mass[i]);
    const Vec3 x = p.position(i);
    for (int a = 0; a < 3; ++a) {
      EXPECT_GE(x[a] - p.radius[i], spec.domain.lo[a] - 1e-15);
      EXPECT_LE(x[a] + p.radius[i], spec.domain.hi[a] + 1e-15);
    }
    for (std::size_t j = 0; j < i; ++j)
      ASSERT_GE(norm(x - p.position(j)), p.radius[i] + p.radius[j]) << i << " " << j;
  }
  EXPECT_GT(dmax / dmin, 1.5); // the diameters do vary (sigma_g = 1.3 over 400 draws)
  // The same diameters as the distribution draws first from the block's seed, largest first.
  std::mt19937_64 rng(5);
  auto drawn = SizeDistribution(*spec.inserts[0].size_distribution).sample(400, rng);
  std::sort(drawn.begin(), drawn.end(), std::greater<>());
  for (std::size_t i = 0; i < p.size(); ++i) EXPECT_EQ(2.0 * p.radius[i], drawn[i]);
}

TEST(SizeDistributionInsertion, SameSeedSameBedOtherSeedOther) {
  const ParticleStore a = insert(bed(Placement::Random, 5, true));
  const ParticleStore b = insert(bed(Placement::Random, 5, true));
  const ParticleStore c = insert(bed(Placement::Random, 6, true));
  EXPECT_EQ(a.radius, b.radius);
  EXPECT_EQ(a.x, b.x);
  EXPECT_EQ(a.z, b.z);
  EXPECT_NE(a.radius, c.radius);
}

TEST(SizeDistributionInsertion, LatticeSpacedByTheLargestDiameter) {
  const ParticleStore p = insert(bed(Placement::Lattice, 5, true));
  ASSERT_EQ(p.size(), 400u);
  // Sites 4 mm apart (the largest diameter), the first at the region's corner plus 2 mm.
  EXPECT_DOUBLE_EQ(p.x[0], 2e-3);
  EXPECT_DOUBLE_EQ(p.x[1] - p.x[0], 4e-3);
  EXPECT_NE(p.radius[0], p.radius[1]);
}

TEST(SizeDistributionInsertion, WithoutDistributionTheSpeciesDiameter) {
  const ParticleStore p = insert(bed(Placement::Random, 5, false));
  for (const double r : p.radius) EXPECT_EQ(r, 1e-3);
  // A distributed block first, then the same plain block: the plain block's positions are
  // those it has alone (its generator is its own and draws no diameters).
  CaseSpec two = bed(Placement::Random, 9, true);
  two.inserts[0].region_hi[2] = 0.05;
  InsertSpec plain = bed(Placement::Random, 5, false).inserts[0];
  plain.region_lo[2] = 0.05;
  two.inserts.push_back(plain);
  CaseSpec alone = bed(Placement::Random, 5, false);
  alone.inserts[0] = plain;
  const ParticleStore q = insert(two), r = insert(alone);
  ASSERT_EQ(q.size(), 800u);
  for (std::size_t i = 0; i < 400; ++i) {
    EXPECT_EQ(q.x[400 + i], r.x[i]);
    EXPECT_EQ(q.z[400 + i], r.z[i]);
  }
}

} // namespace
} // namespace fluidem
