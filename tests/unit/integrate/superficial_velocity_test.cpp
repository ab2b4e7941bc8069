// GasCoupling::superficial_velocity (series.csv `superficial_velocity`): the prescribed inflow
// volume flow over the bed's cross-section. References worked out by hand from the case:
// (a) the Tsuji/Hoomans bubble set-up [Hoomans96 §5.3.1]: a 150 mm bed, a 1.8 m/s background
//     and a 10 mm orifice at 18 m/s: (0.14 x 1.8 + 0.01 x 18) / 0.15 = 2.88 m/s, exactly (to
//     round-off) in 2-D and in 3-D (one cell deep: the depth cancels);
// (b) a velocity table 0 -> 2 m/s over 1 s on the whole bottom: U(t) = 2 t, at t = 0.25 and
//     0.5 s and beyond the table's end (held: 2 m/s);
// (c) a pulsed jet [Deen07 §6.1]: the jet's share only while the pulse lasts.
#include <gtest/gtest.h>

#include <string>

#include "integrate/gas_coupling.hpp"
#include "integrate/simulation.hpp"
#include "io/case_reader.hpp"

namespace fluidem {
namespace {

std::string bed(int dimension, const std::string& bottom) {
  return "[simulation]\ndimension = " + std::to_string(dimension) +
         "\nengine = \"hard_sphere\"\nend_time = 0.01\ntime_step = 1e-4\n"
         "[domain]\nlo = [0, 0, 0]\nhi = [0.15, 0.004, 0.3]\n"
         "[[species]]\nname = \"s\"\ndiameter = 0.004\ndensity = 2700\n"
         "[[insert]]\nspecies = \"s\"\ncount = 20\nplacement = \"lattice\"\n"
         "[gas]\ncells = [15, 1, 15]\n" +
         bottom + "[gas.boundary.top]\ntype = \"pressure\"\npressure = 101325.0\n";
}

double u_at(const std::string& text, double t) {
  Simulation sim(read_case_string(text, "case.toml"));
  return sim.gas()->superficial_velocity(t);
}

const std::string kOrifice = "[gas.boundary.bottom]\ntype = \"inflow\"\nvelocity = 1.8\n"
                             "[[gas.boundary.bottom.region]]\ntype = \"inflow\"\n"
                             "lo = [0.07, 0.0]\nhi = [0.08, 0.004]\nvelocity = 18.0\n";

TEST(SuperficialVelocity, OrificeOverBackground) {
  const double expected = (0.14 * 1.8 + 0.01 * 18.0) / 0.15;
  EXPECT_NEAR(u_at(bed(2, kOrifice), 0.0), expected, 1e-12);
  EXPECT_NEAR(u_at(bed(3, kOrifice), 0.5), expected, 1e-12);
}

TEST(SuperficialVelocity, VelocityTable) {
  const std::string table = "[gas.boundary.bottom]\ntype = \"inflow\"\nmode = \"table\"\n"
                            "times = [0.0, 1.0]\nvelocities = [0.0, 2.0]\n";
  EXPECT_NEAR(u_at(bed(2, table), 0.25), 0.5, 1e-12);
  EXPECT_NEAR(u_at(bed(2, table), 0.5), 1.0, 1e-12);
  EXPECT_NEAR(u_at(bed(2, table), 3.0), 2.0, 1e-12);
}

TEST(SuperficialVelocity, PulsedJet) {
  const std::string pulse = "[gas.boundary.bottom]\ntype = \"inflow\"\nvelocity = 1.25\n"
                            "[[gas.boundary.bottom.region]]\ntype = \"inflow\"\n"
                            "lo = [0.07, 0.0]\nhi = [0.08, 0.004]\nmode = \"pulse\"\n"
                            "velocity = 20.0\nbackground = 1.25\nstart = 0.1\nduration = 0.15\n";
  EXPECT_NEAR(u_at(bed(2, pulse), 0.05), 1.25, 1e-12);
  EXPECT_NEAR(u_at(bed(2, pulse), 0.2), (0.14 * 1.25 + 0.01 * 20.0) / 0.15, 1e-12);
  EXPECT_NEAR(u_at(bed(2, pulse), 0.3), 1.25, 1e-12);
}

} // namespace
} // namespace fluidem
