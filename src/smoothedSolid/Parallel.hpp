// Threads of the library's OpenMP loops (internal force and time update).
// Without OpenMP at build time everything runs on one thread and these
// report 1. The default is OpenMP's (OMP_NUM_THREADS, else all cores); a
// caller that runs one solid per MPI rank should set it to the cores per rank.
#pragma once

namespace smoothedSolid {

int numThreads();
void setNumThreads(int n);  // n >= 1

// Whether the library was compiled with OpenMP; if not, numThreads() is
// always 1 and setNumThreads() only checks its argument
bool builtWithOpenMP();

}  // namespace smoothedSolid
