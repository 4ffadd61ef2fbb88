#include "testMeshes.hpp"

#include "mesh/TetMesh.hpp"

#include <gmsh.h>

#include <cstdlib>
#include <filesystem>

namespace smoothedSolid::test {

using smoothedSolid::initializeGmsh;

std::string tempDir()
{
    const auto dir = std::filesystem::temp_directory_path() / "smoothedSolidTests";
    std::filesystem::create_directories(dir);
    return dir.string();
}

namespace {
void start()
{
    initializeGmsh();
    gmsh::clear();
}
}  // namespace

std::string boxMsh(const std::string& name, double Lx, double Ly, double Lz, double h)
{
    start();
    gmsh::model::add(name);
    const int vol = gmsh::model::occ::addBox(0, 0, 0, Lx, Ly, Lz);
    gmsh::model::occ::synchronize();
    std::vector<int> xmin, xmax;
    gmsh::vectorpair surfaces;
    gmsh::model::getEntities(surfaces, 2);
    for (const auto& [dim, tag] : surfaces) {
        double x0, y0, z0, x1, y1, z1;
        gmsh::model::getBoundingBox(dim, tag, x0, y0, z0, x1, y1, z1);
        if (x1 < 1e-6 * Lx) xmin.push_back(tag);
        if (x0 > Lx * (1 - 1e-6)) xmax.push_back(tag);
    }
    gmsh::model::setPhysicalName(3, gmsh::model::addPhysicalGroup(3, {vol}), "solid");
    gmsh::model::setPhysicalName(2, gmsh::model::addPhysicalGroup(2, xmin), "xmin");
    gmsh::model::setPhysicalName(2, gmsh::model::addPhysicalGroup(2, xmax), "xmax");
    gmsh::option::setNumber("Mesh.CharacteristicLengthMin", h);
    gmsh::option::setNumber("Mesh.CharacteristicLengthMax", h);
    gmsh::model::mesh::generate(3);
    const std::string path = tempDir() + "/" + name + ".msh";
    gmsh::write(path);
    gmsh::clear();
    return path;
}

std::string surfaceOnlyMsh(const std::string& name)
{
    start();
    gmsh::model::add(name);
    const int s = gmsh::model::occ::addRectangle(0, 0, 0, 1, 1);
    gmsh::model::occ::synchronize();
    gmsh::model::addPhysicalGroup(2, {s});
    gmsh::option::setNumber("Mesh.CharacteristicLengthMax", 0.25);
    gmsh::model::mesh::generate(2);
    const std::string path = tempDir() + "/" + name + ".msh";
    gmsh::write(path);
    gmsh::clear();
    return path;
}

}  // namespace smoothedSolid::test
