#include "analysis/spectrum.hpp"

#include <fftw3.h>

#include <cmath>
#include <complex>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>

namespace fluidem {

namespace {
constexpr double pi = 3.14159265358979323846;

/// FFTW's planner is not thread-safe: plans are made under this lock.
std::mutex& planner_mutex() {
  static std::mutex m;
  return m;
}

struct PlanDeleter {
  void operator()(fftw_plan_s* p) const {
    std::lock_guard<std::mutex> lock(planner_mutex());
    fftw_destroy_plan(p);
  }
};
} // namespace

double Spectrum::power() const {
  double s = 0.0;
  for (double v : psd) s += v * resolution;
  return s;
}

Spectrum welch_psd(const std::vector<double>& signal, double sample_rate,
                   std::size_t segment_length) {
  const std::size_t L = segment_length, n = signal.size();
  if (!(sample_rate > 0.0) || !std::isfinite(sample_rate))
    throw std::invalid_argument("welch_psd: the sample rate must be > 0 Hz");
  if (L < 8 || L % 2 != 0)
    throw std::invalid_argument("welch_psd: the segment length must be even and >= 8 (got " +
                                std::to_string(L) + ")");
  if (L > n)
    throw std::invalid_argument("welch_psd: the segment length " + std::to_string(L) +
                                " exceeds the signal's " + std::to_string(n) + " samples");
  for (std::size_t i = 0; i < n; ++i)
    if (!std::isfinite(signal[i]))
      throw std::invalid_argument("welch_psd: sample " + std::to_string(i) + " is not finite");

  std::vector<double> w(L), seg(L);
  double w2 = 0.0;
  for (std::size_t i = 0; i < L; ++i) {
    const double s = std::sin(pi * static_cast<double>(i) / static_cast<double>(L));
    w[i] = s * s; // periodic Hann
    w2 += w[i] * w[i];
  }
  const std::size_t nf = L / 2 + 1;
  std::vector<std::complex<double>> spec(nf);
  std::unique_ptr<fftw_plan_s, PlanDeleter> plan;
  {
    std::lock_guard<std::mutex> lock(planner_mutex());
    plan.reset(fftw_plan_dft_r2c_1d(static_cast<int>(L), seg.data(),
                                    reinterpret_cast<fftw_complex*>(spec.data()), FFTW_ESTIMATE));
  }
  if (!plan) throw std::runtime_error("welch_psd: FFTW could not make a plan");

  Spectrum out;
  out.resolution = sample_rate / static_cast<double>(L);
  out.frequency.resize(nf);
  out.psd.assign(nf, 0.0);
  for (std::size_t k = 0; k < nf; ++k) out.frequency[k] = static_cast<double>(k) * out.resolution;
  const std::size_t hop = L / 2;
  for (std::size_t start = 0; start + L <= n; start += hop) {
    double mean = 0.0;
    for (std::size_t i = 0; i < L; ++i) mean += signal[start + i];
    mean /= static_cast<double>(L);
    for (std::size_t i = 0; i < L; ++i) seg[i] = (signal[start + i] - mean) * w[i];
    fftw_execute(plan.get());
    for (std::size_t k = 0; k < nf; ++k) out.psd[k] += std::norm(spec[k]);
    ++out.segments;
  }
  const double scale = 1.0 / (sample_rate * w2 * static_cast<double>(out.segments));
  for (std::size_t k = 0; k < nf; ++k) {
    const double c = (k == 0 || k == nf - 1) ? 1.0 : 2.0; // one-sided
    out.psd[k] *= c * scale;
  }
  // Dominant frequency: the largest bin above 0, refined by the parabola through it and its
  // neighbours (vertex offset (a - c) / (2 (a - 2b + c)) bins).
  std::size_t peak = 1;
  for (std::size_t k = 2; k < nf; ++k)
    if (out.psd[k] > out.psd[peak]) peak = k;
  double offset = 0.0;
  if (peak + 1 < nf) {
    const double a = out.psd[peak - 1], b = out.psd[peak], c = out.psd[peak + 1];
    const double den = a - 2.0 * b + c;
    if (den < 0.0) offset = 0.5 * (a - c) / den;
  }
  out.dominant_frequency = (static_cast<double>(peak) + offset) * out.resolution;
  return out;
}

} // namespace fluidem
