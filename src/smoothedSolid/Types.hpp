// smoothedSolid: standalone smoothed finite element solid library.
// Common types. No OpenFOAM anywhere in this library.
#pragma once

#include <Eigen/Dense>

#include <stdexcept>
#include <string>

namespace smoothedSolid {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

// Every error the library reports: the message names the file, entry, set
// or element concerned and what to do.
class Error : public std::runtime_error {
public:
    explicit Error(const std::string& what) : std::runtime_error(what) {}
};

}  // namespace smoothedSolid
