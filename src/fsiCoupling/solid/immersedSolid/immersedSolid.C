/*---------------------------------------------------------------------------*\
    isfem: immersed smoothed finite element method (fsiCoupling)
\*---------------------------------------------------------------------------*/

// The solid library first (Eigen), then OpenFOAM
#include "mesh/TetMesh.hpp"

#include "immersedSolid.H"

// * * * * * * * * * * * * * * Static Data Members * * * * * * * * * * * * * //

namespace Foam
{
    defineTypeNameAndDebug(immersedSolid, 0);
    defineRunTimeSelectionTable(immersedSolid, dictionary);
}


// * * * * * * * * * * * * Protected Member Functions  * * * * * * * * * * * //

void Foam::immersedSolid::checkKeywords
(
    const dictionary& dict,
    const wordList& allowed
) const
{
    for (const entry& e : dict)
    {
        const word& key = e.keyword();
        if
        (
            key == "FoamFile"
         || (&dict == &dict_ && key == "coupling")
         || allowed.found(key)
        )
        {
            continue;
        }
        FatalIOErrorInFunction(dict)
            << "Unknown keyword '" << key << "' in " << dict.name()
            << " (file " << dict_.objectPath() << ")" << nl
            << "    Valid keywords: " << flatOutput(allowed)
            << exit(FatalIOError);
    }
}


Foam::fileName Foam::immersedSolid::meshFile() const
{
    fileName f(dict_.get<fileName>("mesh"));
    f.expand();
    if (!f.isAbsolute())
    {
        f = runTime_.globalPath()/f;
    }
    return f;
}


void Foam::immersedSolid::readMesh()
{
    const fileName f(meshFile());
    if (!isFile(f))
    {
        FatalIOErrorInFunction(dict_)
            << "The solid mesh file " << f << " of entry 'mesh' does not exist"
            << exit(FatalIOError);
    }

    try
    {
        const smoothedSolid::TetMesh mesh =
            smoothedSolid::TetMesh::fromGmsh(f);

        points0_.setSize(mesh.nNodes());
        forAll(points0_, i)
        {
            const smoothedSolid::Vec3& X = mesh.coordinates()[i];
            points0_[i] = point(X(0), X(1), X(2));
        }
        elements_.setSize(mesh.nElements());
        forAll(elements_, e)
        {
            for (label k = 0; k < 4; ++k)
            {
                elements_[e][k] = mesh.elements()[e][k];
            }
        }
        nodeSets_.clear();
        for (const std::string& name : mesh.nodeSetNames())
        {
            const std::vector<int>& s = mesh.nodeSet(name);
            labelList l(label(s.size()));
            forAll(l, i) { l[i] = s[i]; }
            nodeSets_.insert(word(name), l);
        }
    }
    catch (const smoothedSolid::Error& err)
    {
        FatalIOErrorInFunction(dict_)
            << "Cannot read the solid mesh of entry 'mesh': " << f << nl
            << "    " << err.what()
            << exit(FatalIOError);
    }

    points_ = points0_;
    velocities_.setSize(points0_.size(), Zero);
    externalForce_.setSize(points0_.size(), Zero);
}


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::immersedSolid::immersedSolid
(
    const Time& runTime,
    const IOdictionary& dict
)
:
    runTime_(runTime),
    dict_(dict),
    time_(runTime.value())
{
    readMesh();
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

void Foam::immersedSolid::surface
(
    List<labelledTri>& triangles,
    labelList& surfacePoints,
    CompactListList<label>& elementTriangles
) const
{
    // The faces of a tet, outward for a positively oriented one
    auto tetFace = [](const solidTet& t, const label i)
    {
        static const label vertex[4][3] =
            {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
        return triFace(t[vertex[i][0]], t[vertex[i][1]], t[vertex[i][2]]);
    };
    auto sorted = [](triFace f)
    {
        std::sort(f.begin(), f.end());
        return f;
    };

    HashTable<label, triFace, Hash<triFace>> count(4*elements_.size());
    for (const solidTet& t : elements_)
    {
        for (label i = 0; i < 4; ++i)
        {
            ++count(sorted(tetFace(t, i)), 0);
        }
    }

    // Element by element, on the surface's own points
    labelList local(points_.size(), -1);
    DynamicList<label> points;
    DynamicList<labelledTri> tris;
    labelList nTriangles(elements_.size(), 0);
    forAll(elements_, e)
    {
        for (label i = 0; i < 4; ++i)
        {
            triFace f(tetFace(elements_[e], i));
            if (count[sorted(f)] != 1)
            {
                continue;
            }
            for (label& pointi : f)
            {
                if (local[pointi] < 0)
                {
                    local[pointi] = points.size();
                    points.append(pointi);
                }
                pointi = local[pointi];
            }
            tris.append(labelledTri(f[0], f[1], f[2], 0));
            ++nTriangles[e];
        }
    }
    triangles.transfer(tris);
    surfacePoints.transfer(points);

    // (the triangles are in element order)
    elementTriangles.setSize(nTriangles);
    labelList& m = elementTriangles.m();
    forAll(m, i)
    {
        m[i] = i;
    }
}


const Foam::labelList& Foam::immersedSolid::nodeSet
(
    const word& name,
    const dictionary& dict,
    const word& keyword
) const
{
    const auto iter = nodeSets_.cfind(name);
    if (!iter.found())
    {
        FatalIOErrorInFunction(dict)
            << "Entry '" << keyword << "' in " << dict.name()
            << ": the solid mesh " << meshFile()
            << " has no physical group '" << name << "'" << nl
            << "    Node sets: " << flatOutput(nodeSets_.sortedToc())
            << exit(FatalIOError);
    }
    return *iter;
}


void Foam::immersedSolid::setState
(
    const pointField& points,
    const vectorField& velocities
)
{
    if (points.size() != nPoints() || velocities.size() != nPoints())
    {
        FatalErrorInFunction
            << "Expected " << nPoints() << " points and velocities, got "
            << points.size() << " and " << velocities.size()
            << exit(FatalError);
    }
    points_ = points;
    velocities_ = velocities;
}


bool Foam::immersedSolid::restart(const string& owner)
{
    const fileName dir(stateDir());
    if (readState(dir))
    {
        Info<< owner.c_str() << ": solid state read from " << dir
            << " (t = " << time() << ")" << endl;
        return true;
    }
    if (isDeformable())
    {
        Info<< owner.c_str() << ": no solid state in " << dir
            << ": the solid starts from its mesh, at rest" << endl;
    }
    return false;
}


// ************************************************************************* //
