/*---------------------------------------------------------------------------*\
    isfem: immersed smoothed finite element method (fsiCoupling)
\*---------------------------------------------------------------------------*/

#include "carriedStableStep.H"
#include "fvm.H"
#include "fvc.H"
#include "fvMatrices.H"
#include "fixedValueFvPatchFields.H"
#include "zeroGradientFvPatchFields.H"
#include "OFstream.H"
#include "IFstream.H"
#include "PtrList.H"

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>

// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::carriedStableStep::carriedStableStep
(
    const fvMesh& mesh,
    const word& owner,
    const dictionary& coeffs
)
:
    mesh_(mesh),
    owner_(owner),
    interval_(20),
    iterations_(12),
    fraction_(0.8),
    refuseGrowth_(1.5),
    mode_(),
    omega2_(0),
    change_(0),
    index_(-1),
    iterationsDone_(0),
    solves_(0),
    backward_(false),
    potential_()
{
    read(coeffs);
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

void Foam::carriedStableStep::read(const dictionary& coeffs)
{
    if (!coeffs.found("stableStep"))
    {
        return;
    }
    const dictionary& dict = coeffs.subDict("stableStep");
    interval_ = dict.getOrDefault<label>("interval", 20);
    iterations_ = dict.getOrDefault<label>("iterations", 12);
    fraction_ = dict.getOrDefault<scalar>("fraction", 0.8);
    refuseGrowth_ = dict.getOrDefault<scalar>("refuseGrowth", 1.5);
    if (refuseGrowth_ != 0 && !(refuseGrowth_ > 1))
    {
        FatalIOErrorInFunction(coeffs)
            << "fvOption " << owner_ << ": stableStep refuseGrowth "
            << refuseGrowth_ << ": give a factor above 1 (the fastest"
            << " node's speed-up in one step that has the step checked),"
            << " or 0 to never refuse a step" << exit(FatalIOError);
    }
    if (interval_ < 1 || iterations_ < 1 || !(fraction_ > 0) || fraction_ > 1)
    {
        FatalIOErrorInFunction(coeffs)
            << "fvOption " << owner_ << ": stableStep { interval "
            << interval_ << "; iterations " << iterations_ << "; fraction "
            << fraction_ << "; }: give interval and iterations of at least"
            << " 1 and a fraction in (0, 1] (of the explicit force's"
            << " stable step)" << exit(FatalIOError);
    }
    ITstream& ddt = mesh_.ddtScheme("ddt(U)");
    const word scheme(ddt);
    ddt.rewind();
    if (scheme != "Euler" && scheme != "backward")
    {
        FatalIOErrorInFunction(coeffs)
            << "fvOption " << owner_ << ": the stable step estimate"
            << " (stableStep) knows the explicit force's bound under the"
            << " Euler and backward time schemes, not ddt(U) " << scheme
            << " (system/fvSchemes): use one of them, or remove stableStep"
            << " and set the step by maxDeltaT" << exit(FatalIOError);
    }
    backward_ = (scheme == "backward");
}


Foam::tmp<Foam::surfaceScalarField> Foam::carriedStableStep::project
(
    const surfaceScalarField& phi
)
{
    if (!potential_.valid())
    {
        // the pressure's conditions, homogeneous: fixed where it is fixed
        const volScalarField& p = mesh_.lookupObject<volScalarField>("p");
        wordList types(p.boundaryField().size());
        forAll(types, patchi)
        {
            const word& patchType = mesh_.boundaryMesh()[patchi].type();
            if (polyPatch::constraintType(patchType))
            {
                types[patchi] = patchType;
            }
            else if (p.boundaryField()[patchi].fixesValue())
            {
                types[patchi] = fixedValueFvPatchScalarField::typeName;
            }
            else
            {
                types[patchi] = zeroGradientFvPatchScalarField::typeName;
            }
        }
        potential_.reset
        (
            new volScalarField
            (
                IOobject
                (
                    owner_ + ":stableStepPotential",
                    mesh_.time().timeName(),
                    mesh_,
                    IOobject::NO_READ,
                    IOobject::NO_WRITE,
                    false
                ),
                mesh_,
                dimensionedScalar(phi.dimensions()/dimLength, Zero),
                types
            )
        );
        mesh_.setFluxRequired(potential_->name());
    }
    volScalarField& q = potential_.ref();
    q.primitiveFieldRef() = Zero;
    q.correctBoundaryConditions();

    fvScalarMatrix qEqn(fvm::laplacian(q) == fvc::div(phi));
    if (q.needReference())
    {
        qEqn.setReference(Pstream::master() ? 0 : -1, 0);
    }
    // the pressure's solver, converged further (an eigenvector's accuracy)
    dictionary solverDict(mesh_.solverDict("p"));
    solverDict.set("relTol", 1e-4);
    solverDict.set("tolerance", 1e-30);
    // quietly: the estimate's solves are counted in its own line
    const int debug = solverPerformance::debug;
    solverPerformance::debug = 0;
    const solverPerformance perf = qEqn.solve(solverDict);
    solverPerformance::debug = debug;
    solves_ += perf.nIterations();
    return phi - qEqn.flux();
}


Foam::tmp<Foam::vectorField> Foam::carriedStableStep::apply
(
    const vectorField& w,
    const stiffnessMap& stiffness,
    const forceFluxMap& forceFlux,
    const velocityMap& velocity
)
{
    vectorField dF;
    string why;
    if (!stiffness(w, dF, why))
    {
        FatalErrorInFunction
            << "fvOption " << owner_ << ": the leaflets' stiffness for the"
            << " stable step estimate at time " << mesh_.time().timeName()
            << ": " << why.c_str() << exit(FatalError);
    }
    // dF = -K w: the map D K w is minus the velocity it gives
    return -velocity(project(forceFlux(dF)()));
}


bool Foam::carriedStableStep::due() const
{
    return mode_.empty() || mesh_.time().timeIndex() - index_ >= interval_;
}


void Foam::carriedStableStep::estimate
(
    const bool fresh,
    const vectorField& free,
    const stiffnessMap& stiffness,
    const forceFluxMap& forceFlux,
    const velocityMap& velocity
)
{
    const bool first = mode_.size() != free.size();
    const label m = (first || fresh) ? 3*iterations_ : iterations_;
    const label index = mesh_.time().timeIndex();

    // the start: the last mode plus as much of a pseudo-random pattern (a
    // mode that grows elsewhere is found, not only the one followed;
    // deterministic: the same on every rank and on a restart)
    vectorField w(free.size());
    forAll(w, i)
    {
        w[i] = vector
        (
            Foam::sin(12.9898*i + 0.1*index),
            Foam::sin(78.233*i + 1 + 0.1*index),
            Foam::sin(37.719*i + 2 + 0.1*index)
        );
    }
    w = cmptMultiply(w, free);
    w /= max(Foam::sqrt(sum(magSqr(w))), VSMALL);
    if (!first)
    {
        w += cmptMultiply(mode_, free);
    }
    const scalar norm = Foam::sqrt(sum(magSqr(w)));
    if (!(norm > 0))
    {
        omega2_ = 0;
        index_ = index;
        return;
    }

    // Arnoldi with full (twice) Gram-Schmidt orthogonalisation (Golub &
    // Van Loan, Sect. 10.5): the largest real Ritz value of the map.
    // The solid is the same on every rank: no reductions
    PtrList<vectorField> Q(m + 1);
    Q.set(0, new vectorField(w/norm));
    Eigen::MatrixXd H = Eigen::MatrixXd::Zero(m + 1, m);
    label k = 0;
    solves_ = 0;
    for (; k < m; ++k)
    {
        vectorField v
        (
            cmptMultiply(apply(Q[k], stiffness, forceFlux, velocity)(), free)
        );
        for (label pass = 0; pass < 2; ++pass)
        {
            for (label i = 0; i <= k; ++i)
            {
                const scalar h = sum(Q[i] & v);
                H(i, k) += h;
                v -= h*Q[i];
            }
        }
        H(k + 1, k) = Foam::sqrt(sum(magSqr(v)));
        if (!(H(k + 1, k) > 1e-12*mag(H(k, k))))
        {
            ++k;
            break;
        }
        Q.set(k + 1, new vectorField(v/H(k + 1, k)));
    }
    iterationsDone_ = k;
    Eigen::EigenSolver<Eigen::MatrixXd> eig(H.topLeftCorner(k, k));
    label best = -1;
    scalar theta = 0;
    for (label j = 0; j < k; ++j)
    {
        if (eig.eigenvalues()(j).real() > theta)
        {
            theta = eig.eigenvalues()(j).real();
            best = j;
        }
    }
    if (best < 0)
    {
        omega2_ = 0;
        index_ = index;
        return;
    }
    // the Ritz vector (its real part) and its residual |h_{k+1,k} y_k|
    const Eigen::VectorXd y = eig.eigenvectors().col(best).real();
    vectorField x(free.size(), Zero);
    for (label i = 0; i < k; ++i)
    {
        x += y(i)*Q[i];
    }
    const scalar xNorm = Foam::sqrt(sum(magSqr(x)));
    change_ =
        (k < H.rows() ? mag(H(k, k - 1)*y(k - 1)) : 0)
       /max(theta*xNorm, VSMALL);
    omega2_ = theta;
    mode_ = x/max(xNorm, VSMALL);
    index_ = index;
}


Foam::label Foam::carriedStableStep::modePeak() const
{
    label peak = -1;
    scalar m = 0;
    forAll(mode_, i)
    {
        if (mag(mode_[i]) > m)
        {
            m = mag(mode_[i]);
            peak = i;
        }
    }
    return peak;
}


Foam::scalar Foam::carriedStableStep::stableDeltaT(const scalar beta) const
{
    if (!(omega2_ > 0))
    {
        return GREAT;
    }
    const scalar omega = this->omega();
    const scalar c = backward_ ? 8 : 4;
    // (sqrt(beta^2 omega^2 + c) - beta omega)/omega, without cancellation
    const scalar bw = beta*omega;
    scalar dt = c/(omega*(Foam::sqrt(sqr(bw) + c) + bw));
    if (backward_)
    {
        dt = min(dt, 2*beta);
    }
    return dt;
}


void Foam::carriedStableStep::report(Ostream& os, const scalar beta) const
{
    os  << "    stable step: " << stableDeltaT(beta) << " s (omega "
        << omega()
        << " 1/s; " << iterationsDone_ << " Arnoldi iterations, residual "
        << change_ << ", " << solves_
        << " Poisson iterations; " << (backward_ ? "backward" : "Euler")
        << ", stiffness damping " << beta << " s), allowed "
        << maxDeltaT(beta) << " s";
}


void Foam::carriedStableStep::writeState(const fileName& dir) const
{
    OFstream os(dir/"stableStep");
    os.precision(17);
    os  << omega2_ << nl << index_ << nl << mode_ << nl;
    if (!os.good())
    {
        FatalErrorInFunction
            << "Cannot write " << os.name() << exit(FatalError);
    }
}


bool Foam::carriedStableStep::readState
(
    const fileName& dir,
    const label nNodes
)
{
    if (!isFile(dir/"stableStep"))
    {
        return false;
    }
    IFstream is(dir/"stableStep");
    scalar omega2 = 0;
    label index = -1;
    is  >> omega2 >> index;
    vectorField mode(is);
    if (!is.good() || mode.size() != nNodes)
    {
        FatalIOErrorInFunction(is)
            << "fvOption " << owner_ << ": " << is.name() << " does not hold"
            << " omega^2, a time index and " << nNodes << " vectors (one per"
            << " node of the solid): the restart state does not belong to"
            << " this solid (remove the file to estimate the stable step"
            << " afresh)" << exit(FatalIOError);
    }
    omega2_ = omega2;
    index_ = index;
    mode_.transfer(mode);
    return true;
}


// ************************************************************************* //
