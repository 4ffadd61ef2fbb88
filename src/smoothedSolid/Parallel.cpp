#include "Parallel.hpp"

#include "Types.hpp"

#include <string>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace smoothedSolid {

int numThreads()
{
#ifdef _OPENMP
    return omp_get_max_threads();
#else
    return 1;
#endif
}

bool builtWithOpenMP()
{
#ifdef _OPENMP
    return true;
#else
    return false;
#endif
}

void setNumThreads(int n)
{
    if (n < 1) throw Error("setNumThreads: need at least one thread, got " + std::to_string(n));
#ifdef _OPENMP
    omp_set_num_threads(n);
#endif
}

}  // namespace smoothedSolid
