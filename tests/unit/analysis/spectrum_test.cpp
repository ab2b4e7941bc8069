// Welch PSD (analysis/spectrum.hpp) against exact results:
//  - Parseval: a sinusoid of amplitude A on a bin frequency carries A^2/2 of power,
//    sum PSD df = A^2/2 to 1e-12 relative (the Hann window's leakage stays within the spectrum);
//  - a sinusoid at 1.82 Hz (Chang08 §4.2's published peak) sampled at 100 Hz for 60 s, 1024-sample
//    segments (df = 0.098 Hz): the dominant frequency within 0.02 Hz (a fifth of a bin, from
//    the parabolic refinement), also with white noise of 3x the sinusoid's power added;
//  - white noise of variance s^2: the mean PSD level is 2 s^2 / f_s within 5% (40000 samples:
//    the statistical error of the average over 77 segments and 512 bins is below 1%);
//  - a constant offset does not leak into the spectrum (each segment's mean is removed);
//  - bad arguments are errors.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>

#include "analysis/spectrum.hpp"

namespace fluidem {
namespace {
constexpr double pi = 3.14159265358979323846;

std::vector<double> sine(double amplitude, double f, double fs, std::size_t n,
                         double offset = 0.0) {
  std::vector<double> s(n);
  for (std::size_t i = 0; i < n; ++i)
    s[i] = offset + amplitude * std::sin(2.0 * pi * f * static_cast<double>(i) / fs + 0.3);
  return s;
}

TEST(Spectrum, ParsevalForASinusoidOnABin) {
  const double fs = 256.0, A = 3.0;
  const std::size_t L = 256;
  const Spectrum s = welch_psd(sine(A, 16.0, fs, 4096, 100.0), fs, L);
  EXPECT_EQ(s.segments, 31);
  EXPECT_NEAR(s.power() / (0.5 * A * A), 1.0, 1e-12);
  EXPECT_NEAR(s.dominant_frequency, 16.0, 1e-9);
  EXPECT_LT(s.psd[0], 1e-20); // the offset of 100 is removed
}

TEST(Spectrum, DominantFrequencyOfAProbeLikeSignal) {
  const double fs = 100.0, f0 = 1.82;
  std::vector<double> x = sine(50.0, f0, fs, 6000);
  EXPECT_NEAR(welch_psd(x, fs, 1024).dominant_frequency, f0, 0.02);
  std::mt19937_64 rng(1);
  std::normal_distribution<double> noise(0.0, 50.0 * std::sqrt(1.5)); // 3x the sine's power
  for (double& v : x) v += noise(rng);
  EXPECT_NEAR(welch_psd(x, fs, 1024).dominant_frequency, f0, 0.02);
}

TEST(Spectrum, WhiteNoiseLevel) {
  const double fs = 1000.0, sigma = 2.0;
  std::mt19937_64 rng(2);
  std::normal_distribution<double> noise(0.0, sigma);
  std::vector<double> x(40000);
  for (double& v : x) v = noise(rng);
  const Spectrum s = welch_psd(x, fs, 1024);
  double mean = 0.0;
  for (std::size_t k = 1; k + 1 < s.psd.size(); ++k) mean += s.psd[k];
  mean /= static_cast<double>(s.psd.size() - 2);
  EXPECT_NEAR(mean / (2.0 * sigma * sigma / fs), 1.0, 0.05);
}

TEST(Spectrum, BadArgumentsAreErrors) {
  const std::vector<double> x(100, 1.0);
  EXPECT_THROW(welch_psd(x, 0.0, 16), std::invalid_argument);
  EXPECT_THROW(welch_psd(x, 10.0, 7), std::invalid_argument);
  EXPECT_THROW(welch_psd(x, 10.0, 200), std::invalid_argument);
  std::vector<double> y = x;
  y[5] = std::nan("");
  EXPECT_THROW(welch_psd(y, 10.0, 16), std::invalid_argument);
}

} // namespace
} // namespace fluidem
