// The fluidem command line: `fluidem run` (also --restart), `fluidem check`, `fluidem analyse`,
// `fluidem plot`, --version, --help.
// Exit codes: 0 success, 2 invalid input (case file, command line, output directory), 3 run went
// unstable, 130 / 143 stopped by SIGINT / SIGTERM after writing a checkpoint.
#pragma once

namespace fluidem {

int run_cli(int argc, char** argv);

} // namespace fluidem
