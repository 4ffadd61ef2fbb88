// A structure-only run described by a case file (io/CaseFile.hpp): builds
// the mesh, material, solid, loads and outputs, then advances to endTime
// writing VTU files and probe histories.
#pragma once

#include "dynamics/ExplicitSolid.hpp"
#include "io/CaseFile.hpp"
#include "io/VtuWriter.hpp"

#include <fstream>
#include <memory>
#include <string>
#include <vector>

namespace smoothedSolid {

class SolidRun {
public:
    explicit SolidRun(const std::string& caseFile);

    // Advance to endTime (or until steady); returns the number of steps
    long run(std::ostream& log);

    ExplicitSolid& solid() { return *solid_; }
    // Displacement of probe i at the end of the run
    Vec3 probeDisplacement(std::size_t i) const;
    const std::vector<std::string>& probeNames() const { return probeNames_; }

private:
    using Ramp = std::function<double(double)>;
    Ramp ramp(const CaseEntry& e, std::size_t first) const;
    void applyLoads();
    void writeProbes();

    CaseFile case_;
    std::unique_ptr<ExplicitSolid> solid_;
    std::vector<std::string> probeNames_;
    // Probe: element containing the point (reference configuration) and the
    // point's barycentric weights there
    struct Probe {
        Tet nodes;
        std::array<double, 4> w;
    };
    std::vector<Probe> probes_;
    struct Traction {
        std::vector<Vec3> nodal;  // at full load
        Ramp s;
    };
    std::vector<Traction> tractions_;
    Vec3 gravity_ = Vec3::Zero();
    Ramp gravityRamp_;
    double endTime_ = 0, writeInterval_ = 0, steadyTol_ = 0;
    std::string outputDir_;
    std::unique_ptr<VtuSeries> vtu_;
    std::ofstream probeFile_;
};

}  // namespace smoothedSolid
