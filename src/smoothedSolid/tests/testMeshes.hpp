// Meshes for the unit tests, written with the gmsh API
#pragma once

#include <string>

namespace smoothedSolid::test {

// Unstructured tet mesh of the box [0,Lx]x[0,Ly]x[0,Lz], element size h,
// written to a .msh file under the test's temporary directory; physical
// groups: volume "solid", surfaces "xmin" and "xmax". Returns the path.
std::string boxMsh(const std::string& name, double Lx, double Ly, double Lz, double h);

// A surface-only (triangle) mesh of a square: a .msh without tetrahedra
std::string surfaceOnlyMsh(const std::string& name);

// Temporary directory of this test process: <system temp>/smoothedSolidTests-
// <pid>-<random>, created on the first call, the same for every later call,
// removed with its files at exit unless SMOOTHEDSOLID_KEEP_TEST_FILES is set
std::string tempDir();

}  // namespace smoothedSolid::test
