#include "testMeshes.hpp"

#include "mesh/TetMesh.hpp"

#include <gmsh.h>
#include <gtest/gtest.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <stdexcept>

#include <sys/wait.h>
#include <unistd.h>

namespace smoothedSolid::test {

using smoothedSolid::initializeGmsh;

namespace {

// A fresh directory per process: ctest -j runs every TEST as its own process,
// and several checkouts may test on one machine, so a shared fixed directory
// would let processes overwrite each other's files. Removed at process exit
// unless SMOOTHEDSOLID_KEEP_TEST_FILES is set (to inspect the files). Owned by
// the pid that created it: a forked child gets its own directory and never
// removes its parent's.
class ProcessTempDir {
public:
    const std::string& path()
    {
        const std::lock_guard<std::mutex> lock(mutex_);
        if (owner_ != ::getpid()) {
            std::string pattern =
                (std::filesystem::temp_directory_path() /
                 ("smoothedSolidTests-" + std::to_string(::getpid()) + "-XXXXXX"))
                    .string();
            if (!::mkdtemp(pattern.data())) {
                throw std::runtime_error("cannot create a temporary directory '" + pattern +
                                         "': " + std::strerror(errno));
            }
            path_ = pattern;
            owner_ = ::getpid();
        }
        return path_;
    }

    ~ProcessTempDir()
    {
        if (owner_ != ::getpid()) return;
        if (std::getenv("SMOOTHEDSOLID_KEEP_TEST_FILES")) {
            std::fprintf(stderr, "kept test files in %s\n", path_.c_str());
            return;
        }
        std::error_code ec;  // never throw from a destructor at exit
        std::filesystem::remove_all(path_, ec);
    }

private:
    std::mutex mutex_;
    std::string path_;
    pid_t owner_ = 0;
};

}  // namespace

std::string tempDir()
{
    static ProcessTempDir dir;  // created on first use, removed by exit()
    return dir.path();
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

namespace {

// Runs tempDir() in a forked child that writes a file there and exits
// normally (running static destructors); returns the child's directory
std::string tempDirOfChildProcess(bool keep)
{
    int fds[2];
    if (::pipe(fds) != 0) return {};
    std::fflush(nullptr);  // else the child flushes the parent's buffered output again
    const pid_t pid = ::fork();
    if (pid == 0) {
        ::close(fds[0]);
        if (keep) ::setenv("SMOOTHEDSOLID_KEEP_TEST_FILES", "1", 1);
        else ::unsetenv("SMOOTHEDSOLID_KEEP_TEST_FILES");
        const std::string dir = smoothedSolid::test::tempDir();
        std::FILE* f = std::fopen((dir + "/file.txt").c_str(), "w");
        const bool ok = f && std::fputs("x", f) >= 0 && std::fclose(f) == 0;
        if (ok) (void)!::write(fds[1], dir.data(), dir.size());
        ::close(fds[1]);
        std::exit(ok ? 0 : 1);
    }
    ::close(fds[1]);
    std::string dir;
    char buf[256];
    for (ssize_t n; (n = ::read(fds[0], buf, sizeof buf)) > 0;) dir.append(buf, n);
    ::close(fds[0]);
    int status = 0;
    ::waitpid(pid, &status, 0);
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "child status " << status;
    return dir;
}

}  // namespace

// The test processes that ctest -j runs side by side must not share files
TEST(TestSupport, TempDirIsPerProcess)
{
    namespace fs = std::filesystem;
    using smoothedSolid::test::tempDir;
    const std::string dir = tempDir();
    const fs::path p(dir);
    const std::string name = p.filename().string();
    std::printf("tempDir() = %s (pid %d; previously the fixed %s)\n", dir.c_str(),
                static_cast<int>(::getpid()),
                (fs::temp_directory_path() / "smoothedSolidTests").c_str());
    EXPECT_EQ(tempDir(), dir);  // one directory for the whole process
    EXPECT_TRUE(fs::is_directory(p));
    EXPECT_EQ(p.parent_path(), fs::temp_directory_path());
    EXPECT_NE(name, "smoothedSolidTests");
    EXPECT_EQ(name.rfind("smoothedSolidTests-" + std::to_string(::getpid()) + "-", 0), 0u)
        << name;

    // Another process gets another directory, removed when it exits ...
    const std::string child = tempDirOfChildProcess(false);
    std::printf("child process: %s, exists after its exit: %s (expected no)\n", child.c_str(),
                fs::exists(child) ? "yes" : "no");
    EXPECT_FALSE(child.empty());
    EXPECT_NE(child, dir);
    EXPECT_FALSE(fs::exists(child));

    // ... unless SMOOTHEDSOLID_KEEP_TEST_FILES is set
    const std::string kept = tempDirOfChildProcess(true);
    const bool keptFile = !kept.empty() && fs::exists(kept + "/file.txt");
    std::printf("child with SMOOTHEDSOLID_KEEP_TEST_FILES: %s, file kept: %s (expected yes)\n",
                kept.c_str(), keptFile ? "yes" : "no");
    EXPECT_TRUE(keptFile);
    if (!kept.empty()) fs::remove_all(kept);
}
