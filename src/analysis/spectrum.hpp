// Power spectral density of a sampled signal (a pressure probe) by Welch's method, and its
// dominant frequency [Chang08 §4.2: the PSD of the pressure fluctuations 150 mm above the
// distributor peaks at 1.82 Hz]. Welch (1967): the signal is cut into segments of L samples
// overlapping by half, each segment has its mean removed and is multiplied by a Hann window
// w_n = sin^2(pi n / L) (periodic form), the periodograms |FFT|^2 are averaged, and the
// one-sided density is scaled so that sum_k PSD_k df = the mean square of the detrended,
// windowed-power-corrected signal (Parseval): PSD_k = c |X_k|^2 / (f_s sum_n w_n^2), c = 2
// except at f = 0 and at the Nyquist frequency (c = 1). A sinusoid of amplitude A then carries
// A^2 / 2 of power, white noise of variance s^2 a flat 2 s^2 / f_s. FFTs by FFTW3.
#pragma once
#include <cstddef>
#include <vector>

namespace fluidem {

struct Spectrum {
  std::vector<double> frequency; ///< Hz, k f_s / L, k = 0 .. L/2
  std::vector<double> psd;       ///< unit^2 / Hz
  double resolution = 0.0;       ///< df = f_s / L, Hz
  int segments = 0;              ///< periodograms averaged
  /// Frequency of the largest PSD value above f = 0, refined by a parabola through the peak
  /// bin and its neighbours (Hz).
  double dominant_frequency = 0.0;
  /// sum_k PSD_k df: the power (mean square of the fluctuation), unit^2.
  double power() const;
};

/// Welch PSD of `signal` sampled at `sample_rate` (Hz) with segments of `segment_length` samples
/// (even, >= 8, <= signal size). Throws std::invalid_argument for bad arguments or a non-finite
/// sample.
Spectrum welch_psd(const std::vector<double>& signal, double sample_rate,
                   std::size_t segment_length);

} // namespace fluidem
