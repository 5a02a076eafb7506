// Ctrl-C (SIGINT) or SIGTERM during render or movie: the command stops after the current
// frame and unwinds, so that temporary files are removed and only complete images remain.
// A second signal ends the program at once.
#pragma once

namespace bsmpm::cli {

void catch_interruptions();
bool interrupted();

}  // namespace bsmpm::cli
