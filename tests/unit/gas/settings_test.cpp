// Bad settings -> fluidem::InputError naming the case-file key; a forced non-convergence
// (gas.solver.max_iterations = 1, tiny tolerance) -> fluidem::InstabilityError naming the
// step and the residual. Reference: the messages themselves (substring match).
#include "core/error.hpp"
#include "gas/gas_solver.hpp"
#include <gtest/gtest.h>
#include <string>

using namespace fluidem;
using namespace fluidem::gas;

namespace {
GasSettings small() {
  GasSettings s;
  s.dimension = 2;
  s.cells = {4, 1, 4};
  s.hi = {0.04, 0.0, 0.04};
  return s;
}

template <class E, class F>
std::string message_of(F&& f) {
  try {
    f();
  } catch (const E& e) {
    return e.what();
  }
  return "<no exception>";
}
} // namespace

TEST(GasSettings, NegativeViscosityNamesKey) {
  GasSettings s = small();
  s.viscosity = -1.0;
  EXPECT_NE(message_of<InputError>([&] { validate(s); }).find("gas.viscosity"), std::string::npos);
  EXPECT_THROW(GasSolver{s}, InputError);
}

TEST(GasSettings, ZeroCellsNamesKey) {
  GasSettings s = small();
  s.cells[2] = 0;
  EXPECT_NE(message_of<InputError>([&] { GasSolver gs(s); }).find("gas.cells"), std::string::npos);
}

TEST(GasSettings, UnknownInflowModeNamesKey) {
  EXPECT_NE(message_of<InputError>([] {
              inflow_mode_from_string("sawtooth", "gas.boundary.bottom.mode");
            }).find("gas.boundary.bottom.mode"),
            std::string::npos);
  GasSettings s = small();
  s.boundary[bottom].type = BoundaryType::inflow;
  s.boundary[bottom].inflow.mode = static_cast<InflowMode>(7);
  EXPECT_NE(message_of<InputError>([&] { validate(s); }).find("gas.boundary.bottom.mode"),
            std::string::npos);
}

TEST(GasSettings, OtherKeys) {
  GasSettings s = small();
  s.tolerance = 0.0;
  EXPECT_NE(message_of<InputError>([&] { validate(s); }).find("gas.solver.tolerance"),
            std::string::npos);
  s = small();
  s.boundary[left].type = BoundaryType::periodic;
  EXPECT_NE(message_of<InputError>([&] { validate(s); }).find("gas.boundary.left.type"),
            std::string::npos);
  s = small();
  s.boundary[bottom].inflow.duration = -1.0;
  EXPECT_NE(message_of<InputError>([&] { validate(s); }).find("gas.boundary.bottom.duration"),
            std::string::npos);
  EXPECT_NE(message_of<InputError>([] {
              boundary_type_from_string("wal", "gas.boundary.top.type");
            }).find("gas.boundary.top.type"),
            std::string::npos);
}

TEST(GasSolverErrors, NonConvergenceIsInstability) {
  GasSettings s = small();
  s.boundary[bottom].type = BoundaryType::inflow;
  s.boundary[bottom].inflow.velocity = 1.0;
  s.boundary[top].type = BoundaryType::pressure;
  s.max_iterations = 1;
  s.tolerance = 1e-300;
  s.velocity_tolerance = 1e-300;
  GasSolver gs(s);
  const std::string m = message_of<InstabilityError>([&] { gs.step(0.5, 1e-4); });
  EXPECT_NE(m.find("did not converge"), std::string::npos) << m;
  EXPECT_NE(m.find("t = 0.5"), std::string::npos) << m;
  EXPECT_NE(m.find("mass residual"), std::string::npos) << m;
}
