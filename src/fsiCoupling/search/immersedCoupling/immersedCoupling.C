/*---------------------------------------------------------------------------*\
    isfem: immersed smoothed finite element method (fsiCoupling)
\*---------------------------------------------------------------------------*/

#include "immersedCoupling.H"

// * * * * * * * * * * * * * * Static Data Members * * * * * * * * * * * * * //

namespace Foam
{
    defineTypeNameAndDebug(immersedCoupling, 0);
}


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::immersedCoupling::immersedCoupling(const fvMesh& mesh)
:
    mesh_(mesh),
    solid_(immersedSolid::New(mesh.time())),
    pairs_(mesh, solid_->dict().subOrEmptyDict("coupling")),
    interpolationScheme_
    (
        solid_->dict().subOrEmptyDict("coupling")
       .getOrDefault<word>("interpolation", "cellLinear")
    ),
    searchTime_(0),
    transferTime_(0)
{
    if (solid_->dict().found("coupling"))
    {
        const dictionary& c = solid_->dict().subDict("coupling");
        const wordList allowed
        (
            {"coverage", "interpolation", "maxWalk", "boundaryTolerance"}
        );
        for (const entry& e : c)
        {
            if (!allowed.found(e.keyword()))
            {
                FatalIOErrorInFunction(c)
                    << "Unknown keyword '" << e.keyword() << "' in "
                    << c.name() << nl
                    << "    Valid keywords: " << flatOutput(allowed)
                    << exit(FatalIOError);
            }
        }
    }
    updatePairs();
    if (pairs_.nOnBoundary())
    {
        Info<< "immersedCoupling: " << pairs_.nOnBoundary() << " of "
            << solid_->points().size() << " solid nodes lie outside the"
            << " fluid mesh's faceted boundary, by at most "
            << pairs_.maxOutside() << " m: each in the cell of its nearest"
            << " boundary face" << endl;
    }
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

void Foam::immersedCoupling::updatePairs()
{
    const clockValue start(true);
    pairs_.findNodeCells(solid_->points());
    const scalar tNodes = double(start.elapsed());
    pairs_.findCoveredCells(solid_->points(), solid_->elements());
    searchTime_ += double(start.elapsed());
    if (debug)
    {
        Info<< "immersedCoupling: F-S pairs " << tNodes << " s, S-F pairs "
            << double(start.elapsed()) - tNodes << " s (element-cell tests "
            << pairs_.nPairTests() << ", skipped by their gap "
            << pairs_.nPairsSkipped() << ", candidate lists built "
            << pairs_.nCandidateUpdates() << " times)" << endl;
    }
}


// ************************************************************************* //
