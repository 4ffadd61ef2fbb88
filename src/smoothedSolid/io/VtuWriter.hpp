// VTK XML output of the solid: one binary .vtu file per written time and a
// .pvd collection, opened by ParaView, VisIt or Python (meshio, vtk).
#pragma once

#include "dynamics/ExplicitSolid.hpp"

#include <map>
#include <string>
#include <vector>

namespace smoothedSolid {

class VtuSeries {
public:
    // Files <directory>/<name>_<index>.vtu and <directory>/<name>.pvd
    VtuSeries(std::string directory, std::string name);

    // Extra nodal fields, e.g. "contactPressure" -> one value per node,
    // or 3 per node for vectors
    using NodalFields = std::map<std::string, std::vector<double>>;

    // Write the current configuration with displacement, velocity, external
    // force, Cauchy stress, von Mises, maximum principal stress and J; with
    // fibre directions set, per element the current fibre direction
    // F a0 / |F a0| ("fibreDirection") and stretch |F a0| ("fibreStretch")
    void write(const ExplicitSolid& solid, const NodalFields& extra = {});

    // The same, as <directory>/<name>_<label>.vtu (e.g. a caller's time
    // name) at collection time 'time'
    void write(const ExplicitSolid& solid, const NodalFields& extra, const std::string& label,
               double time);

    // Continue the collection already in <directory>/<name>.pvd (a
    // restarted run): its data sets up to and including 'time' are kept,
    // later ones dropped. No file: an empty collection. A file that is not
    // a collection written by this class throws naming it.
    void resume(double time);

    int count() const { return static_cast<int>(times_.size()); }

private:
    void writePvd() const;

    std::string directory_, name_;
    std::vector<std::pair<double, std::string>> times_;
};

}  // namespace smoothedSolid
