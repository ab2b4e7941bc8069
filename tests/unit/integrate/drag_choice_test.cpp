// coupling.drag names a closure of the registry (coupling/drag/drag_model.hpp). The case keeps
// the name as a string (io and core know no drag law); the coupling module checks it when the
// run is set up, at the key's source location: an unknown name is exit 2 at file:line:col with
// the key and every name a case may choose; a total-force closure (wen_yu_single) outside the
// "total" form says why; a --set override is named as such. Every name a case may choose sets up a
// run. Without the key a case gets the closure the registry declares the default ([Hoomans96 eq.
// 45-46]'s switch, docs/drag.md), and its resolved case names it; an empty name is refused when
// read.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "coupling/drag/drag_model.hpp"
#include "integrate/simulation.hpp"
#include "io/case_reader.hpp"

namespace fluidem {
namespace {

const std::string kCase =
    "[simulation]\nengine = \"hard_sphere\"\nend_time = 0.01\ntime_step = 1e-3\n"
    "[domain]\nlo = [0, 0, 0]\nhi = [0.04, 0.04, 0.04]\n"
    "[[species]]\nname = \"s\"\ndiameter = 0.005\ndensity = 2700\n"
    "[[insert]]\nspecies = \"s\"\ncount = 1\n"
    "[gas]\ncells = [4, 4, 4]\n[coupling]\nd_mean = 0.005\n";

/// The line of `drag = ...` appended to kCase.
std::string drag_line() {
  return std::to_string(std::count(kCase.begin(), kCase.end(), '\n') + 1);
}

/// The message of the InputError that setting up `text` (with `overrides`) throws; "" if none.
std::string setup_error(const std::string& text, const std::vector<std::string>& overrides = {}) {
  try {
    Simulation sim(read_case_string(text, "case.toml", overrides));
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(DragChoice, UnknownNameIsNamedAtItsKeyWithTheAllowedNames) {
  const std::string msg = setup_error(kCase + "drag = \"wen-yu\"\n");
  EXPECT_EQ(msg.rfind("case.toml:" + drag_line() + ":", 0), 0u) << msg;
  EXPECT_NE(msg.find(": coupling.drag: unknown drag model 'wen-yu' (valid: " +
                     coupling::drag::drag_model_names() + ")"),
            std::string::npos)
      << msg;
  for (const auto m : coupling::drag::all_drag_models) {
    if (!coupling::drag::drag_model_refusal(m).empty()) continue;
    EXPECT_NE(msg.find(std::string(coupling::drag::to_string(m))), std::string::npos) << msg;
  }
}

TEST(DragChoice, TotalForceClosureOutsideTheTotalFormSaysWhyAtTheCoupling) {
  // wen_yu_single is the total gas force [Hoomans96 eq. 34]: with the pressure-gradient form of
  // this Model A case the pressure force would be counted twice.
  const std::string msg = setup_error(kCase + "drag = \"wen_yu_single\"\n");
  EXPECT_NE(msg.find(": coupling: coupling.drag = \"wen_yu_single\" does not go with "
                     "coupling.particle_force = \"pressure_gradient\""),
            std::string::npos)
      << msg;
  EXPECT_NE(msg.find("coupling.particle_force = \"total\" with gas.model = \"B\""),
            std::string::npos)
      << msg;
}

TEST(DragChoice, OverrideIsNamedAsSuch) {
  const std::string msg = setup_error(kCase, {"coupling.drag=gidaspow"});
  EXPECT_EQ(msg.rfind("--set: coupling.drag: unknown drag model 'gidaspow' (valid: ", 0), 0u)
      << msg;
}

TEST(DragChoice, EveryAllowedClosureSetsUpARun) {
  for (const auto m : coupling::drag::all_drag_models) {
    if (!coupling::drag::drag_model_refusal(m).empty()) continue;
    const std::string name(coupling::drag::to_string(m));
    std::string text = kCase + "drag = \"" + name + "\"\n";
    if (coupling::drag::is_total_force(m)) { // its form, in gas Model B
      text += "particle_force = \"total\"\n";
      text.replace(text.find("[gas]\n"), 6, "[gas]\nmodel = \"B\"\n");
    }
    EXPECT_EQ(setup_error(text), "") << name;
  }
}

TEST(DragChoice, WithoutTheKeyTheDefaultClosureIsUsedAndNamed) {
  const CaseSpec read = read_case_string(kCase, "case.toml");
  EXPECT_EQ(read.coupling.drag, "") << "not given";
  Simulation sim(read);
  EXPECT_EQ(sim.spec().coupling.drag, "ergun_wen_yu") << "the resolved case names the closure";
  EXPECT_EQ(coupling::drag::to_string(coupling::drag::default_drag_model()), "ergun_wen_yu");
}

TEST(DragChoice, EmptyNameIsRefusedWhereItIsWritten) {
  try {
    (void)read_case_string(kCase + "drag = \"\"\n", "case.toml");
    FAIL() << "an empty drag name was read";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg.rfind("case.toml:" + drag_line() + ":", 0), 0u) << msg;
    EXPECT_NE(msg.find("coupling.drag: an empty name"), std::string::npos) << msg;
  }
}

} // namespace
} // namespace fluidem
