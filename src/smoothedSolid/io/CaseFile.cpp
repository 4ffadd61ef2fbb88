#include "io/CaseFile.hpp"

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

namespace smoothedSolid {

namespace {
const std::set<std::string> kKeywords = {
    "mesh",   "box",      "hex",      "material", "formulation", "fix",           "planeStrain",
    "bodyForce", "pressure", "traction", "damping",  "safety",        "contact",
    "stiffnessDamping",
    "endTime", "writeInterval", "output", "probe",   "probeInterval", "steadyTolerance",
    "fibres", "contactSurface"};
}

CaseFile::CaseFile(const std::string& fileName) : file_(fileName)
{
    std::ifstream is(fileName);
    if (!is) throw Error("cannot open case file '" + fileName + "'");
    dir_ = std::filesystem::path(fileName).parent_path().string();
    std::string line;
    int n = 0;
    while (std::getline(is, line)) {
        ++n;
        const auto hash = line.find('#');
        if (hash != std::string::npos) line.erase(hash);
        std::istringstream ls(line);
        CaseEntry e;
        e.line = n;
        if (!(ls >> e.keyword)) continue;
        if (!kKeywords.count(e.keyword)) {
            std::string known;
            for (const auto& k : kKeywords) known += " " + k;
            throw Error(fileName + ":" + std::to_string(n) + ": unknown keyword '" + e.keyword +
                        "'; known:" + known);
        }
        std::string a;
        while (ls >> a) e.args.push_back(a);
        entries_.push_back(std::move(e));
    }
}

void CaseFile::fail(const CaseEntry& e, const std::string& what) const
{
    throw Error(file_ + ":" + std::to_string(e.line) + ": '" + e.keyword + "': " + what);
}

const CaseEntry* CaseFile::find(const std::string& keyword, bool optional) const
{
    const auto v = all(keyword);
    if (v.empty()) {
        if (optional) return nullptr;
        throw Error(file_ + ": missing entry '" + keyword + "'");
    }
    if (v.size() > 1) fail(*v[1], "given more than once");
    return v.front();
}

std::vector<const CaseEntry*> CaseFile::all(const std::string& keyword) const
{
    std::vector<const CaseEntry*> v;
    for (const auto& e : entries_) {
        if (e.keyword == keyword) v.push_back(&e);
    }
    return v;
}

double CaseFile::number(const CaseEntry& e, std::size_t i) const
{
    if (i >= e.args.size()) fail(e, "expected at least " + std::to_string(i + 1) + " values");
    try {
        std::size_t used = 0;
        const double v = std::stod(e.args[i], &used);
        if (used != e.args[i].size()) throw std::invalid_argument("");
        return v;
    } catch (const std::exception&) {
        fail(e, "'" + e.args[i] + "' is not a number");
    }
}

double CaseFile::named(const CaseEntry& e, const std::string& name, bool* found) const
{
    for (std::size_t i = 0; i + 1 < e.args.size(); ++i) {
        if (e.args[i] == name) {
            if (found) *found = true;
            return number(e, i + 1);
        }
    }
    if (found) {
        *found = false;
        return 0;
    }
    fail(e, "missing '" + name + " <value>'");
}

}  // namespace smoothedSolid
