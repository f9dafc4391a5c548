// scansurf CLI: `scansurf batch`, many inputs, each one run of this program (batch.cpp).
#pragma once

namespace scansurf::cli {

// argv[1] is "batch". Returns the exit code: 0 when every input is done (or was already),
// else the first failed input's code (after all the others ran); 2 for a bad command line.
int runBatch(int argc, char** argv);

}  // namespace scansurf::cli
