// A granular test bed as case-file text: `count` glass spheres (d = 3 mm, 2500 kg/m3, E = 1e7
// Pa, e = 0.8, mu = 0.4, rolling friction 0.05) at random in a closed box from the origin to `hi`
// (possibly followed by a `periodic = [...]` line), with 0.8 m/s random velocities under
// gravity, time step 2e-5 s, Hertz or linear contacts (`normal`) with tangential history;
// `extra` goes at the end of [contact] (and may open further sections). For tests of the
// integrator (folded step, steady-state allocations) that need list rebuilds: the particles
// move a skin's width in about ten steps.
#pragma once
#include <string>

#include <fmt/format.h>

namespace fluidem::test {

/// The beds' [[species]] entry, named `name`: glass spheres of d = 3 mm, 2500 kg/m3, E = 1e7
/// Pa, e = 0.8, mu = 0.4, rolling friction 0.05.
inline std::string glass_species(const char* name) {
  return fmt::format(R"(
[[species]]
name = "{}"
diameter = 0.003
density = 2500.0
youngs_modulus = 1e7
restitution = 0.8
friction = 0.4
rolling_friction = 0.05)",
                     name);
}

inline std::string random_bed(int count, const char* hi, const char* normal, const char* extra) {
  return fmt::format(R"(
[simulation]
dimension = 3
end_time = 1.0
time_step = 2e-5
gravity = [0.0, 0.0, -9.81]
[domain]
lo = [0.0, 0.0, 0.0]
hi = {}{}
[[insert]]
species = "glass"
count = {}
placement = "random"
velocity_spread = 0.8
seed = 5
[contact]
normal = "{}"
tangential = "history"
{})",
                     hi, glass_species("glass"), count, normal, extra);
}

} // namespace fluidem::test
