// Rigid triangulated surfaces (contact walls) from files:
//   .stl   ASCII or binary STL (binary when the size is 84 + 50 n bytes with
//          n the triangle count in its header; ASCII otherwise). Vertices
//          shared by facets (equal coordinates) are merged. The facet normal
//          records are ignored: the vertex order (x1-x0)x(x2-x0) orients the
//          triangle, as the STL format specifies (counter-clockwise seen
//          from outside).
//   .msh   gmsh mesh: every linear triangle (gmsh element type 2) of the
//          file, oriented as gmsh orders its nodes.
// The contact (contact/PenaltyContact.hpp) needs the normals to point toward
// the solid's side; 'flip' reverses every triangle. Errors name the file:
// missing or unreadable, unknown extension, no triangles, degenerate ones.
#pragma once

#include "contact/PenaltyContact.hpp"

#include <string>

namespace smoothedSolid {

RigidSurface readRigidSurface(const std::string& fileName, bool flip = false);

}  // namespace smoothedSolid
