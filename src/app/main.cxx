#include "app/cli.hpp"
#include "output/hdf5_process.hpp"

int main(int argc, char** argv) {
  fluidem::skip_hdf5_exit_cleanup();
  return fluidem::run_cli(argc, argv);
}
