/*---------------------------------------------------------------------------*\
    isfem: immersed smoothed finite element method (fsiCoupling)
\*---------------------------------------------------------------------------*/

#include "immersedBoundary.H"
#include "fvMatrices.H"
#include "fvcSurfaceIntegrate.H"
#include "surfaceInterpolate.H"
#include "linear.H"
#include "syncTools.H"
#include "coupledFvPatch.H"
#include "triSurfaceSearch.H"

// * * * * * * * * * * * * * * Static Data Members * * * * * * * * * * * * * //

namespace Foam
{
    defineTypeNameAndDebug(immersedBoundary, 0);
}


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::immersedBoundary::immersedBoundary
(
    const fvMesh& mesh
)
:
    regIOobject
    (
        IOobject
        (
            typeName,
            mesh.time().constant(),
            mesh,
            IOobject::NO_READ,
            IOobject::NO_WRITE,
            true
        )
    ),
    mesh_(mesh),
    coveredCells_(),
    coveredVelocity_(),
    coveredIndex_(mesh.nCells(), -1),
    nEnclosed_(0),
    refCells_(),
    pName_("p"),
    nbrCovered_(mesh.nBoundaryFaces(), false),
    nbrVelocity_(mesh.nBoundaryFaces(), Zero),
    internalFaces_(),
    boundaryFaces_(),
    wallFraction_()
{}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

void Foam::immersedBoundary::update
(
    const labelUList& coveredCells,
    const vectorField& coveredVelocity
)
{
    coveredCells_ = coveredCells;
    coveredVelocity_ = coveredVelocity;

    coveredIndex_ = -1;
    forAll(coveredCells_, i)
    {
        coveredIndex_[coveredCells_[i]] = i;
    }

    findEnclosedFluid();

    // Covered flag and solid velocity of the cells across processor faces
    {
        boolList cellCovered(mesh_.nCells(), false);
        vectorField cellVelocity(mesh_.nCells(), Zero);
        forAll(coveredCells_, i)
        {
            cellCovered[coveredCells_[i]] = true;
            cellVelocity[coveredCells_[i]] = coveredVelocity_[i];
        }
        syncTools::swapBoundaryCellList(mesh_, cellCovered, nbrCovered_);
        syncTools::swapBoundaryCellList(mesh_, cellVelocity, nbrVelocity_);
    }

    // Immersed faces: every face of a covered cell (internal, or coupled
    // boundary), and the coupled faces whose other side is covered
    const cellList& cells = mesh_.cells();
    const polyBoundaryMesh& pbm = mesh_.boundaryMesh();
    boolList isImmersed(mesh_.nFaces(), false);
    DynamicList<label> internal(6*coveredCells_.size());
    DynamicList<label> boundary;

    for (const label celli : coveredCells_)
    {
        for (const label facei : cells[celli])
        {
            if (isImmersed[facei])
            {
                continue;
            }
            if (mesh_.isInternalFace(facei))
            {
                isImmersed[facei] = true;
                internal.append(facei);
            }
            else if (pbm[pbm.whichPatch(facei)].coupled())
            {
                isImmersed[facei] = true;
                boundary.append(facei);
            }
        }
    }
    forAll(pbm, patchi)
    {
        if (pbm[patchi].coupled())
        {
            const label start = pbm[patchi].start();
            forAll(pbm[patchi], i)
            {
                const label facei = start + i;
                if (!isImmersed[facei] && nbrCovered(facei))
                {
                    isImmersed[facei] = true;
                    boundary.append(facei);
                }
            }
        }
    }

    internalFaces_.transfer(internal);
    boundaryFaces_.transfer(boundary);
    wallFraction_.setSize(nFaces());
    wallFraction_ = -1;
}


void Foam::immersedBoundary::locateWall(const triSurface& surface)
{
    const labelUList& own = mesh_.owner();
    const labelUList& nei = mesh_.neighbour();
    const volVectorField& C = mesh_.C();
    const polyBoundaryMesh& pbm = mesh_.boundaryMesh();

    // Cell centres across coupled faces
    pointField nbrC(mesh_.nBoundaryFaces());
    {
        pointField cellC(C.primitiveField());
        syncTools::swapBoundaryCellList(mesh_, cellC, nbrC);
    }

    // Segments from the covered to the fluid cell centre
    const label nInt = internalFaces_.size();
    pointField start(nFaces());
    pointField end(nFaces());
    boolList isCF(nFaces(), false);
    forAll(internalFaces_, i)
    {
        const label facei = internalFaces_[i];
        const bool oc = covered(own[facei]);
        if (oc != covered(nei[facei]))
        {
            isCF[i] = true;
            start[i] = C[oc ? own[facei] : nei[facei]];
            end[i] = C[oc ? nei[facei] : own[facei]];
        }
        else
        {
            start[i] = end[i] = C[own[facei]];
        }
    }
    forAll(boundaryFaces_, j)
    {
        const label facei = boundaryFaces_[j];
        const label i = nInt + j;
        const label o = mesh_.faceOwner()[facei];
        start[i] = end[i] = C[o];
        if (covered(o) && !nbrCovered(facei))
        {
            isCF[i] = true;
            end[i] = nbrC[facei - mesh_.nInternalFaces()];
        }
    }

    const triSurfaceSearch search(surface);
    List<pointIndexHit> hits;
    search.findLine(start, end, hits);

    wallFraction_ = -1;
    forAll(hits, i)
    {
        if (isCF[i] && hits[i].hit())
        {
            const scalar d = mag(end[i] - start[i]);
            wallFraction_[i] =
                min(max(mag(hits[i].hitPoint() - start[i])/d, 0.0), 1.0);
        }
    }
    (void)pbm;
}


Foam::tmp<Foam::vectorField> Foam::immersedBoundary::ghostVelocity
(
    const volVectorField& U
) const
{
    const labelUList& own = mesh_.owner();
    const labelUList& nei = mesh_.neighbour();
    const polyBoundaryMesh& pbm = mesh_.boundaryMesh();
    const label nInt = internalFaces_.size();
    // r = lambda/(1 - lambda) at most 2 (lambda <= 2/3): the explicit
    // extrapolation stays a contraction for the fluid cell's row
    const scalar rMax = 2;

    vectorField sum(coveredCells_.size(), Zero);
    labelList count(coveredCells_.size(), 0);

    auto add = [&](const label ic, const vector& uF, const scalar lambda)
    {
        const vector& us = coveredVelocity_[ic];
        const scalar r = min(lambda/max(1 - lambda, SMALL), rMax);
        sum[ic] += us + (us - uF)*r;
        ++count[ic];
    };

    forAll(internalFaces_, i)
    {
        if (wallFraction_[i] < 0)
        {
            continue;
        }
        const label facei = internalFaces_[i];
        const label io = coveredIndex_[own[facei]];
        const label F = io >= 0 ? nei[facei] : own[facei];
        add(io >= 0 ? io : coveredIndex_[nei[facei]], U[F], wallFraction_[i]);
    }
    if (Pstream::parRun())
    {
        vectorField nbrU(mesh_.nBoundaryFaces(), Zero);
        forAll(pbm, patchi)
        {
            if (pbm[patchi].coupled())
            {
                SubList<vector>
                (
                    nbrU,
                    pbm[patchi].size(),
                    pbm[patchi].start() - mesh_.nInternalFaces()
                ) = U.boundaryField()[patchi].patchNeighbourField();
            }
        }
        forAll(boundaryFaces_, j)
        {
            if (wallFraction_[nInt + j] < 0)
            {
                continue;
            }
            const label facei = boundaryFaces_[j];
            add
            (
                coveredIndex_[mesh_.faceOwner()[facei]],
                nbrU[facei - mesh_.nInternalFaces()],
                wallFraction_[nInt + j]
            );
        }
    }

    tmp<vectorField> tu(new vectorField(coveredVelocity_));
    vectorField& u = tu.ref();
    forAll(u, i)
    {
        if (count[i])
        {
            u[i] = sum[i]/count[i];
        }
    }
    return tu;
}


void Foam::immersedBoundary::slip
(
    const volVectorField& U,
    scalar& sumSqr,
    label& count
) const
{
    const labelUList& own = mesh_.owner();
    const labelUList& nei = mesh_.neighbour();

    boolList ghost(coveredCells_.size(), false);
    forAll(internalFaces_, i)
    {
        if (wallFraction_[i] >= 0)
        {
            const label facei = internalFaces_[i];
            const label io = coveredIndex_[own[facei]];
            ghost[io >= 0 ? io : coveredIndex_[nei[facei]]] = true;
        }
    }
    forAll(boundaryFaces_, j)
    {
        if (wallFraction_[internalFaces_.size() + j] >= 0)
        {
            ghost[coveredIndex_[mesh_.faceOwner()[boundaryFaces_[j]]]] = true;
        }
    }
    forAll(coveredCells_, i)
    {
        if (!ghost[i])
        {
            sumSqr += magSqr(U[coveredCells_[i]] - coveredVelocity_[i]);
            ++count;
        }
    }

    forAll(internalFaces_, i)
    {
        const scalar lambda = wallFraction_[i];
        if (lambda < 0)
        {
            continue;
        }
        const label facei = internalFaces_[i];
        const label io = coveredIndex_[own[facei]];
        const label Cc = io >= 0 ? own[facei] : nei[facei];
        const label F = io >= 0 ? nei[facei] : own[facei];
        const vector uWall(U[Cc] + lambda*(U[F] - U[Cc]));
        sumSqr += magSqr(uWall - coveredVelocity_[coveredIndex_[Cc]]);
        ++count;
    }
}


void Foam::immersedBoundary::findEnclosedFluid()
{
    // Fluid cells connected (through faces between fluid cells) to a cell
    // where the pressure is fixed: a boundary face whose p condition
    // fixes the value, or, with none in the domain, the reference cell
    // (CBS pRefCell, on the master). Flood fill, repeated across processor
    // faces until no rank changes.
    const labelUList& own = mesh_.owner();
    const labelUList& nei = mesh_.neighbour();
    const cellList& cells = mesh_.cells();
    const polyBoundaryMesh& pbm = mesh_.boundaryMesh();
    const label nInternal = mesh_.nInternalFaces();

    boolList reached(mesh_.nCells(), false);
    DynamicList<label> front;
    auto seed = [&](const label celli)
    {
        if (coveredIndex_[celli] < 0 && !reached[celli])
        {
            reached[celli] = true;
            front.append(celli);
        }
    };

    const volScalarField* pPtr = mesh_.findObject<volScalarField>(pName_);
    bool anyFixed = false;
    if (pPtr)
    {
        forAll(pbm, patchi)
        {
            if (!pbm[patchi].coupled() && pPtr->boundaryField()[patchi].fixesValue())
            {
                anyFixed = anyFixed || pbm[patchi].size();
                for (const label celli : pbm[patchi].faceCells())
                {
                    seed(celli);
                }
            }
        }
    }
    reduce(anyFixed, orOp<bool>());
    if (!anyFixed && Pstream::master() && mesh_.nCells())
    {
        const label refCell =
            mesh_.solutionDict().subOrEmptyDict("CBS")
           .getOrDefault<label>("pRefCell", 0);
        seed(min(max(refCell, 0), mesh_.nCells() - 1));
    }

    while (true)
    {
        while (front.size())
        {
            const label celli = front.remove();
            for (const label facei : cells[celli])
            {
                if (facei < nInternal)
                {
                    seed(own[facei] == celli ? nei[facei] : own[facei]);
                }
            }
        }
        if (!Pstream::parRun())
        {
            break;
        }
        // across processor faces (fluid on both sides)
        boolList nbrReached(mesh_.nBoundaryFaces(), false);
        syncTools::swapBoundaryCellList(mesh_, reached, nbrReached);
        label added = 0;
        forAll(pbm, patchi)
        {
            if (!pbm[patchi].coupled())
            {
                continue;
            }
            const labelUList& faceCells = pbm[patchi].faceCells();
            forAll(faceCells, i)
            {
                if (nbrReached[pbm[patchi].start() + i - nInternal])
                {
                    const label before = front.size();
                    seed(faceCells[i]);
                    added += front.size() - before;
                }
            }
        }
        if (!returnReduce(added, sumOp<label>()))
        {
            break;
        }
    }

    // The fluid cells not reached form regions enclosed by the solid (and
    // walls) where the pressure is only known up to a constant: one cell
    // of each (this rank's part) gets a reference in constrainPressure
    refCells_.clear();
    nEnclosed_ = 0;
    forAll(reached, celli)
    {
        if (reached[celli] || coveredIndex_[celli] >= 0)
        {
            continue;
        }
        refCells_.append(celli);
        seed(celli);
        while (front.size())
        {
            const label cellj = front.remove();
            ++nEnclosed_;
            for (const label facei : cells[cellj])
            {
                if (facei < nInternal)
                {
                    seed(own[facei] == cellj ? nei[facei] : own[facei]);
                }
            }
        }
    }
}


void Foam::immersedBoundary::constrainFlux(surfaceScalarField& phi) const
{
    const labelUList& own = mesh_.owner();
    const labelUList& nei = mesh_.neighbour();
    const surfaceVectorField& Sf = mesh_.Sf();

    scalarField& phiI = phi.primitiveFieldRef();
    for (const label facei : internalFaces_)
    {
        const label io = coveredIndex_[own[facei]];
        const label in = coveredIndex_[nei[facei]];
        vector us(Zero);
        if (io >= 0 && in >= 0)
        {
            us = 0.5*(coveredVelocity_[io] + coveredVelocity_[in]);
        }
        else
        {
            us = coveredVelocity_[io >= 0 ? io : in];
        }
        phiI[facei] = us & Sf[facei];
    }

    const polyBoundaryMesh& pbm = mesh_.boundaryMesh();
    auto& phiB = phi.boundaryFieldRef();
    for (const label facei : boundaryFaces_)
    {
        const label patchi = pbm.whichPatch(facei);
        const label i = facei - pbm[patchi].start();
        const label io = coveredIndex_[mesh_.faceOwner()[facei]];
        const bool nc = nbrCovered(facei);
        const vector& un = nbrVelocity_[facei - mesh_.nInternalFaces()];
        vector us(Zero);
        if (io >= 0 && nc)
        {
            us = 0.5*(coveredVelocity_[io] + un);
        }
        else
        {
            us = io >= 0 ? coveredVelocity_[io] : un;
        }
        phiB[patchi][i] = us & Sf.boundaryField()[patchi][i];
    }
}


void Foam::immersedBoundary::constrainLaplacian
(
    surfaceScalarField& rAUf
) const
{
    scalarField& rI = rAUf.primitiveFieldRef();
    for (const label facei : internalFaces_)
    {
        rI[facei] = 0;
    }
    const polyBoundaryMesh& pbm = mesh_.boundaryMesh();
    auto& rB = rAUf.boundaryFieldRef();
    for (const label facei : boundaryFaces_)
    {
        const label patchi = pbm.whichPatch(facei);
        rB[patchi][facei - pbm[patchi].start()] = 0;
    }
}


void Foam::immersedBoundary::constrainPressure
(
    fvScalarMatrix& pEqn,
    const volScalarField& p
) const
{
    // With the coefficients of all their faces zero (constrainLaplacian)
    // the covered cells are decoupled; each row becomes D p = D p_old.
    // D is small (1e-6 of the mean diagonal, same sign): a multigrid
    // agglomerate that joins a covered cell and fluid cells (agglomeration
    // by face areas) then keeps the fluid cells' coarse operator; a large D
    // there acts as a spurious fixed value on the coarse levels (GAMG
    // stalled at 1000 iterations with D = the mean diagonal).
    // Fluid regions enclosed by the solid (findEnclosedFluid) have no
    // fixed pressure: pure Neumann blocks, singular (a single enclosed
    // cell is a zero row); GAMG diverged on them. One cell of each gets a
    // reference to its current value, as fvMatrix::setReference does
    scalarField& diag = pEqn.diag();
    scalarField& source = pEqn.source();
    const scalar D = 1e-6*gAverage(diag);
    for (const label celli : coveredCells_)
    {
        diag[celli] = D;
        source[celli] = D*p[celli];
    }
    for (const label celli : refCells_)
    {
        source[celli] += diag[celli]*p[celli];
        diag[celli] += diag[celli];
        if (diag[celli] == 0)
        {
            diag[celli] = D;
            source[celli] = D*p[celli];
        }
    }
}


Foam::tmp<Foam::surfaceScalarField> Foam::immersedBoundary::wallFaceValues
(
    const volScalarField& p,
    vectorField* gradient
) const
{
    const labelUList& own = mesh_.owner();
    const labelUList& nei = mesh_.neighbour();
    const surfaceVectorField& Sf = mesh_.Sf();
    const surfaceVectorField& Cf = mesh_.Cf();
    const volVectorField& C = mesh_.C();
    const scalarField& V = mesh_.V();
    const polyBoundaryMesh& pbm = mesh_.boundaryMesh();
    const label nInternal = mesh_.nInternalFaces();

    tmp<surfaceScalarField> tpf(linearInterpolate(p));
    surfaceScalarField& pf = tpf.ref();
    scalarField& pfI = pf.primitiveFieldRef();
    auto& pfB = pf.boundaryFieldRef();

    // Start from the fluid cell's value (zero gradient at the wall)
    for (const label facei : internalFaces_)
    {
        const bool oc = covered(own[facei]);
        const bool nc = covered(nei[facei]);
        if (oc != nc)
        {
            pfI[facei] = p[oc ? nei[facei] : own[facei]];
        }
    }
    for (const label facei : boundaryFaces_)
    {
        const label patchi = pbm.whichPatch(facei);
        const label i = facei - pbm[patchi].start();
        if (!covered(mesh_.faceOwner()[facei]))
        {
            pfB[patchi][i] = p[mesh_.faceOwner()[facei]];
        }
    }

    // Gauss gradient g0 with those values. With the wall values
    // p_F + (x_f - x_F).g on the immersed faces of a fluid cell F, its Gauss
    // gradient satisfies g = g0 + M g, M = (1/V) sum_imm S_f (x_f - x_F)^T:
    // solved cell by cell, g = (I - M)^-1 g0. Where I - M is near singular
    // (the immersed faces surround the cell on opposite sides: no
    // information across; det < 0.1, e.g. a cell between the two layers of
    // a leaflet) the zero-gradient values are kept (g = g0).
    vectorField g(fvc::surfaceIntegrate(Sf*pf)().primitiveField());

    // M per fluid cell beside the wall (a map: no field over all cells)
    Map<label> wallCell(2*internalFaces_.size());
    DynamicList<label> wallCells(internalFaces_.size());
    DynamicList<tensor> M(internalFaces_.size());
    auto addFace = [&](const label F, const vector& S, const point& xf)
    {
        auto iter = wallCell.cfind(F);
        label k;
        if (iter.found())
        {
            k = iter.val();
        }
        else
        {
            k = wallCells.size();
            wallCell.insert(F, k);
            wallCells.append(F);
            M.append(Zero);
        }
        M[k] += (S*(xf - C[F]))/V[F];
    };
    for (const label facei : internalFaces_)
    {
        const label o = own[facei];
        const label n = nei[facei];
        const bool oc = covered(o);
        if (oc != covered(n))
        {
            // S_f points out of the owner
            if (oc)
            {
                addFace(n, -Sf[facei], Cf[facei]);
            }
            else
            {
                addFace(o, Sf[facei], Cf[facei]);
            }
        }
    }
    for (const label facei : boundaryFaces_)
    {
        const label o = mesh_.faceOwner()[facei];
        if (!covered(o))
        {
            const label patchi = pbm.whichPatch(facei);
            const label i = facei - pbm[patchi].start();
            addFace
            (
                o,
                Sf.boundaryField()[patchi][i],
                Cf.boundaryField()[patchi][i]
            );
        }
    }
    forAll(wallCells, k)
    {
        const label F = wallCells[k];
        const tensor A(I - M[k]);
        if (mag(det(A)) > 0.1)
        {
            g[F] = inv(A) & g[F];
        }
    }

    // The wall values with those gradients
    for (const label facei : internalFaces_)
    {
        const label o = own[facei];
        const label n = nei[facei];
        const bool oc = covered(o);
        if (oc != covered(n))
        {
            const label F = oc ? n : o;
            pfI[facei] = p[F] + ((Cf[facei] - C[F]) & g[F]);
        }
    }
    for (const label facei : boundaryFaces_)
    {
        const label o = mesh_.faceOwner()[facei];
        if (!covered(o))
        {
            const label patchi = pbm.whichPatch(facei);
            const label i = facei - pbm[patchi].start();
            pfB[patchi][i] =
                p[o] + ((Cf.boundaryField()[patchi][i] - C[o]) & g[o]);
        }
    }

    if (gradient)
    {
        *gradient = g;
    }

    // Coupled faces with the covered cell on this side: the wall value of
    // the fluid side, from the other rank
    if (boundaryFaces_.size() || Pstream::parRun())
    {
        scalarField wallValue(mesh_.nBoundaryFaces(), Zero);
        for (const label facei : boundaryFaces_)
        {
            const label patchi = pbm.whichPatch(facei);
            wallValue[facei - nInternal] =
                pfB[patchi][facei - pbm[patchi].start()];
        }
        syncTools::swapBoundaryFaceList(mesh_, wallValue);
        for (const label facei : boundaryFaces_)
        {
            if (covered(mesh_.faceOwner()[facei]) && !nbrCovered(facei))
            {
                const label patchi = pbm.whichPatch(facei);
                pfB[patchi][facei - pbm[patchi].start()] =
                    wallValue[facei - nInternal];
            }
        }
    }

    return tpf;
}


Foam::tmp<Foam::volVectorField> Foam::immersedBoundary::gaussGrad
(
    const surfaceScalarField& pf,
    const word& name
) const
{
    tmp<volVectorField> tg
    (
        new volVectorField
        (
            IOobject
            (
                "immersedGrad(" + name + ')',
                pf.instance(),
                mesh_,
                IOobject::NO_READ,
                IOobject::NO_WRITE,
                false
            ),
            fvc::surfaceIntegrate(mesh_.Sf()*pf),
            "zeroGradient"
        )
    );
    tg.ref().correctBoundaryConditions();
    return tg;
}


Foam::tmp<Foam::volVectorField> Foam::immersedBoundary::grad
(
    const volScalarField& p
) const
{
    return gaussGrad(wallFaceValues(p)(), p.name());
}


Foam::tmp<Foam::volVectorField> Foam::immersedBoundary::correctPressure
(
    volScalarField& p
) const
{
    // the gradient first: the covered cells' values set below do not
    // enter the fluid cells' wall values
    const tmp<surfaceScalarField> tpf(wallFaceValues(p));
    const surfaceScalarField& pf = tpf();
    tmp<volVectorField> tgrad(gaussGrad(pf, p.name()));
    const labelUList& own = mesh_.owner();
    const labelUList& nei = mesh_.neighbour();
    const polyBoundaryMesh& pbm = mesh_.boundaryMesh();

    scalarField sum(coveredCells_.size(), Zero);
    labelList count(coveredCells_.size(), 0);
    for (const label facei : internalFaces_)
    {
        const label io = coveredIndex_[own[facei]];
        const label in = coveredIndex_[nei[facei]];
        if ((io >= 0) != (in >= 0))
        {
            const label i = io >= 0 ? io : in;
            sum[i] += pf[facei];
            ++count[i];
        }
    }
    for (const label facei : boundaryFaces_)
    {
        const label io = coveredIndex_[mesh_.faceOwner()[facei]];
        if (io >= 0 && !nbrCovered(facei))
        {
            const label patchi = pbm.whichPatch(facei);
            sum[io] += pf.boundaryField()[patchi][facei - pbm[patchi].start()];
            ++count[io];
        }
    }
    scalarField& pI = p.primitiveFieldRef();
    forAll(coveredCells_, i)
    {
        if (count[i])
        {
            pI[coveredCells_[i]] = sum[i]/count[i];
        }
    }
    p.correctBoundaryConditions();
    return tgrad;
}


Foam::tmp<Foam::vectorField> Foam::immersedBoundary::traction
(
    const volScalarField& p,
    const volVectorField& U,
    const volScalarField& nu,
    const scalar rhoFluid
) const
{
    tmp<vectorField> tt(new vectorField(coveredCells_.size(), Zero));
    vectorField& t = tt.ref();

    vectorField gradp;
    const tmp<surfaceScalarField> tpf(wallFaceValues(p, &gradp));
    const surfaceScalarField& pf = tpf();
    const labelUList& own = mesh_.owner();
    const labelUList& nei = mesh_.neighbour();
    const surfaceVectorField& Sf = mesh_.Sf();
    const surfaceScalarField& delta = mesh_.nonOrthDeltaCoeffs();
    const volVectorField& Cc = mesh_.C();
    const polyBoundaryMesh& pbm = mesh_.boundaryMesh();

    forAll(internalFaces_, facej)
    {
        const label facei = internalFaces_[facej];
        const label o = own[facei];
        const label n = nei[facei];
        const label io = coveredIndex_[o];
        const label in = coveredIndex_[n];
        if ((io >= 0) == (in >= 0))
        {
            continue;
        }
        // S from the covered cell C to the fluid cell F
        const label C = io >= 0 ? o : n;
        const label F = io >= 0 ? n : o;
        const vector S(io >= 0 ? Sf[facei] : -Sf[facei]);
        // pressure at the wall point, else at the face
        const scalar lambda = wallFraction_[facej];
        const scalar pw =
            lambda < 0
          ? pf[facei]
          : p[F] + ((Cc[C] + lambda*(Cc[F] - Cc[C]) - Cc[F]) & gradp[F]);
        t[io >= 0 ? io : in] +=
            rhoFluid
           *(
              - pw*S
              + nu[F]*mag(S)*delta[facei]*(U[F] - U[C])
            );
    }

    forAll(pbm, patchi)
    {
        if (!pbm[patchi].coupled())
        {
            continue;
        }
        const vectorField Unbr(U.boundaryField()[patchi].patchNeighbourField());
        const scalarField nuNbr
        (
            nu.boundaryField()[patchi].patchNeighbourField()
        );
        const label start = pbm[patchi].start();
        const labelUList& faceCells = pbm[patchi].faceCells();
        forAll(pbm[patchi], i)
        {
            const label facei = start + i;
            const label io = coveredIndex_[faceCells[i]];
            if (io < 0 || nbrCovered(facei))
            {
                continue;
            }
            const vector& S = Sf.boundaryField()[patchi][i];
            t[io] +=
                rhoFluid
               *(
                  - pf.boundaryField()[patchi][i]*S
                  + nuNbr[i]*mag(S)*delta.boundaryField()[patchi][i]
                   *(Unbr[i] - U[faceCells[i]])
                );
        }
    }

    return tt;
}


// ************************************************************************* //
