// Fibre directions from a file: one line 'x y z' per tetrahedron, in the
// order of the mesh file's tetrahedra; '#' starts a comment, blank lines are
// skipped (e.g. the .circumferential file makeValveMeshes writes beside the
// valve leaflets). Each direction is normalised. Errors (Error) name the
// file and the line: missing or unreadable, a line that is not three numbers
// of a non-zero direction, or a count other than nElements.
#pragma once

#include "Types.hpp"

#include <string>
#include <vector>

namespace smoothedSolid {

std::vector<Vec3> readFibreDirections(const std::string& fileName, int nElements);

}  // namespace smoothedSolid
