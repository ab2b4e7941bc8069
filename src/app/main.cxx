#include "app/cli.hpp"

int main(int argc, char** argv) {
  return fluidem::run_cli(argc, argv);
}
