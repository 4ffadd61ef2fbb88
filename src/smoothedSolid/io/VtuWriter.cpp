#include "io/VtuWriter.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>

namespace smoothedSolid {

namespace {

std::string base64(const std::vector<unsigned char>& in)
{
    static const char* t = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    out.reserve(4 * ((in.size() + 2) / 3));
    std::size_t i = 0;
    for (; i + 2 < in.size(); i += 3) {
        const unsigned v = (in[i] << 16) | (in[i + 1] << 8) | in[i + 2];
        out += t[(v >> 18) & 63];
        out += t[(v >> 12) & 63];
        out += t[(v >> 6) & 63];
        out += t[v & 63];
    }
    if (i + 1 == in.size()) {
        const unsigned v = in[i] << 16;
        out += t[(v >> 18) & 63];
        out += t[(v >> 12) & 63];
        out += "==";
    } else if (i + 2 == in.size()) {
        const unsigned v = (in[i] << 16) | (in[i + 1] << 8);
        out += t[(v >> 18) & 63];
        out += t[(v >> 12) & 63];
        out += t[(v >> 6) & 63];
        out += '=';
    }
    return out;
}

// VTK XML "binary" data: base64 of (UInt64 byte count + raw little-endian data)
template <class T>
void dataArray(std::ostream& os, const char* type, const std::string& name, int components,
               const std::vector<T>& data)
{
    const std::uint64_t bytes = data.size() * sizeof(T);
    std::vector<unsigned char> buf(sizeof bytes + bytes);
    std::memcpy(buf.data(), &bytes, sizeof bytes);
    std::memcpy(buf.data() + sizeof bytes, data.data(), bytes);
    os << "        <DataArray type=\"" << type << "\" Name=\"" << name
       << "\" NumberOfComponents=\"" << components << "\" format=\"binary\">\n          "
       << base64(buf) << "\n        </DataArray>\n";
}

std::vector<double> flatten(const std::vector<Vec3>& v)
{
    std::vector<double> out(3 * v.size());
    for (std::size_t i = 0; i < v.size(); ++i) {
        out[3 * i] = v[i].x();
        out[3 * i + 1] = v[i].y();
        out[3 * i + 2] = v[i].z();
    }
    return out;
}

}  // namespace

VtuSeries::VtuSeries(std::string directory, std::string name)
    : directory_(std::move(directory)), name_(std::move(name))
{
    std::error_code ec;
    std::filesystem::create_directories(directory_, ec);
    if (ec) throw Error("cannot create output directory '" + directory_ + "': " + ec.message());
}

void VtuSeries::write(const ExplicitSolid& solid, const NodalFields& extra)
{
    char index[32];
    std::snprintf(index, sizeof index, "%06d", count());
    write(solid, extra, index, solid.time());
}

void VtuSeries::resume(double time)
{
    times_.clear();
    const std::string path = directory_ + "/" + name_ + ".pvd";
    std::ifstream is(path);
    if (!is) return;
    std::string line;
    bool collection = false;
    while (std::getline(is, line)) {
        if (line.find("type=\"Collection\"") != std::string::npos) collection = true;
        const auto ts = line.find("timestep=\"");
        const auto fs = line.find("file=\"");
        if (ts == std::string::npos || fs == std::string::npos) continue;
        const auto te = line.find('"', ts + 10);
        const auto fe = line.find('"', fs + 6);
        if (te == std::string::npos || fe == std::string::npos) {
            throw Error("cannot read the collection '" + path + "': bad line '" + line + "'");
        }
        double t = 0;
        try {
            t = std::stod(line.substr(ts + 10, te - ts - 10));
        } catch (const std::exception&) {
            throw Error("cannot read the collection '" + path + "': bad time in '" + line + "'");
        }
        if (t <= time * (1 + 1e-12) + 1e-300) times_.emplace_back(t, line.substr(fs + 6, fe - fs - 6));
    }
    if (!collection) {
        throw Error("'" + path + "' is not a VTK collection (.pvd): remove it or choose another "
                    "output directory");
    }
    writePvd();
}

void VtuSeries::write(const ExplicitSolid& solid, const NodalFields& extra,
                      const std::string& label, double time)
{
    const TetMesh& mesh = solid.mesh();
    const int nn = mesh.nNodes(), ne = mesh.nElements();

    std::vector<Mat3> sigma;
    std::vector<double> J;
    solid.elementStress(sigma, J);
    std::vector<double> sig9(9 * ne), mises(ne), maxPrincipal(ne);
    for (int e = 0; e < ne; ++e) {
        const Mat3 s = 0.5 * (sigma[e] + sigma[e].transpose());
        for (int a = 0; a < 3; ++a)
            for (int b = 0; b < 3; ++b) sig9[9 * e + 3 * a + b] = s(a, b);
        const Mat3 dev = s - s.trace() / 3.0 * Mat3::Identity();
        mises[e] = std::sqrt(1.5 * dev.cwiseProduct(dev).sum());
        Eigen::SelfAdjointEigenSolver<Mat3> eig(s, Eigen::EigenvaluesOnly);
        maxPrincipal[e] = eig.eigenvalues().maxCoeff();
    }

    std::vector<std::int64_t> conn(4 * ne), offsets(ne);
    std::vector<std::uint8_t> types(ne, 10);  // VTK_TETRA
    for (int e = 0; e < ne; ++e) {
        for (int a = 0; a < 4; ++a) conn[4 * e + a] = mesh.elements()[e][a];
        offsets[e] = 4 * (e + 1);
    }

    const std::string file = name_ + "_" + label + ".vtu";
    std::ofstream os(directory_ + "/" + file);
    if (!os) throw Error("cannot write '" + directory_ + "/" + file + "'");
    os << "<?xml version=\"1.0\"?>\n"
       << "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
          "header_type=\"UInt64\">\n  <UnstructuredGrid>\n"
       << "    <Piece NumberOfPoints=\"" << nn << "\" NumberOfCells=\"" << ne << "\">\n"
       << "      <Points>\n";
    dataArray(os, "Float64", "Points", 3, flatten(solid.currentCoordinates()));
    os << "      </Points>\n      <Cells>\n";
    dataArray(os, "Int64", "connectivity", 1, conn);
    dataArray(os, "Int64", "offsets", 1, offsets);
    dataArray(os, "UInt8", "types", 1, types);
    os << "      </Cells>\n      <PointData Vectors=\"displacement\">\n";
    dataArray(os, "Float64", "displacement", 3, flatten(solid.displacement()));
    dataArray(os, "Float64", "velocity", 3, flatten(solid.velocity()));
    dataArray(os, "Float64", "externalForce", 3,
              flatten(solid.externalForce()));
    for (const auto& [fieldName, values] : extra) {
        const int comps = static_cast<int>(values.size() / std::max(nn, 1));
        if (comps * nn != static_cast<int>(values.size()) || (comps != 1 && comps != 3)) {
            throw Error("VtuSeries: field '" + fieldName + "' has " +
                        std::to_string(values.size()) + " values for " + std::to_string(nn) +
                        " nodes (need 1 or 3 per node)");
        }
        dataArray(os, "Float64", fieldName, comps, values);
    }
    os << "      </PointData>\n      <CellData Scalars=\"vonMises\">\n";
    dataArray(os, "Float64", "cauchyStress", 9, sig9);
    dataArray(os, "Float64", "vonMises", 1, mises);
    dataArray(os, "Float64", "maxPrincipalStress", 1, maxPrincipal);
    dataArray(os, "Float64", "J", 1, J);
    if (!solid.fibreDirections().empty()) {
        // the fibres in the current configuration: a = F_e a0, unit
        // direction and stretch |a| per element
        const auto& u = solid.displacement();
        std::vector<double> dir(3 * ne), stretch(ne);
        for (int e = 0; e < ne; ++e) {
            const auto g = elementGradients(mesh, e);
            Mat3 F = Mat3::Identity();
            for (int a = 0; a < 4; ++a) F += u[mesh.elements()[e][a]] * g.row(a);
            const Vec3 a = F * solid.fibreDirections()[e];
            stretch[e] = a.norm();
            for (int k = 0; k < 3; ++k) dir[3 * e + k] = a[k] / stretch[e];
        }
        dataArray(os, "Float64", "fibreDirection", 3, dir);
        dataArray(os, "Float64", "fibreStretch", 1, stretch);
    }
    os << "      </CellData>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n";
    if (!os) throw Error("error while writing '" + directory_ + "/" + file + "'");

    // (a file written again, e.g. after a restart, replaces its entry)
    times_.erase(std::remove_if(times_.begin(), times_.end(),
                                [&](const auto& tf) { return tf.second == file || tf.first >= time; }),
                 times_.end());
    times_.emplace_back(time, file);
    writePvd();
}

void VtuSeries::writePvd() const
{
    const std::string path = directory_ + "/" + name_ + ".pvd";
    std::ofstream os(path);
    if (!os) throw Error("cannot write '" + path + "'");
    os << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n"
          "  <Collection>\n";
    for (const auto& [t, file] : times_) {
        os.precision(17);
        os << "    <DataSet timestep=\"" << t << "\" part=\"0\" file=\"" << file << "\"/>\n";
    }
    os << "  </Collection>\n</VTKFile>\n";
}

}  // namespace smoothedSolid
