// Process-wide HDF5 set-up for the fluidem program.
#pragma once

namespace fluidem {

/// Call first in main(): HDF5 installs no exit handler. Every file fluidem opens is closed by
/// its owner before main returns; what the handler would do is close files again, and for a
/// file whose close already failed (a full disk) HDF5 1.10's handler crashes (SIGSEGV in
/// H5F__close_cb), turning a clean "disk full" exit into a segmentation fault.
void skip_hdf5_exit_cleanup();

} // namespace fluidem
