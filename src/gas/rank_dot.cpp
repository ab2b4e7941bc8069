#define OMPI_SKIP_MPICXX 1
#define MPICH_SKIP_MPICXX 1
#include "gas/rank_dot.hpp"
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <mpi.h>

namespace fluidem::gas {

double rank_dot(int comm, long total_entries, const double* a, const double* b, std::size_t n) {
  double m = 0.0; // max |a_i b_i| (NaN or inf: stays inf)
  for (std::size_t i = 0; i < n; ++i) {
    const double t = std::abs(a[i] * b[i]);
    m = std::isfinite(t) ? std::max(m, t) : std::numeric_limits<double>::infinity();
  }
  const MPI_Comm c = comm == kThisProcessAlone ? MPI_COMM_NULL : MPI_Comm_f2c(comm);
  if (c != MPI_COMM_NULL) MPI_Allreduce(MPI_IN_PLACE, &m, 1, MPI_DOUBLE, MPI_MAX, c);
  if (!std::isfinite(m)) return std::numeric_limits<double>::quiet_NaN();
  if (m == 0.0) return 0.0;
  // |a_i b_i| 2^s < 2^(ilogb(m) + 1 + s) = 2^min(60 - bits(N), 51): N of them stay below 2^60,
  // and each is below 2^51, where adding and subtracting 1.5 2^52 rounds it to the nearest
  // integer (ties to even) exactly, without a call to llround.
  const auto bits_n =
      static_cast<int>(std::bit_width(static_cast<unsigned long>(std::max(total_entries, 1L))));
  const int s = std::min(60 - bits_n, 51) - (std::ilogb(m) + 1); // |s| <= 1126
  // 2^s as two factors, each a normal double (2^s itself is not for m below ~2^-970); scaling
  // by powers of two is exact.
  const double scale1 = std::ldexp(1.0, s / 2), scale2 = std::ldexp(1.0, s - s / 2);
  constexpr double kRound = 0x1.8p52;
  std::int64_t sum = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double v = a[i] * b[i] * scale1 * scale2;
    sum += static_cast<std::int64_t>((v + kRound) - kRound);
  }
  if (c != MPI_COMM_NULL) MPI_Allreduce(MPI_IN_PLACE, &sum, 1, MPI_INT64_T, MPI_SUM, c);
  return std::ldexp(static_cast<double>(sum), -s);
}

} // namespace fluidem::gas
