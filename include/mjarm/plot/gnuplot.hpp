#pragma once
/// @file
/// Runs Debian's gnuplot (package gnuplot-nox) on a script file as a child process, with a
/// timeout, and reports its messages when it fails.

#include <filesystem>
#include <string>
#include <string_view>

namespace mjarm::plot {

/// @p text as one gnuplot string expression that evaluates to exactly @p text: the only way text
/// reaches a gnuplot script (titles, labels, file names, comments).
///
/// Printable characters go in single quotes, where gnuplot substitutes nothing (no backquote
/// command, no `@` macro, no escape). A quote and a control character (newline, carriage
/// return, tab, …) go as an octal escape in a double-quoted piece that holds nothing else
/// (gnuplot 5.4 misreads a run of doubled quotes), joined by gnuplot's `.` operator:
/// `a<newline>b` becomes `'a'."\012".'b'`. The result holds no line break and does not end
/// with a backslash, so it can neither end a command nor continue a comment. NUL characters are
/// dropped (gnuplot strings end at NUL). Use it wherever gnuplot expects a string (`set output`,
/// `set title`, `set label`, `plot FILE … title`). A file name given to gnuplot must also be
/// absolute: gnuplot reads a name starting with '<' or '|' as a shell command.
std::string gnuplot_string(std::string_view text);

/// The `gnuplot` executable found on $PATH.
/// @throws Error when there is none, naming the Debian package to install (gnuplot-nox).
std::filesystem::path find_gnuplot();

/// Runs `gnuplot SCRIPT` and waits for it (the working directory is not changed: scripts should
/// name their files by absolute path).
/// @param script a gnuplot script
/// @param timeout_s how long gnuplot may run [s] before it is killed
/// @throws Error when gnuplot is missing (see `find_gnuplot`), cannot start, exits with an
///         error (its messages are quoted), runs past the timeout, or an interrupt arrives
///         while it runs (SIGINT/SIGTERM under an `InterruptGuard`, mjarm/interrupt.hpp): gnuplot
///         is killed then.
void run_gnuplot(const std::filesystem::path& script, double timeout_s = 60.0);

}  // namespace mjarm::plot
