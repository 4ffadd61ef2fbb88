#include "contact/PenaltyContact.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <cstdint>
#include <string>
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

// Closest point of triangle (a, b, c) to p as barycentric weights w
// (Ericson, Real-Time Collision Detection, 2005, Sect. 5.1.5): inside the
// face, on an edge or at a vertex
void closestPoint(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c, double w[3])
{
    const Vec3 ab = b - a, ac = c - a, ap = p - a;
    const double d1 = ab.dot(ap), d2 = ac.dot(ap);
    if (d1 <= 0 && d2 <= 0) { w[0] = 1, w[1] = 0, w[2] = 0; return; }
    const Vec3 bp = p - b;
    const double d3 = ab.dot(bp), d4 = ac.dot(bp);
    if (d3 >= 0 && d4 <= d3) { w[0] = 0, w[1] = 1, w[2] = 0; return; }
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) {
        const double v = d1 / (d1 - d3);
        w[0] = 1 - v, w[1] = v, w[2] = 0;
        return;
    }
    const Vec3 cp = p - c;
    const double d5 = ab.dot(cp), d6 = ac.dot(cp);
    if (d6 >= 0 && d5 <= d6) { w[0] = 0, w[1] = 0, w[2] = 1; return; }
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) {
        const double v = d2 / (d2 - d6);
        w[0] = 1 - v, w[1] = 0, w[2] = v;
        return;
    }
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
        const double v = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        w[0] = 0, w[1] = 1 - v, w[2] = v;
        return;
    }
    const double denom = 1.0 / (va + vb + vc);
    w[1] = vb * denom, w[2] = vc * denom, w[0] = 1 - w[1] - w[2];
}

// Distance of p to triangle (a, b, c): closest point q (weights w), gap
// g = n.(p - q) along the unit face normal n (negative: behind the face) and
// the lateral offset l = |(p - q) - g n|, non-zero when p lies outside the
// triangle's normal prism (beyond an edge). False for a degenerate triangle.
struct Proximity {
    double distance, gap, lateral;
    Vec3 normal;
    double w[3];
};

bool proximity(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c, Proximity& r)
{
    r.normal = (b - a).cross(c - a);
    const double twiceArea = r.normal.norm();
    if (twiceArea <= 0) return false;
    r.normal /= twiceArea;
    closestPoint(p, a, b, c, r.w);
    const Vec3 d = p - (r.w[0] * a + r.w[1] * b + r.w[2] * c);
    r.distance = d.norm();
    r.gap = d.dot(r.normal);
    r.lateral = (d - r.gap * r.normal).norm();
    return true;
}

}  // namespace

PenaltyContact::PenaltyContact(const TetMesh& mesh, double hMin, double waveModulus,
                               double density, const std::vector<double>& mass,
                               ContactOptions options)
    : options_(options), mass_(mass)
{
    auto range = [](const char* name, double v, bool ok, const char* allowed) {
        if (!ok || !std::isfinite(v)) {
            throw Error(std::string("contact option ") + name + " = " + std::to_string(v) +
                        " is out of range: it must lie in " + allowed);
        }
    };
    range("stepFraction", options_.stepFraction,
          options_.stepFraction > 0 && options_.stepFraction < 1, "(0, 1)");
    range("penaltyScale", options_.penaltyScale, options_.penaltyScale > 0, "(0, inf)");
    range("depthFraction", options_.depthFraction,
          options_.depthFraction > 0 && options_.depthFraction <= 2, "(0, 2]");
    range("facingCosine", options_.facingCosine,
          options_.facingCosine >= 0 && options_.facingCosine < 1, "[0, 1)");
    range("volumeLimit", options_.volumeLimit,
          options_.volumeLimit >= 0 && options_.volumeLimit < 1, "[0, 1)");
    if (options_.volumeLimit > 0 && !options_.kinematic) {
        throw Error("contact option volumeLimit = " + std::to_string(options_.volumeLimit) +
                    " limits the velocities of a carried solid: it needs the kinematic option");
    }
    range("dampingRatio", options_.dampingRatio,
          options_.dampingRatio >= 0 && options_.dampingRatio <= 1, "[0, 1]");
    (void)density;
    const int nn = mesh.nNodes();
    const auto& X = mesh.coordinates();
    depth_ = options_.depthFraction * hMin;
    skin_ = depth_;

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
    load_.assign(nn, 0.0);
    for (int v = 0; v < nn; ++v) {
        if (onBoundary[v]) {
            slaveNodes_.push_back(v);
            k_[v] = options_.penaltyScale * waveModulus * area_[v] / hMin;
        }
    }

    nodePart_.assign(nn, -1);
    for (int e = 0; e < mesh.nElements(); ++e) {
        for (int v : mesh.elements()[e]) nodePart_[v] = mesh.elementPart()[e];
    }
    for (int f : mesh.boundaryFaces()) triPart_.push_back(mesh.elementPart()[mesh.faces()[f].owner]);

    // boundary faces around each node, for the node normals
    const auto& bf = mesh.boundaryFaces();
    nodeFaceStart_.assign(nn + 1, 0);
    for (int f : bf) {
        for (int v : mesh.faces()[f].nodes) ++nodeFaceStart_[v + 1];
    }
    for (int v = 0; v < nn; ++v) nodeFaceStart_[v + 1] += nodeFaceStart_[v];
    nodeFaces_.resize(nodeFaceStart_[nn]);
    {
        std::vector<int> fill(nodeFaceStart_.begin(), nodeFaceStart_.end() - 1);
        for (int i = 0; i < static_cast<int>(bf.size()); ++i) {
            for (int v : mesh.faces()[bf[i]].nodes) nodeFaces_[fill[v]++] = i;
        }
    }

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
    const int sId = static_cast<int>(rigid_.size());
    for (int t = 0; t < static_cast<int>(surface.triangles.size()); ++t) rigidTri_.push_back({sId, t});
    rigid_.push_back(std::move(surface));
    built_ = false;
}

void PenaltyContact::setStillNodes(std::vector<char> still)
{
    if (!still.empty() && still.size() != nodePart_.size()) {
        throw Error("PenaltyContact::setStillNodes: " + std::to_string(still.size()) +
                    " entries for " + std::to_string(nodePart_.size()) + " nodes");
    }
    still_ = std::move(still);
    built_ = false;
}

void PenaltyContact::triangle(const TetMesh& mesh, const std::vector<Vec3>& x, int id, Vec3& a,
                              Vec3& b, Vec3& c) const
{
    if (id >= 0) {
        const Tri& t = mesh.faces()[mesh.boundaryFaces()[id]].nodes;
        a = x[t[0]], b = x[t[1]], c = x[t[2]];
    } else {
        const auto& r = rigidTri_[-1 - id];
        const RigidSurface& s = rigid_[r[0]];
        const Tri& t = s.triangles[r[1]];
        a = s.points[t[0]], b = s.points[t[1]], c = s.points[t[2]];
    }
}

// Candidate lists: rebuilt once a boundary node has moved by more than
// skin/2 since the last build
void PenaltyContact::search(const TetMesh& mesh, const std::vector<Vec3>& x) const
{
    bool rebuild = !built_;
    const int ns = static_cast<int>(slaveNodes_.size());
    const double limit2 = 0.25 * skin_ * skin_;
    for (int s = 0; s < ns && !rebuild; ++s) {
        rebuild = (x[slaveNodes_[s]] - xBuild_[s]).squaredNorm() > limit2;
    }
    if (rebuild) buildCandidates(mesh, x);
}

void PenaltyContact::buildCandidates(const TetMesh& mesh, const std::vector<Vec3>& x) const
{
    ++builds_;
    built_ = true;
    const auto& bfaces = mesh.boundaryFaces();
    const bool meshTris = options_.betweenParts || options_.selfContact;
    std::vector<int> ids;
    if (meshTris) {
        for (int i = 0; i < static_cast<int>(bfaces.size()); ++i) ids.push_back(i);
    }
    for (int i = 0; i < static_cast<int>(rigidTri_.size()); ++i) ids.push_back(-1 - i);

    const int ns = static_cast<int>(slaveNodes_.size());
    candStart_.assign(ns + 1, 0);
    cand_.clear();
    xBuild_.resize(ns);
    for (int s = 0; s < ns; ++s) xBuild_[s] = x[slaveNodes_[s]];
    if (ids.empty()) return;

    const double reach = depth_ + skin_;
    double meanSize = 0;
    for (int id : ids) {
        Vec3 a, b, c;
        triangle(mesh, x, id, a, b, c);
        meanSize += ((b - a).norm() + (c - b).norm() + (a - c).norm()) / 3.0;
    }
    SpatialHash hash(std::max(meanSize / ids.size(), 2.0 * reach));
    for (int id : ids) {
        Vec3 a, b, c;
        triangle(mesh, x, id, a, b, c);
        const Vec3 pad = Vec3::Constant(reach);
        hash.insert(id, a.cwiseMin(b).cwiseMin(c) - pad, a.cwiseMax(b).cwiseMax(c) + pad);
    }
    for (int s = 0; s < ns; ++s) {
        const int p = slaveNodes_[s];
        if (const std::vector<int>* cands = hash.query(x[p])) {
            const bool still = !still_.empty() && still_[p];
            for (int id : *cands) {
                if (id < 0 && still) continue;  // neither side can move
                if (id >= 0) {
                    const Tri& t = mesh.faces()[bfaces[id]].nodes;
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
                Vec3 a, b, c;
                triangle(mesh, x, id, a, b, c);
                Proximity r;
                if (proximity(x[p], a, b, c, r) && r.distance <= reach) cand_.push_back(id);
            }
        }
        candStart_[s + 1] = static_cast<int>(cand_.size());
    }
}

bool PenaltyContact::nearest(const TetMesh& mesh, const std::vector<Vec3>& x, int s,
                             Nearest& best, bool facingRigid) const
{
    if (candStart_[s] == candStart_[s + 1]) return false;
    const int p = slaveNodes_[s];
    // Outward normal of the node (area-weighted): a node only contacts
    // triangles facing it, so that a node on an edge of another body's
    // face (e.g. where two plates meet at a side) is not pushed sideways
    // by that body's side faces
    Vec3 nodeNormal = Vec3::Zero();
    for (int i = nodeFaceStart_[p]; i < nodeFaceStart_[p + 1]; ++i) {
        const Tri& t = mesh.faces()[mesh.boundaryFaces()[nodeFaces_[i]]].nodes;
        nodeNormal += (x[t[1]] - x[t[0]]).cross(x[t[2]] - x[t[0]]);
    }
    nodeNormal.normalize();
    // Closest facing triangle (distance to its closest point), the gap
    // measured along its normal
    Proximity bestP{depth_, 0, 0, Vec3::Zero(), {0, 0, 0}};
    int bestId = 0;
    for (int i = candStart_[s]; i < candStart_[s + 1]; ++i) {
        const int id = cand_[i];
        Vec3 a, b, c;
        triangle(mesh, x, id, a, b, c);
        Proximity r;
        if (!proximity(x[p], a, b, c, r)) continue;
        if ((id >= 0 || facingRigid) && nodeNormal.dot(r.normal) > -options_.facingCosine) {
            continue;
        }
        if (r.distance < bestP.distance) {
            bestP = r;
            bestId = id;
        }
    }
    best = {bestId, bestP.gap, bestP.lateral, bestP.normal, {bestP.w[0], bestP.w[1], bestP.w[2]}};
    return bestP.distance < depth_;
}

KinematicContact PenaltyContact::constrainVelocities(const TetMesh& mesh,
                                                     const std::vector<Vec3>& x,
                                                     std::vector<Vec3>& v,
                                                     const std::vector<double>& invMass,
                                                     double dt, int sweeps) const
{
    const int nn = mesh.nNodes();
    if (static_cast<int>(v.size()) != nn || static_cast<int>(invMass.size()) != nn) {
        throw Error("PenaltyContact::constrainVelocities: " + std::to_string(v.size()) +
                    " velocities and " + std::to_string(invMass.size()) + " inverse masses for " +
                    std::to_string(nn) + " nodes");
    }
    if (!(dt > 0) || !std::isfinite(dt)) {
        throw Error("PenaltyContact::constrainVelocities: the step must be positive and finite, "
                    "not " + std::to_string(dt));
    }
    KinematicContact report;
    const bool pairs = options_.betweenParts || options_.selfContact || !rigidTri_.empty();
    const double jMin = options_.volumeLimit;
    if (!pairs && !(jMin > 0)) return report;

    // One unilateral constraint: sum_j dir_j . v_{node_j} >= target, met by
    // impulses lambda dir_j (velocity changes lambda invMass_j dir_j)
    struct Constraint {
        int n;          // nodes
        int node[4];
        Vec3 dir[4];
        double target;  // smallest admissible rate
        double k;       // 1 / (sum_j |dir_j|^2 invMass_j): rate per unit impulse, inverted
        double lambda;  // accumulated impulse
        bool volume;
    };
    // The elements' constraints first in each sweep, the pairs last: the
    // sweeps stop with the pairs' corrections the latest
    std::vector<Constraint> pairCs, volumeCs;
    auto add = [&](std::vector<Constraint>& cs, Constraint c) {
        double sum = 0;
        for (int j = 0; j < c.n; ++j) sum += c.dir[j].squaredNorm() * invMass[c.node[j]];
        if (!(sum > 0)) return false;  // no node may move
        c.k = 1.0 / sum;
        cs.push_back(c);
        return true;
    };
    double vScale = 0;
    for (const Vec3& vi : v) vScale = std::max(vScale, vi.norm());

    // Contact pairs: v_n = n.(v_p - sum_j w_j v_j) >= -g/dt (g >= 0), -g/(2 dt) (g < 0)
    std::vector<char> inPair(jMin > 0 ? nn : 0, 0);
    if (pairs) {
        search(mesh, x);
        const int ns = static_cast<int>(slaveNodes_.size());
        report.minGap = depth_;
        for (int s = 0; s < ns; ++s) {
            Nearest r;
            if (!nearest(mesh, x, s, r, false) || r.lateral >= depth_) continue;
            ++report.pairs;
            report.minGap = std::min(report.minGap, r.gap);
            Constraint c{1, {slaveNodes_[s], 0, 0, 0}, {r.normal, Vec3::Zero(), Vec3::Zero(),
                         Vec3::Zero()}, r.gap >= 0 ? -r.gap / dt : -0.5 * r.gap / dt, 0, 0, false};
            if (r.id >= 0) {
                const Tri& t = mesh.faces()[mesh.boundaryFaces()[r.id]].nodes;
                for (int j = 0; j < 3; ++j) c.node[j + 1] = t[j], c.dir[j + 1] = -r.w[j] * r.normal;
                c.n = 4;
            }
            if (!inPair.empty()) {
                for (int j = 0; j < c.n; ++j) inPair[c.node[j]] = 1;
            }
            add(pairCs, c);
        }
        if (report.pairs == 0) report.minGap = 0;
    }

    // Volume limits: dV/dt = sum_a g_a.v_a >= (Jmin V0 - V)/dt, half that
    // below Jmin V0; scaled by V0^(2/3) to a velocity. An element is watched
    // once J, or J at the end of the step at the velocities as they stand,
    // is below (1 + Jmin)/2, or a node of it is in a pair; after the sweeps
    // the elements not watched are checked again at the corrected
    // velocities (the elements' impulses squeeze their neighbours)
    std::vector<char> watched(jMin > 0 ? mesh.nElements() : 0, 0);
    auto watchElements = [&](bool first) {
        const double watch = 0.5 * (1.0 + jMin);
        bool added = false;
        for (int e = 0; e < mesh.nElements(); ++e) {
            if (watched[e]) continue;
            const Tet& t = mesh.elements()[e];
            const Vec3 d1 = x[t[1]] - x[t[0]], d2 = x[t[2]] - x[t[0]], d3 = x[t[3]] - x[t[0]];
            Vec3 g[4];
            g[1] = d2.cross(d3) / 6.0;
            g[2] = d3.cross(d1) / 6.0;
            g[3] = d1.cross(d2) / 6.0;
            g[0] = -(g[1] + g[2] + g[3]);
            const double vol = d1.dot(g[1]);
            double rate = 0;
            for (int j = 0; j < 4; ++j) rate += g[j].dot(v[t[j]]);
            const double v0 = mesh.elementVolume(e);
            const double J = vol / v0;
            bool touched = false;
            for (int j = 0; first && j < 4 && !inPair.empty(); ++j) touched = touched || inPair[t[j]];
            if (!(J < watch || (vol + dt * rate) / v0 < watch || touched)) continue;
            watched[e] = 1;
            const double scale = 1.0 / std::cbrt(v0 * v0);
            const double lower = jMin * v0;
            Constraint con{4, {t[0], t[1], t[2], t[3]},
                           {scale * g[0], scale * g[1], scale * g[2], scale * g[3]},
                           scale * (vol >= lower ? (lower - vol) / dt : 0.5 * (lower - vol) / dt),
                           0, 0, true};
            if (add(volumeCs, con)) {
                ++report.elements;
                report.minVolumeRatio = std::min(report.minVolumeRatio, J);
                added = true;
            }
        }
        return added;
    };
    if (jMin > 0) watchElements(true);

    const double tolerance = 1e-9 + 1e-3 * vScale;
    std::vector<Vec3> v0;
    auto sweep = [&](std::vector<Constraint>& cs) {
        double worst = 0;
        for (Constraint& c : cs) {
            double rate = 0;
            for (int j = 0; j < c.n; ++j) rate += c.dir[j].dot(v[c.node[j]]);
            // projected: the accumulated impulse stays >= 0
            const double lambda = std::max(0.0, c.lambda + (c.target - rate) * c.k);
            const double d = lambda - c.lambda;
            if (d == 0) continue;
            worst = std::max(worst, std::abs(d) / c.k);
            if (v0.empty()) v0 = v;
            c.lambda = lambda;
            for (int j = 0; j < c.n; ++j) v[c.node[j]] += (d * invMass[c.node[j]]) * c.dir[j];
        }
        return worst;
    };
    for (int round = 0; round < 4; ++round) {
        while (!(pairCs.empty() && volumeCs.empty()) && report.sweeps < sweeps) {
            ++report.sweeps;
            const double worstVolume = sweep(volumeCs);
            const double worstPair = sweep(pairCs);
            if (std::max(worstVolume, worstPair) <= tolerance) break;
        }
        if (!(jMin > 0) || v0.empty() || !watchElements(false)) break;
    }
    for (const Constraint& c : pairCs) report.held += c.lambda > 0;
    for (const Constraint& c : volumeCs) report.volumeHeld += c.lambda > 0;
    for (std::size_t i = 0; !v0.empty() && i < v.size(); ++i) {
        report.maxChange = std::max(report.maxChange, (v[i] - v0[i]).norm());
    }
    return report;
}

double PenaltyContact::addForces(const TetMesh& mesh_, const std::vector<Vec3>& x,
                                 const std::vector<Vec3>& velocity, double dt,
                                 const std::vector<double>& omega2, std::vector<Vec3>& f,
                                 std::vector<double>& pressure) const
{
    pressure.assign(mesh_.nNodes(), 0.0);
    if (!(options_.betweenParts || options_.selfContact) && rigidTri_.empty()) return 0.0;

    search(mesh_, x);
    const int ns = static_cast<int>(slaveNodes_.size());

    pairs_.clear();
    for (int s = 0; s < ns; ++s) {
        Nearest r;
        if (!nearest(mesh_, x, s, r, true)) continue;
        // the force fades out linearly with the lateral offset over the
        // search depth: continuous where the node slides over an edge of
        // the other surface, whether that edge is a crease (a pressed plate
        // makes a bowl, whose creases a penetrating node can lie beyond) or
        // the body's edge, and a node exactly above an edge or vertex
        // (matching meshes) is held
        const double fade = 1.0 - r.lateral / depth_;
        if (r.gap < 0 && fade > 0) {
            pairs_.push_back({slaveNodes_[s], r.id, k_[slaveNodes_[s]] * fade, r.gap, r.normal,
                              {r.w[0], r.w[1], r.w[2]}});
        }
    }

    // Limit the stiffness where a node's Gershgorin bound would exceed the
    // budget the step leaves beside the elements' (see the header):
    // load_i = (1/m_i) sum_pairs k |b_i| sum_j |b_j|
    const double total = std::pow(2.0 * safety_ / dt, 2);
    auto budget = [&](int i) { return std::max(0.0, total - omega2[i]); };
    auto nodesOf = [&](const Pair& c, int v[4], double b[4]) {
        v[0] = c.node, b[0] = 1;
        if (c.id < 0) return 1;
        const Tri& t = mesh_.faces()[mesh_.boundaryFaces()[c.id]].nodes;
        for (int i = 0; i < 3; ++i) v[i + 1] = t[i], b[i + 1] = c.w[i];
        return 4;
    };
    for (const Pair& c : pairs_) {
        int v[4];
        double b[4];
        const int n = nodesOf(c, v, b);
        const double sum = n == 1 ? 1.0 : 2.0;  // 1 + sum of barycentric weights
        for (int i = 0; i < n; ++i) load_[v[i]] += c.k * b[i] * sum / mass_[v[i]];
    }
    double maxPenetration = 0;
    for (Pair& c : pairs_) {
        int v[4];
        double b[4];
        const int n = nodesOf(c, v, b);
        double scale = 1.0;
        for (int i = 0; i < n; ++i) {
            if (b[i] > 0 && load_[v[i]] > budget(v[i])) {
                scale = std::min(scale, budget(v[i]) / load_[v[i]]);
            }
        }
        // Spring and normal dashpot on the relative normal velocity
        // (critical damping ratio zeta of the pair's spring with the
        // reduced mass), never pulling: f_n = max(0, -k g - c_d v_n)
        const double k = scale * c.k;
        double vn = 0, mT = 0;
        for (int i = 0; i < n; ++i) vn += (i == 0 ? 1.0 : -b[i]) * velocity[v[i]].dot(c.direction);
        for (int i = 1; i < n; ++i) mT += b[i] * mass_[v[i]];
        const double mp = mass_[c.node];
        const double mEff = n == 1 ? mp : mp * mT / (mp + mT);
        const double fn = std::max(0.0, -k * c.gap - 2.0 * options_.dampingRatio * std::sqrt(k * mEff) * vn);
        const Vec3 fc = fn * c.direction;  // pushes p out
        for (int i = 0; i < n; ++i) f[v[i]] += (i == 0 ? 1.0 : -b[i]) * fc;
        pressure[c.node] += fc.norm() / area_[c.node];
        maxPenetration = std::max(maxPenetration, -c.gap);
    }
    for (const Pair& c : pairs_) {
        load_[c.node] = 0;
        if (c.id >= 0) {
            for (int v : mesh_.faces()[mesh_.boundaryFaces()[c.id]].nodes) load_[v] = 0;
        }
    }
    return maxPenetration;
}

// ---------------------------------------------------------------------------

namespace {

template <class T>
void putVec(std::ostream& os, const std::vector<T>& v)
{
    const std::int64_t n = static_cast<std::int64_t>(v.size());
    os.write(reinterpret_cast<const char*>(&n), sizeof n);
    os.write(reinterpret_cast<const char*>(v.data()), static_cast<std::streamsize>(sizeof(T) * v.size()));
}

template <class T>
bool getVec(std::istream& is, std::vector<T>& v)
{
    std::int64_t n = -1;
    is.read(reinterpret_cast<char*>(&n), sizeof n);
    if (!is || n < 0 || n > (std::int64_t(1) << 34)) return false;
    v.resize(static_cast<std::size_t>(n));
    is.read(reinterpret_cast<char*>(v.data()), static_cast<std::streamsize>(sizeof(T) * v.size()));
    return bool(is);
}

}  // namespace

void PenaltyContact::writeState(std::ostream& os) const
{
    const std::int32_t built = built_ ? 1 : 0;
    const std::int64_t builds = builds_;
    const std::int64_t slaves = static_cast<std::int64_t>(slaveNodes_.size());
    os.write(reinterpret_cast<const char*>(&slaves), sizeof slaves);
    os.write(reinterpret_cast<const char*>(&built), sizeof built);
    os.write(reinterpret_cast<const char*>(&builds), sizeof builds);
    putVec(os, candStart_);
    putVec(os, cand_);
    putVec(os, xBuild_);
}

std::unique_ptr<PenaltyContact::State> PenaltyContact::readState(std::istream& is,
                                                                 const std::string& file) const
{
    auto bad = [&](const std::string& what) {
        throw Error("state file '" + file + "': contact state " + what);
    };
    std::int64_t slaves = -1, builds = 0;
    std::int32_t built = 0;
    is.read(reinterpret_cast<char*>(&slaves), sizeof slaves);
    is.read(reinterpret_cast<char*>(&built), sizeof built);
    is.read(reinterpret_cast<char*>(&builds), sizeof builds);
    if (!is) bad("is truncated");
    if (slaves != static_cast<std::int64_t>(slaveNodes_.size())) {
        bad("has " + std::to_string(slaves) + " boundary nodes, this solid has " +
            std::to_string(slaveNodes_.size()));
    }
    auto s = std::make_unique<State>();
    s->built = built != 0;
    s->builds = builds;
    if (!getVec(is, s->candStart) || !getVec(is, s->cand) || !getVec(is, s->xBuild)) bad("is truncated");
    if (s->built) {
        const std::size_t ns = slaveNodes_.size();
        if (s->candStart.size() != ns + 1 || s->xBuild.size() != ns ||
            static_cast<std::size_t>(s->candStart.back()) != s->cand.size()) {
            bad("is inconsistent with this solid's boundary");
        }
        const int nTri = static_cast<int>(rigidTri_.size());
        for (int id : s->cand) {
            if (id < -nTri) bad("refers to rigid triangle " + std::to_string(-1 - id) + " of " +
                                std::to_string(nTri) + ": add the same rigid surfaces before loading");
        }
    }
    return s;
}

void PenaltyContact::setState(State state)
{
    built_ = state.built;
    builds_ = state.builds;
    candStart_ = std::move(state.candStart);
    cand_ = std::move(state.cand);
    xBuild_ = std::move(state.xBuild);
}

}  // namespace smoothedSolid
