// The fluidem command line: `fluidem run`, `fluidem check`, --version, --help.
// Exit codes: 0 success, 2 invalid input (case file or command line), 3 run went unstable.
#pragma once

namespace fluidem {

int run_cli(int argc, char** argv);

} // namespace fluidem
