// Ctrl-C (SIGINT) or SIGTERM during run, render or movie: the command stops after the current
// step or frame and unwinds, so that temporary files are removed and only complete images
// remain. A second signal ends the program at once.
#pragma once

namespace bsmpm::cli {

void catch_interruptions();
bool interrupted();
// The exit status of a command stopped by that signal: 128 + its number (130 for SIGINT, 143
// for SIGTERM), as a shell reports a program the signal killed.
int interrupted_exit_status();

}  // namespace bsmpm::cli
