// Patch test and rigid rotation for the four formulations on an
// unstructured gmsh mesh
#include "dynamics/ExplicitSolid.hpp"
#include "testMeshes.hpp"

#include <gtest/gtest.h>

#include <cstdio>

using namespace smoothedSolid;

namespace {

const Formulation kAll[] = {Formulation::FEM_T4, Formulation::NS_FEM, Formulation::FS_FEM,
                            Formulation::Selective};

const TetMesh& unstructuredBox()
{
    static const TetMesh mesh = TetMesh::fromGmsh(test::boxMsh("patch", 1.0, 0.7, 0.5, 0.15));
    return mesh;
}

std::vector<SmoothingDomains> domainsOf(const TetMesh& mesh)
{
    return {elementDomains(mesh), nodeDomains(mesh), faceDomains(mesh)};
}

}  // namespace

TEST(Smoothing, DomainVolumesSumToMeshVolume)
{
    const TetMesh& mesh = unstructuredBox();
    for (const auto& sd : domainsOf(mesh)) {
        double V = 0;
        for (double v : sd.volume) V += v;
        EXPECT_NEAR(V, 1.0 * 0.7 * 0.5, 1e-12);
    }
}

// An affine displacement u = A X + c gives F = I + A in every domain and,
// with the constant stress it causes, zero internal force at interior nodes
TEST(Smoothing, PatchTestAllFormulations)
{
    const TetMesh& mesh = unstructuredBox();
    Mat3 A;
    A << 0.10, -0.05, 0.02, 0.03, 0.08, -0.04, -0.02, 0.06, -0.07;
    const Vec3 c(0.3, -0.1, 0.2);
    std::vector<Vec3> u(mesh.nNodes());
    for (int i = 0; i < mesh.nNodes(); ++i) u[i] = A * mesh.coordinates()[i] + c;

    // Exact F in every domain of every kind
    for (const auto& sd : domainsOf(mesh)) {
        double err = 0;
        for (int d = 0; d < sd.size(); ++d) {
            err = std::max(err, (sd.deformationGradient(d, u) - Mat3::Identity() - A).norm());
        }
        EXPECT_LT(err, 1e-12);
    }

    std::vector<char> boundary(mesh.nNodes(), 0);
    for (int f : mesh.boundaryFaces()) {
        for (int v : mesh.faces()[f].nodes) boundary[v] = 1;
    }
    auto material = std::make_shared<MooneyRivlin>(1000.0, 200.0, 50000.0, 1000.0);
    const double Pscale = material->firstPK(Mat3::Identity() + A).norm() * 0.15 * 0.15;
    for (Formulation form : kAll) {
        ExplicitSolid solid(mesh, material, {form, 0.8, 0.0});
        const auto f = solid.internalForce(u);
        double worst = 0;
        int interior = 0;
        for (int i = 0; i < mesh.nNodes(); ++i) {
            if (!boundary[i]) {
                worst = std::max(worst, f[i].norm());
                ++interior;
            }
        }
        std::printf("%-20s patch test: max |f_int| at %d interior nodes / (|P| h^2) = %.2e "
                    "(tolerance 1e-10)\n",
                    toString(form).c_str(), interior, worst / Pscale);
        EXPECT_GT(interior, 10);
        EXPECT_LT(worst / Pscale, 1e-10);
    }
}

TEST(Smoothing, RigidRotationGivesNoInternalForce)
{
    const TetMesh& mesh = unstructuredBox();
    const Mat3 R = Eigen::AngleAxisd(1.1, Vec3(0.3, -1, 0.5).normalized()).toRotationMatrix();
    std::vector<Vec3> u(mesh.nNodes());
    for (int i = 0; i < mesh.nNodes(); ++i) {
        u[i] = (R - Mat3::Identity()) * mesh.coordinates()[i] + Vec3(1, 2, 3);
    }
    auto material = std::make_shared<NeoHookean>(80.0, 4000.0, 1.0);
    for (Formulation form : kAll) {
        ExplicitSolid solid(mesh, material, {form, 0.8, 0.0});
        double worst = 0;
        for (const Vec3& f : solid.internalForce(u)) worst = std::max(worst, f.norm());
        const double W = solid.strainEnergy(u);
        std::printf("%-20s rotation 1.1 rad: max |f_int|/(mu h^2) = %.2e, W = %.2e "
                    "(tolerance 1e-10)\n",
                    toString(form).c_str(), worst / (80.0 * 0.15 * 0.15), W);
        EXPECT_LT(worst / (80.0 * 0.15 * 0.15), 1e-10);
        EXPECT_LT(std::abs(W), 1e-10);
    }
}

// f_int = dW_h/du: the internal force is the derivative of the discrete
// strain energy, for every formulation
TEST(Smoothing, InternalForceIsEnergyGradient)
{
    const TetMesh mesh = TetMesh::box(3, 2, 2, [](const Vec3& x) { return x; });
    auto material = std::make_shared<MooneyRivlin>(1000.0, 200.0, 20000.0, 1000.0);
    std::vector<Vec3> u(mesh.nNodes());
    for (int i = 0; i < mesh.nNodes(); ++i) {
        const Vec3& X = mesh.coordinates()[i];
        u[i] = Vec3(0.1 * std::sin(3 * X.y()), 0.05 * X.x() * X.z(), -0.08 * X.y() * X.y());
    }
    for (Formulation form : kAll) {
        ExplicitSolid solid(mesh, material, {form, 0.8, 0.0});
        const auto f = solid.internalForce(u);
        double worst = 0, scale = 0;
        const double h = 1e-6;
        for (int i = 0; i < mesh.nNodes(); i += 3) {
            for (int k = 0; k < 3; ++k) {
                auto up = u, um = u;
                up[i][k] += h;
                um[i][k] -= h;
                const double fd = (solid.strainEnergy(up) - solid.strainEnergy(um)) / (2 * h);
                worst = std::max(worst, std::abs(fd - f[i][k]));
                scale = std::max(scale, std::abs(fd));
            }
        }
        std::printf("%-20s max |f_int - dW/du| / max |dW/du| = %.2e (tolerance 1e-6)\n",
                    toString(form).c_str(), worst / scale);
        EXPECT_LT(worst / scale, 1e-6);
    }
}
