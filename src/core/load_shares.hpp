// How the threads of a loop over contiguous work (the contact loop's slab groups) share it out,
// measured and adjusted step by step: thread t takes the work between the fractions bounds[t]
// and bounds[t + 1] of the particles; after each step the boundaries move toward equal busy
// times (each thread's seconds of work per particle, smoothed over steps). Even shares by
// particle count leave one thread waiting for the other at the end of each step whenever the
// work per particle differs between the parts of a bed (contacts, walls, slabs per particle),
// or when a shared machine slows one core. The boundaries change which thread computes what,
// never the order of the operations: results stay the same whatever they are.
// (The same idea as LAMMPS' "fix balance" with time weights, within one process.)
#pragma once
#include <algorithm>
#include <vector>

namespace fluidem {

class LoadShares {
public:
  /// The boundaries for a team of nt threads, as fractions of the particles (bounds[0] = 0,
  /// bounds[nt] = 1): the last update's, or even shares when the team size changed (allocates
  /// only then). Called before the region; the threads read them, each records its step.
  const double* prepare(int nt) {
    if (nt != nt_) {
      nt_ = nt;
      bounds_.resize(static_cast<std::size_t>(nt) + 1);
      for (int t = 0; t <= nt; ++t) bounds_[t] = static_cast<double>(t) / nt;
      rate_.assign(static_cast<std::size_t>(nt), 0.0);
      slots_.assign(static_cast<std::size_t>(nt), Slot{});
    }
    for (Slot& s : slots_) s = Slot{};
    return bounds_.data();
  }
  int threads() const { return nt_; }
  /// Thread t worked `busy` seconds on `particles` particles this step (its own slot: no race).
  void record(int t, double particles, double busy) {
    slots_[t].particles = particles;
    slots_[t].busy = busy;
  }
  /// After the region, on one thread: smooth each thread's seconds per particle and set the
  /// boundaries so that each thread's share is proportional to its speed.
  void update() {
    if (nt_ < 2) return;
    double mean = 0.0; // of this step's measured rates
    int known = 0;
    for (int t = 0; t < nt_; ++t) {
      const Slot& s = slots_[t];
      if (s.particles <= 0.0 || s.busy <= 0.0) continue;
      double r = s.busy / s.particles;
      double& rate = rate_[t];
      // One step's outlier (the core taken away for a moment) moves the estimate by a
      // bounded amount.
      if (rate > 0.0) r = std::clamp(r, 0.5 * rate, 2.0 * rate);
      rate = rate > 0.0 ? rate + kSmoothing * (r - rate) : r;
      mean += rate, ++known;
    }
    if (known == 0) return;
    mean /= known;
    // A thread that had no work this step (its share fell between two group boundaries) is not
    // measured: its estimate moves toward the others', so that its share grows back.
    for (int t = 0; t < nt_; ++t) {
      const Slot& s = slots_[t];
      if (s.particles > 0.0 && s.busy > 0.0) continue;
      rate_[t] = rate_[t] > 0.0 ? rate_[t] + kSmoothing * (mean - rate_[t]) : mean;
    }
    double total = 0.0;
    std::vector<double>& speed = speed_;
    speed.resize(static_cast<std::size_t>(nt_));
    for (int t = 0; t < nt_; ++t) total += speed[t] = 1.0 / rate_[t];
    // Each share at least a quarter of an even one.
    const double least = 0.25 / nt_;
    double sum = 0.0;
    for (int t = 0; t < nt_; ++t) sum += speed[t] = std::max(speed[t] / total, least);
    for (int t = 0; t < nt_; ++t) bounds_[t + 1] = bounds_[t] + speed[t] / sum;
    bounds_[nt_] = 1.0;
  }

private:
  static constexpr double kSmoothing = 0.05; // per step: about 20 steps' memory
  struct alignas(64) Slot {                  // one cache line per thread's record
    double particles = 0.0, busy = 0.0;
  };
  int nt_ = 0;
  std::vector<double> bounds_, rate_, speed_;
  std::vector<Slot> slots_;
};

} // namespace fluidem
