// smoothedSolidRun <case file>: structure-only runs of the smoothedSolid
// library (case format: io/CaseFile.hpp)
#include "io/SolidRun.hpp"

#include <iostream>

int main(int argc, char* argv[])
{
    if (argc != 2 || std::string(argv[1]) == "-h" || std::string(argv[1]) == "--help") {
        std::cerr << "usage: smoothedSolidRun <case file>\n";
        return argc == 2 ? 0 : 2;
    }
    try {
        smoothedSolid::SolidRun run(argv[1]);
        const long steps = run.run(std::cout);
        std::cout << "smoothedSolidRun: t = " << run.solid().time() << " after " << steps
                  << " sub-steps\n";
        for (std::size_t i = 0; i < run.probeNames().size(); ++i) {
            const auto u = run.probeDisplacement(i);
            std::cout << "probe " << run.probeNames()[i] << " displacement " << u.x() << " "
                      << u.y() << " " << u.z() << "\n";
        }
    } catch (const std::exception& e) {
        std::cerr << "smoothedSolidRun: " << e.what() << "\n";
        return 1;
    }
    return 0;
}
