// Benchmark (not a test): time of one explicit sub-step of the selective
// FS/NS-FEM per tetrahedron, on structured box meshes of about 10k, 100k and
// 1M tets, against FEM-T4 on the same mesh, and with self contact switched
// on (every boundary node searched against the boundary triangles each step),
// all on one thread; then the selective scheme on all threads and its
// speed-up.
//   smoothedSolidBench [maxTets]     (default 1.1e6)
#include "Parallel.hpp"
#include "dynamics/ExplicitSolid.hpp"

#include <chrono>
#include <cstdio>
#include <cstdlib>

using namespace smoothedSolid;

namespace {

double nsPerTetStep(Formulation form, int n, int* tetsOut, bool contact = false)
{
    TetMesh mesh = TetMesh::box(n, n, n, [](const Vec3& x) { return x; });
    *tetsOut = mesh.nElements();
    ExplicitSolid solid(std::move(mesh),
                        std::make_shared<MooneyRivlin>(1000.0, 200.0, 50000.0, 1000.0),
                        {form, 0.8, 0.0});
    solid.fix("xmin");
    solid.addFollowerPressure("xmax", [](double) { return 100.0; });
    if (contact) solid.enableContact({true, true});
    const double dt = solid.stableTimeStep();
    for (int k = 0; k < 3; ++k) solid.step(dt);  // warm up
    const int steps = std::max(5, int(2e7 / *tetsOut));
    const auto t0 = std::chrono::steady_clock::now();
    for (int k = 0; k < steps; ++k) solid.step(dt);
    const auto t1 = std::chrono::steady_clock::now();
    return std::chrono::duration<double, std::nano>(t1 - t0).count() / steps / *tetsOut;
}

}  // namespace

int main(int argc, char* argv[])
{
    const double maxTets = argc > 1 ? std::atof(argv[1]) : 1.1e6;
    const int threads = numThreads();
    std::printf("ns per tet per sub-step; 1 thread unless stated\n");
    std::printf("%10s %10s %10s %8s %16s %14s %10s\n", "tets", "selective", "FEM-T4", "ratio",
                "selective+self", "selective", "speed-up");
    std::printf("%10s %10s %10s %8s %16s %11s %2d %10s\n", "", "", "", "", "contact",
                "threads", threads, "");
    for (int n : {12, 26, 55}) {
        if (6.0 * n * n * n > maxTets) break;
        int tets = 0;
        setNumThreads(1);
        const double sel = nsPerTetStep(Formulation::Selective, n, &tets);
        const double fem = nsPerTetStep(Formulation::FEM_T4, n, &tets);
        const double con = nsPerTetStep(Formulation::Selective, n, &tets, true);
        setNumThreads(threads);
        const double par = nsPerTetStep(Formulation::Selective, n, &tets);
        std::printf("%10d %10.1f %10.1f %8.2f %16.1f %14.1f %10.2f\n", tets, sel, fem, sel / fem, con,
                    par, sel / par);
    }
    std::printf("target: selective <= 200 ns per tet per sub-step on one core "
                "(121k-tet leaflets in under 25 ms)\n");
    return 0;
}
