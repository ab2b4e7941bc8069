// Continuum averaging of a real settled bed (soft spheres, the contact loop's ContactRecord)
// [Zhu07 Tables 5-6]: 800 spheres of 4 mm (linear springs, friction 0.3, e = 0.3) dropped from
// a slightly perturbed lattice into a box periodic in x and y (no side walls, so no Janssen
// effect) with a frictionless floor, settled for 0.4 s; the contacts of the last step.
// References (static equilibrium, the kinetic energy left is checked to be below 1e-4 of the
// potential energy):
//  - one volume cell over the whole box: sum_p sum_c f_z (z_c - z_p) = -g sum_p m_p z_p
//    exactly for particles in equilibrium with the floor at z = 0 (pair terms cancel at the
//    common contact point, floor contacts sit at z = 0), so T_zz V = -g sum m z: within 1e-3
//    (the residual accelerations of a bed at rest);
//  - volume layers of 10 mm: the bottom layer's T_zz equals minus the weight above its
//    mid-height per floor area, -(W - W_bottom / 2) / A, within 5% (the layer average of a
//    stress growing linearly with depth, up to the granularity of a 2.5-diameter layer);
//  - weighted (w = d, cutoff 3 w), the mean over 4 x 4 cell centres at a height z at least 3 w
//    from the floor and from the bed surface: T_zz = -(g/A) sum_p m_p Phi((z_p - z)/w), the
//    weight above z smoothed by the Gaussian's normal marginal (the static momentum balance of
//    the coarse-grained fields, dT_zz/dz = rho g), within 5% (the truncation at 3 w and the
//    lateral variation of a granular bed);
//  - the off-diagonal T_xz, T_yz and the mean horizontal velocity stay below 2% of |T_zz|;
//  - run() wrote continuum.h5 and continuum.xmf with one frame per 0.1 s interval (4 frames).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "analysis/continuum_averaging.hpp"
#include "integrate/simulation.hpp"
#include "io/case_reader.hpp"

namespace fluidem {
namespace {

namespace fs = std::filesystem;

const double kD = 0.004, kL = 0.04, kG = 9.81;

std::string bed_case() {
  return "[simulation]\nend_time = 0.4\ntime_step = 2e-5\n"
         "[domain]\nlo = [0, 0, 0]\nhi = [0.04, 0.04, 0.1]\nperiodic = [true, true, false]\n"
         "[walls]\nfriction = 0.0\nrestitution = 0.3\n"
         "[[species]]\nname = \"s\"\ndiameter = 0.004\ndensity = 2500\n"
         "restitution = 0.3\nfriction = 0.3\n"
         "[[insert]]\nspecies = \"s\"\ncount = 800\nplacement = \"lattice\"\n"
         "region = { lo = [0.002, 0.002, 0.002], hi = [0.038, 0.038, 0.098] }\n"
         "velocity_spread = 0.05\n"
         "[contact]\nnormal = \"linear\"\nstiffness = 2.0e3\ntangential = \"history\"\n"
         "[output]\nframe_interval = 0.1\nseries_interval = 0.01\n"
         "[output.continuum]\ncells = [1, 1, 10]\nmethod = \"volume\"\ninterval = 0.1\n";
}

ContinuumFields average(const Simulation& sim, ContinuumGrid grid, ContinuumSettings s) {
  grid.periodic = {true, true, false};
  ContinuumAverager avg(grid, s);
  avg.accumulate(sim.particles(), sim.contact_record().samples);
  return avg.result();
}

TEST(ContinuumBed, SettledBedStressIsTheWeightAbove) {
  const fs::path out =
      fs::temp_directory_path() / ("fluidem_continuum_" + std::to_string(getpid()));
  fs::remove_all(out);
  Simulation sim(read_case_string(bed_case(), "case.toml"));
  sim.run(out.string());
  const ParticleStore& p = sim.particles();
  ASSERT_EQ(p.size(), 800u);
  ASSERT_FALSE(sim.contact_record().samples.empty());

  double weight = 0.0, moment = 0.0, e_kin = 0.0, top = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    weight += p.mass[i] * kG;
    moment += p.mass[i] * kG * p.z[i];
    e_kin += 0.5 * p.mass[i] * norm2(p.velocity(i));
    top = std::max(top, p.z[i]);
  }
  const double area = kL * kL;
  std::printf("[ measured ] settled bed: top centre %.4f m, kinetic energy %.3g J (potential "
              "%.3g J)\n",
              top, e_kin, moment);
  ASSERT_LT(e_kin, 1e-4 * moment) << "the bed has not settled";

  { // one cell: the exact static identity
    ContinuumGrid g;
    g.spacing = {kL, kL, 0.1};
    const ContinuumFields f = average(sim, g, {});
    const double expect = -moment / (kL * kL * 0.1);
    std::printf("[ measured ] whole box T_zz = %.6g Pa, -g sum m z / V = %.6g Pa (rel. %.2e)\n",
                f.contact_stress[8][0], expect, f.contact_stress[8][0] / expect - 1.0);
    EXPECT_NEAR(f.contact_stress[8][0], expect, 1e-3 * std::abs(expect));
  }
  { // volume layers of 10 mm: the bottom one
    ContinuumGrid g;
    g.cells = {1, 1, 10};
    g.spacing = {kL, kL, 0.01};
    const ContinuumFields f = average(sim, g, {});
    double w_bottom = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i)
      if (p.z[i] < 0.01) w_bottom += p.mass[i] * kG;
    const double expect = -(weight - 0.5 * w_bottom) / area;
    std::printf("[ measured ] bottom layer T_zz = %.6g Pa, -(W - W_layer/2)/A = %.6g Pa (rel. "
                "%.2e)\n",
                f.contact_stress[8][0], expect, f.contact_stress[8][0] / expect - 1.0);
    EXPECT_NEAR(f.contact_stress[8][0], expect, 0.05 * std::abs(expect));
    EXPECT_LT(std::abs(f.contact_stress[2][0]), 0.02 * std::abs(expect)); // T_xz
    EXPECT_LT(std::abs(f.contact_stress[5][0]), 0.02 * std::abs(expect)); // T_yz
  }
  { // weighted: horizontal mean over 4 x 4 cell centres at each height far enough from the
    // floor and from the surface, against the weight above smoothed by the same Gaussian
    ContinuumGrid g;
    g.cells = {4, 4, 50};
    g.spacing = {kL / 4, kL / 4, 0.002};
    ContinuumSettings s;
    s.method = AveragingMethod::Weighted;
    s.width = kD;
    const ContinuumFields f = average(sim, g, s);
    int checked = 0;
    for (int k = 0; k < 50; ++k) {
      const double z = (k + 0.5) * 0.002;
      if (z < 3 * kD || z > top - 3 * kD) continue;
      double got = 0.0;
      for (std::size_t c = 0; c < 16; ++c) got += f.contact_stress[8][16 * k + c] / 16.0;
      double above = 0.0;
      for (std::size_t i = 0; i < p.size(); ++i)
        above += p.mass[i] * kG * 0.5 * std::erfc((z - p.z[i]) / (std::sqrt(2.0) * kD));
      const double expect = -above / area;
      EXPECT_NEAR(got, expect, 0.05 * std::abs(expect)) << "z = " << z;
      std::printf("[ measured ] weighted T_zz at z = %.3f m: %.6g Pa, smoothed weight above / A "
                  "= %.6g Pa (rel. %.2e)\n",
                  z, got, expect, got / expect - 1.0);
      ++checked;
    }
    EXPECT_GE(checked, 3);
  }

  // The run's own file: 4 intervals of 0.1 s.
  ASSERT_TRUE(fs::exists(out / "continuum.h5"));
  std::ifstream xmf(out / "continuum.xmf");
  std::stringstream text;
  text << xmf.rdbuf();
  EXPECT_NE(text.str().find("frame_3"), std::string::npos);
  EXPECT_EQ(text.str().find("frame_4"), std::string::npos);
  EXPECT_NE(text.str().find("contact_stress_zz"), std::string::npos);
  fs::remove_all(out);
}

} // namespace
} // namespace fluidem
