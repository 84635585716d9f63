#pragma once
/// @file
/// Runs Debian's gnuplot (package gnuplot-nox) on a script file as a child process, with a
/// timeout, and reports its messages when it fails.

#include <filesystem>
#include <string>

namespace mjarm::plot {

/// The `gnuplot` executable found on $PATH.
/// @throws Error when there is none, naming the Debian package to install (gnuplot-nox).
std::filesystem::path find_gnuplot();

/// Runs `gnuplot SCRIPT` and waits for it (the working directory is not changed: scripts should
/// name their files by absolute path).
/// @param script a gnuplot script
/// @param timeout_s how long gnuplot may run [s] before it is killed
/// @throws Error when gnuplot is missing (see `find_gnuplot`), cannot start, exits with an
///         error (its messages are quoted) or runs past the timeout.
void run_gnuplot(const std::filesystem::path& script, double timeout_s = 60.0);

}  // namespace mjarm::plot
