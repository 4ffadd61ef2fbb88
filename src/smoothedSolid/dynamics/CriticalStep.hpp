// The critical time step of the central difference, computed (not
// bounded): dt_crit = 2 / omega_max, omega_max^2 the largest eigenvalue of
// M^-1 K_T(u), by the Lanczos method on M^-1/2 K_T M^-1/2 with full
// reorthogonalisation (Golub & Van Loan, Matrix Computations, 4th ed.,
// Sect. 10.1); K_T v by central differences of the internal force. All
// nodes free (constraints only raise the critical step). Costs two internal
// force evaluations per iteration: a check for tests and benchmarks, not
// for every step (ExplicitSolid::stableTimeStep() is the cheap bound).
#pragma once

#include "dynamics/ExplicitSolid.hpp"

namespace smoothedSolid {

struct CriticalStep {
    double dt;          // 2 / omega_max
    double omega2;      // largest Ritz value
    double change;      // relative change of it over the last 10 iterations
    int iterations;
};

CriticalStep criticalTimeStep(const ExplicitSolid& solid, const std::vector<Vec3>& u,
                              int iterations = 120);

}  // namespace smoothedSolid
