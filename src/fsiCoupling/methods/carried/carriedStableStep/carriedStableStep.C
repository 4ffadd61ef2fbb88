/*---------------------------------------------------------------------------*\
    isfem: immersed smoothed finite element method (fsiCoupling)
\*---------------------------------------------------------------------------*/

#include "carriedStableStep.H"
#include "OFstream.H"
#include "IFstream.H"
#include "PtrList.H"

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>

// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::carriedStableStep::carriedStableStep
(
    const fvMesh& mesh,
    carriedCouplingMap& map,
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
    map_(map)
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
    const word& scheme = map_.ddtScheme();
    if (scheme != "Euler" && scheme != "backward")
    {
        FatalIOErrorInFunction(coeffs)
            << "fvOption " << owner_ << ": the stable step estimate"
            << " (stableStep) knows the explicit force's bound under the"
            << " Euler and backward time schemes, not ddt(U) " << scheme
            << " (system/fvSchemes): use one of them, or remove stableStep"
            << " and set the step by maxDeltaT" << exit(FatalIOError);
    }
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
    const label solves0 = map_.solves();
    for (; k < m; ++k)
    {
        vectorField v
        (
            cmptMultiply
            (
                map_.apply(Q[k], stiffness, forceFlux, velocity, 1e-4)(),
                free
            )
        );
        H(k + 1, k) = carriedCouplingMap::orthogonalise(Q, k, v, H);
        if (!(H(k + 1, k) > 1e-12*mag(H(k, k))))
        {
            ++k;
            break;
        }
        Q.set(k + 1, new vectorField(v/H(k + 1, k)));
    }
    iterationsDone_ = k;
    solves_ = map_.solves() - solves0;
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
    const scalar c = map_.backward() ? 8 : 4;
    // (sqrt(beta^2 omega^2 + c) - beta omega)/omega, without cancellation
    const scalar bw = beta*omega;
    scalar dt = c/(omega*(Foam::sqrt(sqr(bw) + c) + bw));
    if (map_.backward())
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
        << " Poisson iterations; " << map_.ddtScheme()
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
