#include "io/FibreFile.hpp"

#include <fstream>
#include <sstream>

namespace smoothedSolid {

std::vector<Vec3> readFibreDirections(const std::string& fileName, int nElements)
{
    std::ifstream in(fileName);
    if (!in) throw Error("cannot read the fibre direction file " + fileName);
    std::vector<Vec3> d;
    std::string line;
    int lineNo = 0;
    while (std::getline(in, line)) {
        ++lineNo;
        const auto hash = line.find('#');
        if (hash != std::string::npos) line.erase(hash);
        std::istringstream ls(line);
        Vec3 v;
        if (!(ls >> v.x())) continue;  // blank or comment
        std::string rest;
        if (!(ls >> v.y() >> v.z()) || (ls >> rest) || !v.allFinite() || !(v.norm() > 0)) {
            throw Error(fileName + " line " + std::to_string(lineNo) +
                        ": expected three numbers of a non-zero direction");
        }
        d.push_back(v.normalized());
    }
    if (static_cast<int>(d.size()) != nElements) {
        throw Error(fileName + " holds " + std::to_string(d.size()) + " directions for " +
                    std::to_string(nElements) +
                    " elements of the mesh (one per element, in its order)");
    }
    return d;
}

}  // namespace smoothedSolid
