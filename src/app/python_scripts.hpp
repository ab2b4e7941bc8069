// Running fluidem's Python scripts (python/*.py: pictures, the validation report) with Debian's
// interpreter. The scripts are looked for in $FLUIDEM_PYTHON_DIR, then in the source tree this
// binary was built from (<source>/python, from this file's compile-time path: works from any
// build directory of the tree), then next to an installed binary (<bin>/../share/fluidem/python).
// The interpreter is $FLUIDEM_PYTHON, else /usr/bin/python3 (which has matplotlib/h5py/numpy;
// another python3 may come first on PATH).
#pragma once
#include <filesystem>
#include <string>
#include <vector>

namespace fluidem {

/// The folder holding `script`; InputError listing the places looked in.
std::filesystem::path find_python_script_dir(const std::string& script, const char* argv0);

/// The path of this running binary (/proc/self/exe, else argv0).
std::filesystem::path own_binary_path(const char* argv0);

/// Run `python script args...`; returns the script's exit code (1 if it could not run).
int run_python_script(const std::filesystem::path& script, const std::vector<std::string>& args);

/// Replace this process by `python script args...` (signals reach the script itself: a stopped
/// `fluidem validate` stops its run with a checkpoint); returns only when that fails (127).
int exec_python_script(const std::filesystem::path& script, const std::vector<std::string>& args);

} // namespace fluidem
