// Point-to-point hand-off between the threads of one OpenMP region: per work item (the contact
// loop's slab groups), the step whose phase 0 and phase 1 it has finished. A thread that needs
// an item's phase done waits for that item alone instead of for every thread at a barrier, so a
// thread held up for a moment (a shared machine's other work) holds up only the threads that
// need its items, and only once their own work runs out.
#pragma once
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <thread>

namespace fluidem {

class PhaseProgress {
public:
  PhaseProgress() = default;
  /// A copy starts without marks: they mean something only within one step.
  PhaseProgress(const PhaseProgress&) {}
  PhaseProgress& operator=(const PhaseProgress&) { return *this; }

  /// Start a step over `items` items (called before the region, by one thread): returns the
  /// step's mark, which no item holds yet. Allocates only when `items` exceeds every earlier
  /// step's.
  std::uint64_t start(std::size_t items) {
    if (items > capacity_) {
      capacity_ = std::max(items, 2 * capacity_);
      marks_ = std::make_unique<Marks[]>(capacity_); // all 0, below any step's mark
    }
    return ++step_;
  }
  /// Item `item` has finished `phase` (0 or 1) of step `step`: what it wrote is visible to a
  /// thread that then waits for it.
  void finish(std::size_t item, int phase, std::uint64_t step) {
    marks_[item].phase[phase].store(step, std::memory_order_release);
  }
  /// Wait until item `item` has finished `phase` of step `step` (spinning, then yielding the core
  /// to a thread that may be the one awaited, when there are more threads than cores). Returns
  /// the seconds waited (0 when the item was done: then without reading the clock).
  double wait(std::size_t item, int phase, std::uint64_t step) const {
    const std::atomic<std::uint64_t>& mark = marks_[item].phase[phase];
    if (mark.load(std::memory_order_acquire) == step) return 0.0;
    const auto t0 = std::chrono::steady_clock::now();
    for (unsigned spins = 0; mark.load(std::memory_order_acquire) != step; ++spins) {
      if (spins < kSpins)
        pause();
      else
        std::this_thread::yield();
    }
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }
  std::size_t bytes() const { return capacity_ * sizeof(Marks); }

private:
  static constexpr unsigned kSpins = 1u << 14; // pause instructions before the first yield
  static void pause() {
#if defined(__x86_64__) || defined(__i386__)
    __builtin_ia32_pause();
#endif
  }
  // One cache line per item: its marks are written by the thread that runs it and read by the
  // others.
  struct alignas(64) Marks {
    std::atomic<std::uint64_t> phase[2] = {0, 0};
  };
  std::unique_ptr<Marks[]> marks_;
  std::size_t capacity_ = 0;
  std::uint64_t step_ = 0;
};

} // namespace fluidem
