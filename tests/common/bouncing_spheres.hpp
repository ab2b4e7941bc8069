// The small case of the CLI tests: ten glass spheres (d = 4 mm) in a closed 40 x 4 x 40 mm box,
// linear contact, from a lattice: bouncing elastically with random velocities (0.5 m/s) by
// default, or at rest with the default walls. Each test sets what it is about: the dimension,
// the times, the output schedule; a key left unset is not written (the case's default applies).
#pragma once
#include <fmt/format.h>

#include <optional>
#include <string>

namespace fluidem::test {

struct BouncingSpheres {
  int dimension = 3;
  double end_time = 0.2;
  std::optional<double> time_step = 1e-5;
  std::optional<double> frame_interval = 0.1;
  std::optional<double> series_interval = 0.01;
  std::optional<double> checkpoint_interval = std::nullopt;
  bool engine_key = true; ///< write engine = "soft_sphere"
  bool moving = true;     ///< velocity_spread = 0.5 and elastic walls (else at rest, no [walls])
};

/// A TOML float as a person writes it (1000.0, 0.01, 2e-5): the shortest text that reads back
/// as x, with a decimal point or an exponent, the exponent without leading zeros (tests find
/// and replace these lines in the text).
inline std::string toml_float(double x) {
  std::string t = fmt::format("{}", x);
  const std::size_t e = t.find('e');
  if (e == std::string::npos) return t.find('.') == std::string::npos ? t + ".0" : t;
  std::size_t digits = e + 1 + (t[e + 1] == '-' || t[e + 1] == '+' ? 1 : 0);
  if (t[e + 1] == '+') t.erase(e + 1, 1), --digits;
  while (digits + 1 < t.size() && t[digits] == '0') t.erase(digits, 1);
  return t;
}

/// The case file text.
inline std::string bouncing_spheres_case(const BouncingSpheres& c) {
  std::string text = fmt::format("[simulation]\ndimension = {}\nend_time = {}\n", c.dimension,
                                 toml_float(c.end_time));
  if (c.engine_key) text += "engine = \"soft_sphere\"\n";
  if (c.time_step) text += fmt::format("time_step = {}\n", toml_float(*c.time_step));
  std::string output;
  for (const auto& [key, value] : {std::pair{"frame_interval", c.frame_interval},
                                   std::pair{"series_interval", c.series_interval},
                                   std::pair{"checkpoint_interval", c.checkpoint_interval}})
    if (value) output += fmt::format("{} = {}\n", key, toml_float(*value));
  if (!output.empty()) text += "\n[output]\n" + output;
  text += R"(
[domain]
lo = [0.0, 0.0, 0.0]
hi = [0.04, 0.004, 0.04]

[[species]]
name = "glass"
diameter = 0.004
density = 2700.0

[[insert]]
species = "glass"
count = 10
placement = "lattice"
)";
  if (c.moving) text += "velocity_spread = 0.5\n";
  text += R"(
[contact]
normal = "linear"
stiffness = 800.0
)";
  if (c.moving) text += "\n[walls]\nrestitution = 1.0\n";
  return text;
}

/// The smallest valid case of the CLI tests: ten discs at rest on a lattice, 2-D, 0.02 s,
/// every other key at its default.
inline std::string resting_discs_case() {
  return bouncing_spheres_case({.dimension = 2,
                                .end_time = 0.02,
                                .time_step = std::nullopt,
                                .frame_interval = std::nullopt,
                                .series_interval = std::nullopt,
                                .engine_key = false,
                                .moving = false});
}

} // namespace fluidem::test
