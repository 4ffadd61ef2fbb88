// The case file of smoothedSolidRun: one keyword per line, '#' comments.
//
//   mesh          leaflet.msh                 gmsh file, relative to the case file
//   box           nx ny nz  x0 y0 z0  x1 y1 z1  (or a structured box of tets)
//   hex           nx ny nz  p0 ... p7         (or a trilinear hexahedron of tets,
//                                             corners ordered as VTK's hexahedron)
//                 box and hex define node/face sets xmin xmax ymin ymax zmin
//                 zmax (the faces of the parameter cube)
//   material      neoHookean mu 80 K 4e5 rho 1
//                 mooneyRivlin c10 1000 c01 200 kappa 5e4 rho 1000   (or nu 0.49)
//                 stVenantKirchhoff mu 0.5e6 nu 0.4 rho 1000          (or lambda)
//                 holzapfelGasserOgden c10 .. [c01 ..] k1 .. k2 .. kappa .. rho ..
//                                             fibre-reinforced tissue (or nu for
//                                             kappa; c01 default 0; constants for
//                                             aortic leaflets: docs/references.md);
//                                             needs a 'fibres' entry
//   fibres        cylindrical origin (x y z) axis (x y z)
//                                             each element's fibre direction: the
//                                             circumferential e_theta = axis x r
//                                             (normalised, right-handed about the
//                                             axis) at its centroid
//                 uniform (x y z)             or one direction for all
//                 file <path>                 or one line 'x y z' per element in
//                                             the mesh's order ('#' comments;
//                                             e.g. makeValveMeshes' .circumferential)
//                                             (parentheses optional; only with a
//                                             fibre-reinforced material)
//   formulation   selective | FS-FEM | NS-FEM | FEM-T4
//   fix           <nodeSet> [xyz | x | y | z | xy | ...]
//   planeStrain   z                           fix that component everywhere
//   bodyForce     gx gy gz [ramp T]           acceleration, ramped over T
//   pressure      <faceSet> p [ramp T]        follower pressure
//   traction      <faceSet> tx ty tz [ramp T] dead load per reference area
//   damping       c                           mass-proportional [1/s]
//   safety        0.8                         fraction of the stable step
//   contact       [self] [dampingRatio 0.1] [stepFraction 0.5] [penaltyScale 2]
//                 [depthFraction 0.5] [facingCosine 0.2]
//                                             penalty contact between parts
//                                             (and within them); see
//                                             contact/PenaltyContact.hpp
//   contactSurface wall.stl [flip]            a rigid triangulated surface the
//                                             solid cannot pass (contact is
//                                             enabled with the defaults if no
//                                             'contact' entry); .stl (ASCII or
//                                             binary) or gmsh .msh (its 3-node
//                                             triangles), relative to the case
//                                             file; triangle normals
//                                             (x1-x0)x(x2-x0) must face the solid,
//                                             'flip' reverses them; several allowed
//   endTime       T                           the run advances with sub-steps
//                                             at the solid's current stable
//                                             step, ending exactly at each
//                                             write and probe time and at T
//   writeInterval dt                          VTU output interval
//   output        results                     output directory
//   probe         A 0.6 0.2 0                 displacement at the point
//                                             (interpolated in its element);
//                                             history in <output>/probes.dat
//   probeInterval dt                          probe sampling interval
//                                             (default writeInterval/50)
//   steadyTolerance 1e-6                      stop when the probes' relative
//                                             change per writeInterval is below
#pragma once

#include "Types.hpp"

#include <map>
#include <string>
#include <vector>

namespace smoothedSolid {

struct CaseEntry {
    std::string keyword;
    std::vector<std::string> args;
    int line;
};

class CaseFile {
public:
    explicit CaseFile(const std::string& fileName);

    const std::string& fileName() const { return file_; }
    const std::string& directory() const { return dir_; }
    const std::vector<CaseEntry>& entries() const { return entries_; }

    // The single entry with this keyword; throws naming the file when
    // missing (unless optional) or repeated
    const CaseEntry* find(const std::string& keyword, bool optional = false) const;
    std::vector<const CaseEntry*> all(const std::string& keyword) const;

    // Argument i of an entry as a number / the value after 'name' in a
    // "name value" list; errors name the file, line and keyword
    double number(const CaseEntry& e, std::size_t i) const;
    double named(const CaseEntry& e, const std::string& name, bool* found = nullptr) const;
    [[noreturn]] void fail(const CaseEntry& e, const std::string& what) const;

private:
    std::string file_, dir_;
    std::vector<CaseEntry> entries_;
};

}  // namespace smoothedSolid
