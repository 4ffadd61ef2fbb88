// A structure-only run described by a case file (io/CaseFile.hpp): builds
// the mesh, material, solid, loads and outputs, then advances to endTime
// writing VTU files and probe histories. The run advances by
// ExplicitSolid::advance() in chunks that end exactly at the output events
// (write times, probe times, endTime); within a chunk the solid sub-cycles
// at its current stable step (halved while contact is near), and the
// time-dependent loads are updated at the start of every sub-step.
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

    // Advance to endTime (or until steady); returns the number of sub-steps
    long run(std::ostream& log);

    // The sub-steps of one write interval (from the previous write time, or
    // the start, to 'time'), one entry per write time reached by run()
    struct WriteInterval {
        double time;         // the write time
        long subSteps;       // sub-steps taken in the interval
        double minSubStep;   // smallest and largest sub-step used there
        double maxSubStep;
        double stableStep;   // the solid's stable step at the write time
    };
    const std::vector<WriteInterval>& writeIntervals() const { return intervals_; }
    double probeInterval() const { return probeInterval_; }

    ExplicitSolid& solid() { return *solid_; }
    // Displacement of probe i at the end of the run
    Vec3 probeDisplacement(std::size_t i) const;
    const std::vector<std::string>& probeNames() const { return probeNames_; }

private:
    using Ramp = std::function<double(double)>;
    Ramp ramp(const CaseEntry& e, std::size_t first) const;
    void applyLoads(double t);
    void writeProbes();
    // Sub-step bookkeeping: the load update marks the start of each sub-step
    // (a sub-step lasts until the next start, or the end of its chunk)
    void subStepStarted(double t);
    void chunkEnded();
    void noteSubStep(double h);

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
    double endTime_ = 0, writeInterval_ = 0, probeInterval_ = 0, steadyTol_ = 0;
    double stepStart_ = 0;
    bool stepOpen_ = false;
    WriteInterval current_{};
    std::vector<WriteInterval> intervals_;
    double lastProbeTime_ = -1;
    std::string outputDir_;
    std::unique_ptr<VtuSeries> vtu_;
    std::ofstream probeFile_;
};

}  // namespace smoothedSolid
