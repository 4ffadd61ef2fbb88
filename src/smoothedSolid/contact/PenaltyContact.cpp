#include "contact/PenaltyContact.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>

namespace smoothedSolid {

namespace {

// Spatial hash of axis-aligned boxes on a uniform grid
class SpatialHash {
public:
    explicit SpatialHash(double cell) : inv_(1.0 / cell) {}

    void insert(int id, const Vec3& lo, const Vec3& hi)
    {
        const auto a = cellOf(lo), b = cellOf(hi);
        for (long i = a[0]; i <= b[0]; ++i)
            for (long j = a[1]; j <= b[1]; ++j)
                for (long k = a[2]; k <= b[2]; ++k) cells_[key(i, j, k)].push_back(id);
    }

    const std::vector<int>* query(const Vec3& p) const
    {
        const auto c = cellOf(p);
        auto it = cells_.find(key(c[0], c[1], c[2]));
        return it == cells_.end() ? nullptr : &it->second;
    }

private:
    std::array<long, 3> cellOf(const Vec3& p) const
    {
        return {long(std::floor(p.x() * inv_)), long(std::floor(p.y() * inv_)),
                long(std::floor(p.z() * inv_))};
    }
    static std::uint64_t key(long i, long j, long k)
    {
        return (std::uint64_t(i) * 73856093u) ^ (std::uint64_t(j) * 19349663u) ^
               (std::uint64_t(k) * 83492791u);
    }
    double inv_;
    std::unordered_map<std::uint64_t, std::vector<int>> cells_;
};

// Gap of p against triangle (a, b, c) and barycentric weights of the
// projection; false when the projection falls outside the triangle
bool project(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c, double& gap,
             Vec3& n, double w[3])
{
    n = (b - a).cross(c - a);
    const double twiceArea = n.norm();
    if (twiceArea <= 0) return false;
    n /= twiceArea;
    gap = (p - a).dot(n);
    const Vec3 q = p - gap * n;
    w[0] = (b - q).cross(c - q).dot(n) / twiceArea;
    w[1] = (c - q).cross(a - q).dot(n) / twiceArea;
    w[2] = 1.0 - w[0] - w[1];
    const double tol = -1e-12;
    return w[0] >= tol && w[1] >= tol && w[2] >= tol;
}

}  // namespace

PenaltyContact::PenaltyContact(const TetMesh& mesh, double waveModulus,
                               const std::vector<double>& mass, ContactOptions options)
    : options_(options), mass_(mass)
{
    const int nn = mesh.nNodes();
    const auto& X = mesh.coordinates();
    hMin_ = std::numeric_limits<double>::max();
    for (int e = 0; e < mesh.nElements(); ++e) hMin_ = std::min(hMin_, mesh.elementHeight(e));
    depth_ = options_.depthFraction * hMin_;

    area_.assign(nn, 0.0);
    std::vector<char> onBoundary(nn, 0);
    for (int f : mesh.boundaryFaces()) {
        const Tri& t = mesh.faces()[f].nodes;
        const double A = 0.5 * (X[t[1]] - X[t[0]]).cross(X[t[2]] - X[t[0]]).norm();
        for (int v : t) {
            area_[v] += A / 3.0;
            onBoundary[v] = 1;
        }
    }
    k_.assign(nn, 0.0);
    for (int v = 0; v < nn; ++v) {
        if (onBoundary[v]) {
            slaveNodes_.push_back(v);
            k_[v] = options_.penaltyScale * waveModulus * area_[v] / hMin_;
        }
    }

    nodePart_.assign(nn, -1);
    for (int e = 0; e < mesh.nElements(); ++e) {
        for (int v : mesh.elements()[e]) nodePart_[v] = mesh.elementPart()[e];
    }
    for (int f : mesh.boundaryFaces()) triPart_.push_back(mesh.elementPart()[mesh.faces()[f].owner]);

    if (options_.selfContact) {
        neighbours_.assign(nn, {});
        const auto& start = mesh.nodeElementStart();
        const auto& elems = mesh.nodeElements();
        for (int v : slaveNodes_) {
            auto& nb = neighbours_[v];
            for (int i = start[v]; i < start[v + 1]; ++i) {
                for (int w : mesh.elements()[elems[i]]) nb.push_back(w);
            }
            std::sort(nb.begin(), nb.end());
            nb.erase(std::unique(nb.begin(), nb.end()), nb.end());
        }
    }
}

void PenaltyContact::addRigidSurface(RigidSurface surface)
{
    for (const Tri& t : surface.triangles) {
        for (int v : t) {
            if (v < 0 || v >= static_cast<int>(surface.points.size())) {
                throw Error("rigid surface: triangle refers to point " + std::to_string(v) +
                            " of " + std::to_string(surface.points.size()));
            }
        }
    }
    rigid_.push_back(std::move(surface));
}

double PenaltyContact::stableTimeStepFactor(double dtElement) const
{
    double worst = 0;
    for (int v : slaveNodes_) worst = std::max(worst, k_[v] / mass_[v]);
    // omega^2 adds up: omega_total^2 = omega_e^2 + k/m with omega_e = 2/dt_e
    return 1.0 / std::sqrt(1.0 + worst * dtElement * dtElement / 4.0);
}

double PenaltyContact::addForces(const TetMesh& mesh_, const std::vector<Vec3>& x,
                                 std::vector<Vec3>& f, std::vector<double>& pressure) const
{
    pressure.assign(mesh_.nNodes(), 0.0);
    const auto& bfaces = mesh_.boundaryFaces();

    // Triangles: mesh boundary (ids >= 0) and rigid (ids < 0)
    struct RigidRef {
        int surface, tri;
    };
    std::vector<RigidRef> rigidRefs;
    for (int s = 0; s < static_cast<int>(rigid_.size()); ++s) {
        for (int t = 0; t < static_cast<int>(rigid_[s].triangles.size()); ++t) {
            rigidRefs.push_back({s, t});
        }
    }
    const bool meshTris = options_.betweenParts || options_.selfContact;
    if (!meshTris && rigidRefs.empty()) return 0.0;

    double meanSize = 0;
    int count = 0;
    auto triangle = [&](int id, Vec3& a, Vec3& b, Vec3& c) {
        if (id >= 0) {
            const Tri& t = mesh_.faces()[bfaces[id]].nodes;
            a = x[t[0]], b = x[t[1]], c = x[t[2]];
        } else {
            const RigidRef& r = rigidRefs[-1 - id];
            const RigidSurface& s = rigid_[r.surface];
            const Tri& t = s.triangles[r.tri];
            a = s.points[t[0]], b = s.points[t[1]], c = s.points[t[2]];
        }
    };
    std::vector<int> ids;
    if (meshTris) {
        for (int i = 0; i < static_cast<int>(bfaces.size()); ++i) ids.push_back(i);
    }
    for (int i = 0; i < static_cast<int>(rigidRefs.size()); ++i) ids.push_back(-1 - i);
    for (int id : ids) {
        Vec3 a, b, c;
        triangle(id, a, b, c);
        meanSize += ((b - a).norm() + (c - b).norm() + (a - c).norm()) / 3.0;
        ++count;
    }
    SpatialHash hash(std::max(meanSize / count, 2.0 * depth_));
    for (int id : ids) {
        Vec3 a, b, c;
        triangle(id, a, b, c);
        const Vec3 pad = Vec3::Constant(depth_);
        hash.insert(id, a.cwiseMin(b).cwiseMin(c) - pad, a.cwiseMax(b).cwiseMax(c) + pad);
    }

    // Outward normals of the boundary nodes (area-weighted): a node only
    // contacts triangles facing it, so that a node on an edge of another
    // body's face (e.g. where two plates meet at a side) is not pushed
    // sideways by that body's side faces
    std::vector<Vec3> nodeNormal(mesh_.nNodes(), Vec3::Zero());
    for (int f : bfaces) {
        const Tri& t = mesh_.faces()[f].nodes;
        const Vec3 nA = (x[t[1]] - x[t[0]]).cross(x[t[2]] - x[t[0]]);
        for (int v : t) nodeNormal[v] += nA;
    }
    for (int p : slaveNodes_) nodeNormal[p].normalize();

    double maxPenetration = 0;
    for (int p : slaveNodes_) {
        const std::vector<int>* cands = hash.query(x[p]);
        if (!cands) continue;
        // deepest valid contact of this node
        double best = 0;
        int bestId = 0;
        Vec3 bestN;
        double bestW[3] = {0, 0, 0};
        for (int id : *cands) {
            if (id >= 0) {
                const Tri& t = mesh_.faces()[bfaces[id]].nodes;
                if (t[0] == p || t[1] == p || t[2] == p) continue;
                const bool same = triPart_[id] == nodePart_[p];
                if (same && !options_.selfContact) continue;
                if (!same && !options_.betweenParts) continue;
                if (same) {
                    const auto& nb = neighbours_[p];
                    if (std::binary_search(nb.begin(), nb.end(), t[0]) ||
                        std::binary_search(nb.begin(), nb.end(), t[1]) ||
                        std::binary_search(nb.begin(), nb.end(), t[2]))
                        continue;
                }
            }
            Vec3 a, b, c, n;
            triangle(id, a, b, c);
            double g, w[3];
            if (!project(x[p], a, b, c, g, n, w)) continue;
            if (nodeNormal[p].dot(n) > -options_.facingCosine) continue;
            if (g < best && g > -depth_) {
                best = g;
                bestId = id;
                bestN = n;
                std::copy(w, w + 3, bestW);
            }
        }
        if (best < 0) {
            const Vec3 fc = -k_[p] * best * bestN;  // pushes p out along n
            f[p] += fc;
            if (bestId >= 0) {
                const Tri& t = mesh_.faces()[bfaces[bestId]].nodes;
                for (int i = 0; i < 3; ++i) f[t[i]] -= bestW[i] * fc;
            }
            pressure[p] += fc.norm() / area_[p];
            maxPenetration = std::max(maxPenetration, -best);
        }
    }
    return maxPenetration;
}

}  // namespace smoothedSolid
