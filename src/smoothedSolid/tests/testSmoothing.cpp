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

// ---------------------------------------------------------------------------
// Fibre directions: per element from the caller, per smoothing domain the
// sign-aligned volume-weighted mean (Smoothing::domainDirections)

namespace {

// Directions varying over the mesh, circumferential about the z axis
// through (-0.5, -0.5), some elements given the opposite sign
std::vector<Vec3> swirl(const TetMesh& mesh, bool flipSome)
{
    std::vector<Vec3> a(mesh.nElements());
    const auto& X = mesh.coordinates();
    for (int e = 0; e < mesh.nElements(); ++e) {
        const Tet& t = mesh.elements()[e];
        const Vec3 c = 0.25 * (X[t[0]] + X[t[1]] + X[t[2]] + X[t[3]]) + Vec3(0.5, 0.5, 0);
        a[e] = Vec3(-c.y(), c.x(), 0.3 * c.z()).normalized();
        if (flipSome && e % 3 == 1) a[e] = -a[e];
    }
    return a;
}

std::vector<Vec3> wavyDisplacement(const TetMesh& mesh)
{
    std::vector<Vec3> u(mesh.nNodes());
    for (int i = 0; i < mesh.nNodes(); ++i) {
        const Vec3& X = mesh.coordinates()[i];
        u[i] = Vec3(0.25 * X.x() + 0.1 * std::sin(3 * X.y()), 0.2 * X.y() + 0.05 * X.x() * X.z(),
                    -0.08 * X.y() * X.y());
    }
    return u;
}

}  // namespace

TEST(Smoothing, DomainDirectionsAreSignAlignedWeightedMeans)
{
    // two tets sharing a face, directions a and -a: the face domain takes +-a
    // (a plain sum would vanish); unequal volumes weight the mean
    const std::vector<Vec3> X = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1),
                                 Vec3(1, 1, 2)};
    const TetMesh mesh(X, {Tet{0, 1, 2, 3}, Tet{1, 2, 3, 4}}, true);
    Smoothing sm(mesh);
    const Vec3 a = Vec3(1, 2, 0).normalized(), b = Vec3(0, 1, 0);
    std::vector<Vec3> out;
    sm.domainDirections(DomainKind::Face, {a, Vec3(-a)}, out);
    int shared = -1;
    for (int f = 0; f < sm.size(DomainKind::Face); ++f) {
        if (mesh.faces()[f].neighbour >= 0) shared = f;
    }
    ASSERT_GE(shared, 0);
    const double align = std::abs(out[shared].dot(a));
    // a and b: the volume-weighted mean of the two, normalised
    sm.domainDirections(DomainKind::Face, {a, b}, out);
    const double v0 = mesh.elementVolume(0), v1 = mesh.elementVolume(1);
    const Vec3 ref = (v0 * a + v1 * b).normalized();
    const double err = (out[shared] - ref).norm();
    // and b given as -b: the same axis
    sm.domainDirections(DomainKind::Face, {a, Vec3(-b)}, out);
    const double errFlip = std::min((out[shared] - ref).norm(), (out[shared] + ref).norm());
    std::printf("face domain between a and -a: |a_d . a| = %.15f (must be 1); between a and b: "
                "|a_d - (V0 a + V1 b)/|..|| = %.1e, with -b %.1e (tolerance 1e-14)\n",
                align, err, errFlip);
    EXPECT_NEAR(align, 1.0, 1e-14);
    EXPECT_LT(err, 1e-14);
    EXPECT_LT(errFlip, 1e-14);
}

// The fibre material in the solver: f_int = dW_h/du for every formulation,
// and the forces do not depend on the signs the caller gives the directions
TEST(Smoothing, FibreInternalForceIsEnergyGradientAndSignFree)
{
    const TetMesh mesh = TetMesh::box(3, 2, 2, [](const Vec3& x) { return x; });
    auto material = std::make_shared<HolzapfelGasserOgden>(1000.0, 200.0, 5000.0, 3.0, 20000.0, 1000.0);
    const std::vector<Vec3> u = wavyDisplacement(mesh);
    for (Formulation form : kAll) {
        ExplicitSolid solid(mesh, material, {form, 0.8, 0.0});
        EXPECT_THROW(solid.internalForce(u), Error);  // no directions yet
        solid.setFibreDirections(swirl(mesh, false));
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
        ExplicitSolid flipped(mesh, material, {form, 0.8, 0.0});
        flipped.setFibreDirections(swirl(mesh, true));
        const auto g = flipped.internalForce(u);
        double diff = 0, fmax = 0;
        for (int i = 0; i < mesh.nNodes(); ++i) {
            diff = std::max(diff, (f[i] - g[i]).norm());
            fmax = std::max(fmax, f[i].norm());
        }
        std::printf("%-20s fibres: max |f_int - dW/du| / max |dW/du| = %.2e (tolerance 1e-6); "
                    "a third of the directions reversed: max |df| / max |f| = %.1e (tolerance "
                    "1e-12)\n",
                    toString(form).c_str(), worst / scale, diff / fmax);
        EXPECT_LT(worst / scale, 1e-6);
        EXPECT_LT(diff / fmax, 1e-12);
    }
}

TEST(Smoothing, FibreDirectionsBadInputThrows)
{
    const TetMesh mesh = TetMesh::box(2, 2, 1, [](const Vec3& x) { return x; });
    auto fibre = std::make_shared<HolzapfelGasserOgden>(1000.0, 0.0, 5000.0, 3.0, 20000.0, 1000.0);
    ExplicitSolid solid(mesh, fibre);
    auto message = [&](std::vector<Vec3> a) {
        try {
            solid.setFibreDirections(std::move(a));
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    const std::string wrongSize = message(std::vector<Vec3>(3, Vec3::UnitX()));
    std::vector<Vec3> a(mesh.nElements(), Vec3::UnitX());
    a[5] = Vec3::Zero();
    const std::string zero = message(a);
    std::printf("wrong count: %s\nzero direction: %s\n", wrongSize.c_str(), zero.c_str());
    EXPECT_NE(wrongSize.find("one per element"), std::string::npos);
    EXPECT_NE(zero.find("element 5"), std::string::npos);
    ExplicitSolid iso(mesh, std::make_shared<MooneyRivlin>(1000.0, 0.0, 2e4, 1000.0));
    EXPECT_THROW(iso.setFibreDirections(std::vector<Vec3>(mesh.nElements(), Vec3::UnitX())), Error);
}
