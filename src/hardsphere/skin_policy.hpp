// The neighbour skin of the event-driven engine, chosen at each list build from counts alone
// (so the choice, and with it series.csv's neighbour_builds, is the same on any number of
// threads and across restarts; the particles do not depend on it: the list only has to hold
// every pair that can meet within its life).
//
// With s = 1.5 (v_max + |g| DT) DT the most a particle moves in one flow step, a list of skin
// k s lives while the largest displacement since its build plus s stays below k s / 2
// (HardSphereEngine::update_neighbour_list). Per particle and flow step, a list with E entries
// per particle that lives L steps costs
//   C = B / L + w E,   w = 1/2 + 2 c
// where c is the events per particle in the step (first_events computes every pair once; each
// event re-predicts two rows) and B the cost of one build in entry-scans per particle. Two
// skins are compared: long (8 s: about four steps, fewer when the fastest particles speed up)
// and short (2 s: a build every step):
//   the short skin pays when B + w E(2) < B / L(8) + w E(8).
// E(8) and E(2) are counted in a build with the long skin (a probe: every pair's gap is known,
// so both counts come from one build), and L(8) is the number of steps that list served; while
// the short skin is chosen, every kProbeEvery-th build is a probe again, so that the choice
// follows the bed. B = 12 entry-scans was fitted to whole-run times of a settled 2-D bed
// (short 1.7x faster) and a falling 3-D bed (long 1.5x faster): bench/RESULTS.md, "Hard-sphere
// neighbour skin".
#pragma once
#include <cstdint>

namespace fluidem::hardsphere {

struct SkinProbe {
  std::int64_t build = -1;    ///< list_builds at the last probe (-1: none yet)
  double long_entries = 0.0;  ///< list entries per particle with the long skin, E(8)
  double short_entries = 0.0; ///< ... of them within the short skin, E(2)
  std::int64_t life = 0;      ///< flow steps that list served, L(8) (0: still serving)
};

inline constexpr double kLongSkinSteps = 8.0;
inline constexpr double kShortSkinSteps = 2.0;
inline constexpr std::int64_t kProbeEvery = 64;
inline constexpr double kBuildCost = 12.0; ///< B, in entry-scans per particle

/// Whether a list with the short skin is expected to be cheaper, after the probe `probe` and a
/// last step with `events_per_particle` events per moving particle.
inline bool short_skin_pays(const SkinProbe& probe, double events_per_particle) {
  if (probe.build < 0) return false;
  const double life = probe.life > 0 ? static_cast<double>(probe.life) : 4.0;
  const double w = 0.5 + 2.0 * events_per_particle;
  return kBuildCost + w * probe.short_entries < kBuildCost / life + w * probe.long_entries;
}

/// The skin, in steps s, of the build numbered `build` (list_builds before it): the short one
/// when it pays and the last probe is recent, else the long one (a probe).
inline double skin_steps(const SkinProbe& probe, std::int64_t build, double events_per_particle) {
  const bool recent = probe.build >= 0 && build - probe.build < kProbeEvery;
  return recent && short_skin_pays(probe, events_per_particle) ? kShortSkinSteps : kLongSkinSteps;
}

} // namespace fluidem::hardsphere
