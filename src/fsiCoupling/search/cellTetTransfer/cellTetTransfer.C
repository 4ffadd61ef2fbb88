/*---------------------------------------------------------------------------*\
    isfem: immersed smoothed finite element method (fsiCoupling)
\*---------------------------------------------------------------------------*/

#include "cellTetTransfer.H"
#include "volFields.H"
#include "tetIndices.H"
#include "syncTools.H"
#include "wallPolyPatch.H"

// * * * * * * * * * * * * * * * Static Data Members * * * * * * * * * * * * //

const Foam::Enum<Foam::cellTetTransfer::wallCondition>
Foam::cellTetTransfer::wallConditionNames
({
    { wallCondition::free, "free" },
    { wallCondition::slip, "slip" },
    { wallCondition::noSlip, "noSlip" },
});


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::cellTetTransfer::cellTetTransfer(const fvMesh& mesh)
:
    mesh_(mesh),
    pointVolume_(),
    wall_(wallCondition::free),
    wallNormal_(),
    ownCentre_(),
    nSmallCells_(0),
    cell_(),
    points_(),
    weights_()
{}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

void Foam::cellTetTransfer::setPointData(const scalar smallCell)
{
    const scalarField& V = mesh_.V();
    const labelListList& pointCells = mesh_.pointCells();
    pointVolume_.setSize(mesh_.nPoints());
    forAll(pointCells, pointi)
    {
        scalar sum = 0;
        for (const label celli : pointCells[pointi])
        {
            sum += V[celli];
        }
        pointVolume_[pointi] = sum;
    }
    syncTools::syncPointList(mesh_, pointVolume_, plusEqOp<scalar>(), 0.0);

    // A cell's centre carries its own value unless the cell is much
    // smaller than the cells around it: with its own value a node's force
    // density in it is F/(rho V_c), and a sliver tet beside the root wall
    // (checkMesh: determinant below 1e-3) blew the fluid up there; such a
    // cell's centre takes the mean of its points', whose force densities
    // are bounded by the points' cell volumes
    ownCentre_.setSize(mesh_.nCells());
    label nSmall = 0;
    forAll(V, celli)
    {
        const labelList& cPoints = mesh_.cellPoints()[celli];
        scalar around = 0;
        label count = 0;
        for (const label pointi : cPoints)
        {
            around += pointVolume_[pointi];
            count += mesh_.pointCells()[pointi].size();
        }
        // the mean volume of the cells around (point-neighbours, all ranks
        // for the points' volumes; the counts are this rank's: a bound)
        const scalar mean = around/max(count, label(1));
        ownCentre_[celli] = (V[celli] >= smallCell*mean);
        if (!ownCentre_[celli])
        {
            ++nSmall;
        }
    }
    nSmallCells_ = returnReduce(nSmall, sumOp<label>());
}


Foam::label Foam::cellTetTransfer::setWallPoints(const wallCondition c)
{
    wall_ = c;
    if (c == wallCondition::free)
    {
        wallNormal_.clear();
        return 0;
    }
    // the area-weighted normals of the wall faces around each wall point,
    // summed over the patches and the ranks (a point where two walls meet
    // takes their mean), then normalised
    wallNormal_.setSize(mesh_.nPoints());
    wallNormal_ = Zero;
    const vectorField& Sf = mesh_.faceAreas();
    for (const polyPatch& pp : mesh_.boundaryMesh())
    {
        if (!isA<wallPolyPatch>(pp))
        {
            continue;
        }
        forAll(pp, i)
        {
            const label facei = pp.start() + i;
            for (const label pointi : mesh_.faces()[facei])
            {
                wallNormal_[pointi] += Sf[facei];
            }
        }
    }
    syncTools::syncPointList
    (
        mesh_, wallNormal_, plusEqOp<vector>(), vector::zero
    );
    const bitSet master(syncTools::getMasterPoints(mesh_));
    label n = 0;
    forAll(wallNormal_, pointi)
    {
        const scalar m = mag(wallNormal_[pointi]);
        if (m > VSMALL)
        {
            wallNormal_[pointi] /= m;
            n += master.test(pointi);
        }
        else
        {
            wallNormal_[pointi] = Zero;
        }
    }
    // a point on a processor boundary counted once
    return returnReduce(n, sumOp<label>());
}


void Foam::cellTetTransfer::applyWall(vectorField& pointValues) const
{
    if (wallNormal_.empty())
    {
        return;
    }
    if (wall_ == wallCondition::slip)
    {
        // (I - n n^T) u_p
        forAll(pointValues, pointi)
        {
            const vector& n = wallNormal_[pointi];
            pointValues[pointi] -= (n & pointValues[pointi])*n;
        }
    }
    else
    {
        // the wall at rest: zero (n is zero off the walls)
        forAll(pointValues, pointi)
        {
            if (wallNormal_[pointi] != vector::zero)
            {
                pointValues[pointi] = Zero;
            }
        }
    }
}


void Foam::cellTetTransfer::setSize(const label n)
{
    cell_.setSize(n, -1);
    points_.setSize(n);
    weights_.setSize(n);
}


void Foam::cellTetTransfer::setWeights
(
    const label i,
    const point& x
)
{
    const label celli = cell_[i];
    label tetFacei = -1;
    label tetPti = -1;
    mesh_.findTetFacePt(celli, x, tetFacei, tetPti);
    if (tetFacei < 0)
    {
        // outside the cell's tets (outside the fluid, or by round-off on
        // the cell's boundary): the nearest tet, the weights clamped
        scalar best = GREAT;
        for (const label facei : mesh_.cells()[celli])
        {
            const face& f = mesh_.faces()[facei];
            for (label tetPt = 1; tetPt < f.size() - 1; ++tetPt)
            {
                const tetIndices t(celli, facei, tetPt);
                const scalar d =
                    mag(t.tet(mesh_).nearestPoint(x).rawPoint() - x);
                if (d < best)
                {
                    best = d;
                    tetFacei = facei;
                    tetPti = tetPt;
                }
            }
        }
    }
    const tetIndices tetIs(celli, tetFacei, tetPti);
    barycentric b = tetIs.tet(mesh_).pointToBarycentric(x);
    scalar sum = 0;
    for (direction k = 0; k < 4; ++k)
    {
        b[k] = max(b[k], scalar(0));
        sum += b[k];
    }
    const triFace tri(tetIs.faceTriIs(mesh_));
    for (direction k = 0; k < 4; ++k)
    {
        weights_[i][k] = b[k]/max(sum, VSMALL);
    }
    for (direction k = 0; k < 3; ++k)
    {
        points_[i][k] = tri[k];
    }
}


Foam::tmp<Foam::vectorField> Foam::cellTetTransfer::pointValues
(
    const vectorField& u
) const
{
    const scalarField& V = mesh_.V();
    const labelListList& pointCells = mesh_.pointCells();
    tmp<vectorField> tup(new vectorField(mesh_.nPoints(), Zero));
    vectorField& up = tup.ref();
    forAll(pointCells, pointi)
    {
        for (const label celli : pointCells[pointi])
        {
            up[pointi] += V[celli]*u[celli];
        }
    }
    syncTools::syncPointList(mesh_, up, plusEqOp<vector>(), vector::zero);
    forAll(up, pointi)
    {
        up[pointi] /= pointVolume_[pointi];
    }
    applyWall(up);
    return tup;
}


Foam::tmp<Foam::vectorField> Foam::cellTetTransfer::gather
(
    const vectorField& u
) const
{
    tmp<vectorField> tv(new vectorField(cell_.size(), Zero));
    vectorField& v = tv.ref();
    const vectorField up(pointValues(u));
    forAll(v, i)
    {
        const label celli = cell_[i];
        if (celli < 0)
        {
            continue;
        }
        // the cell centre's value: the cell's own, or in a cell much
        // smaller than those around it (a sliver) the mean of its points'
        // (setPointData())
        vector uc(Zero);
        if (ownCentre_[celli])
        {
            uc = u[celli];
        }
        else
        {
            const labelList& cPoints = mesh_.cellPoints()[celli];
            for (const label pointi : cPoints)
            {
                uc += up[pointi];
            }
            uc /= cPoints.size();
        }
        v[i] = weights_[i][0]*uc;
        for (direction k = 0; k < 3; ++k)
        {
            v[i] += weights_[i][k + 1]*up[points_[i][k]];
        }
    }
    Pstream::listCombineGather(v, plusEqOp<vector>());
    Pstream::listCombineScatter(v);
    return tv;
}


void Foam::cellTetTransfer::spread
(
    const vectorField& F,
    const scalar rho,
    vectorField& s
) const
{
    // the transpose of gather(): the cell centre's share to the cell (or
    // to its points equally, setPointData()), every point's share over the
    // volume of the point's cells; s per unit fluid mass
    const scalarField& V = mesh_.V();
    s.setSize(mesh_.nCells());
    s = Zero;
    vectorField pointF(mesh_.nPoints(), Zero);
    forAll(F, i)
    {
        const label celli = cell_[i];
        if (celli < 0)
        {
            continue;
        }
        if (ownCentre_[celli])
        {
            s[celli] += weights_[i][0]*F[i]/(rho*V[celli]);
        }
        else
        {
            const labelList& cPoints = mesh_.cellPoints()[celli];
            const vector Fc = weights_[i][0]*F[i]/cPoints.size();
            for (const label pointi : cPoints)
            {
                pointF[pointi] += Fc;
            }
        }
        for (direction k = 0; k < 3; ++k)
        {
            pointF[points_[i][k]] += weights_[i][k + 1]*F[i];
        }
    }
    syncTools::syncPointList(mesh_, pointF, plusEqOp<vector>(), vector::zero);
    applyWall(pointF);

    const labelListList& pointCells = mesh_.pointCells();
    forAll(pointF, pointi)
    {
        if (pointF[pointi] == vector::zero)
        {
            continue;
        }
        const vector d = pointF[pointi]/(rho*pointVolume_[pointi]);
        for (const label celli : pointCells[pointi])
        {
            s[celli] += d;
        }
    }
}


// ************************************************************************* //
