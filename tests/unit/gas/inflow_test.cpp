// Inflow time windows [Deen07 §6.1]: constant, pulse (start, duration, velocity during the
// pulse, background otherwise) and pulsation (mean + amplitude sin(2 pi f t)). Reference: the
// formulas; exact equality for inflow_velocity(), and the boundary face velocity times the
// ghost porosity equals it to 4 ulp (one division and one multiplication) at sampled times.
#include "core/error.hpp"
#include "gas/gas_solver.hpp"
#include <cmath>
#include <gtest/gtest.h>
#include <numbers>

using namespace fluidem;
using namespace fluidem::gas;

TEST(Inflow, ProfilesExact) {
  InflowProfile pulse{InflowMode::pulse, 20.0, 1.25, 0.1, 0.15, 0.0, 0.0};
  EXPECT_EQ(inflow_velocity(pulse, 0.0), 1.25);
  EXPECT_EQ(inflow_velocity(pulse, 0.0999), 1.25);
  EXPECT_EQ(inflow_velocity(pulse, 0.1), 20.0);
  EXPECT_EQ(inflow_velocity(pulse, 0.2), 20.0);
  EXPECT_EQ(inflow_velocity(pulse, 0.25), 1.25); // end of the window is excluded
  EXPECT_EQ(inflow_velocity(pulse, 1.0), 1.25);
  InflowProfile puls{InflowMode::pulsation, 0.8, 0.0, 0.0, 0.0, 0.4, 10.0};
  for (double t : {0.0, 0.0125, 0.025, 0.0375, 0.1234})
    EXPECT_EQ(inflow_velocity(puls, t), 0.8 + 0.4 * std::sin(2.0 * std::numbers::pi * 10.0 * t));
  EXPECT_EQ(inflow_velocity({InflowMode::constant, 0.7}, 3.0), 0.7);
  // Table: piecewise linear, constant beyond the ends (a velocity sweep up and down).
  InflowProfile table{InflowMode::table};
  table.times = {1.0, 3.0, 5.0};
  table.velocities = {0.5, 3.0, 0.5};
  EXPECT_EQ(inflow_velocity(table, 0.0), 0.5);
  EXPECT_EQ(inflow_velocity(table, 1.0), 0.5);
  EXPECT_DOUBLE_EQ(inflow_velocity(table, 2.0), 1.75);
  EXPECT_EQ(inflow_velocity(table, 3.0), 3.0);
  EXPECT_DOUBLE_EQ(inflow_velocity(table, 4.5), 1.125);
  EXPECT_EQ(inflow_velocity(table, 9.0), 0.5);
}

TEST(Inflow, BadTablesAreInputErrors) {
  GasSettings s;
  s.boundary[bottom].type = BoundaryType::inflow;
  s.boundary[bottom].inflow.mode = InflowMode::table;
  s.boundary[bottom].inflow.times = {0.0, 1.0};
  s.boundary[bottom].inflow.velocities = {1.0};
  EXPECT_THROW(validate(s), InputError);
  s.boundary[bottom].inflow.velocities = {1.0, 2.0};
  EXPECT_NO_THROW(validate(s));
  s.boundary[bottom].inflow.times = {1.0, 1.0};
  EXPECT_THROW(validate(s), InputError);
}

TEST(Inflow, FaceVelocityFollowsProfile) {
  GasSettings s;
  s.dimension = 2;
  s.cells = {6, 1, 6};
  s.hi = {0.06, 0.0, 0.06};
  s.eos = EquationOfState::incompressible;
  for (auto& b : s.boundary) b.type = BoundaryType::wall_free_slip;
  s.boundary[bottom].type = BoundaryType::inflow;
  s.boundary[bottom].inflow = {InflowMode::pulsation, 0.8, 0.0, 0.0, 0.0, 0.4, 10.0};
  s.boundary[bottom].porosity = 0.4;
  // Central jet (cells 3-4, x in [0.02, 0.04]) with a pulse.
  s.boundary[bottom].regions.push_back({BoundaryType::inflow,
                                        {0.02, 0.0},
                                        {0.04, 1.0},
                                        {InflowMode::pulse, 20.0, 1.25, 2e-3, 3e-3},
                                        0.5,
                                        0.0});
  s.boundary[top].type = BoundaryType::pressure;
  s.tolerance = 1e-6;
  s.velocity_tolerance = 1e-4;
  GasSolver gs(s);
  const GasGrid& g = gs.grid();
  const double dt = 1e-3;
  double t = 0.0;
  for (int n = 0; n < 8; ++n, t += dt) {
    gs.step(t, dt);
    const double tn = t + dt;
    for (int i = 1; i <= g.n[0]; ++i) {
      const bool jet = i == 3 || i == 4;
      const double ref = jet ? (tn >= 2e-3 && tn < 5e-3 ? 20.0 : 1.25)
                             : 0.8 + 0.4 * std::sin(2.0 * std::numbers::pi * 10.0 * tn);
      const double w = gs.velocity(2)[g.idx(i, 1, 0)];
      EXPECT_DOUBLE_EQ(w * (jet ? 0.5 : 0.4), ref) << "t = " << tn << " i = " << i;
      EXPECT_EQ(gs.porosity()[g.idx(i, 1, 0)], jet ? 0.5 : 0.4);
    }
  }
}
