/*---------------------------------------------------------------------------*\
    isfem: immersed smoothed finite element method (fsiCoupling)
\*---------------------------------------------------------------------------*/

#include "carriedImplicitForce.H"
#include "PtrList.H"
#include "clockTime.H"

#include <Eigen/Dense>

// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::carriedImplicitForce::carriedImplicitForce
(
    carriedCouplingMap& map,
    const word& owner,
    const dictionary& coeffs
)
:
    map_(map),
    owner_(owner),
    iterations_(30),
    tolerance_(1e-2),
    projectionTolerance_(1e-2),
    correctionTolerance_(1e-4),
    theta_(1),
    implicitTethers_(true),
    tetherDampingTime_(2e-5),
    tetherSpringTime_(Foam::sqrt(1e-9)),
    tetherMaxGain_(20),
    lastIterations_(0),
    lastResidual_(0)
{
    read(coeffs);
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

void Foam::carriedImplicitForce::read(const dictionary& coeffs)
{
    const dictionary& d = coeffs.subDict("implicitForce");
    iterations_ = d.getOrDefault<label>("iterations", 30);
    tolerance_ = d.getOrDefault<scalar>("tolerance", 1e-2);
    projectionTolerance_ = d.getOrDefault<scalar>("projectionTolerance", 1e-2);
    correctionTolerance_ = d.getOrDefault<scalar>("correctionTolerance", 1e-4);
    theta_ = d.getOrDefault<scalar>("theta", 1);
    if
    (
        iterations_ < 1
     || !(tolerance_ > 0) || !(tolerance_ < 1)
     || !(projectionTolerance_ > 0) || !(projectionTolerance_ < 1)
     || !(correctionTolerance_ > 0) || !(correctionTolerance_ < 1)
    )
    {
        FatalIOErrorInFunction(d)
            << "fvOption " << owner_ << ": implicitForce { iterations "
            << iterations_ << "; tolerance " << tolerance_
            << "; projectionTolerance " << projectionTolerance_
            << "; correctionTolerance " << correctionTolerance_
            << "; }: give at least 1 iteration and tolerances in (0, 1)"
            << " (relative: of the nodes' velocity change, of the map's"
            << " Poisson solves and of the correction's)"
            << exit(FatalIOError);
    }
    if (!(theta_ >= 0.5) || !(theta_ <= 1))
    {
        FatalIOErrorInFunction(d)
            << "fvOption " << owner_ << ": implicitForce { theta " << theta_
            << "; }: give theta in [0.5, 1] (the force of x^n + theta dt"
            << " v^{n+1}: below 0.5 the stiff modes grow)"
            << exit(FatalIOError);
    }
    const word tethers(d.getOrDefault<word>("tethers", "implicit"));
    if (tethers != "explicit" && tethers != "implicit")
    {
        FatalIOErrorInFunction(d)
            << "fvOption " << owner_ << ": implicitForce { tethers "
            << tethers << "; }: give explicit (the feedback of"
            << " tetherRelaxation and tetherStiffness) or implicit (in the"
            << " solve)" << exit(FatalIOError);
    }
    implicitTethers_ = (tethers == "implicit");
    tetherDampingTime_ = d.getOrDefault<scalar>("tetherDampingTime", 2e-5);
    tetherSpringTime_ =
        d.getOrDefault<scalar>("tetherSpringTime", Foam::sqrt(1e-9));
    tetherMaxGain_ = d.getOrDefault<scalar>("tetherMaxGain", 20);
    if
    (
        !(tetherDampingTime_ > 0) || !(tetherSpringTime_ > 0)
     || !(tetherMaxGain_ > 0)
    )
    {
        FatalIOErrorInFunction(d)
            << "fvOption " << owner_ << ": implicitForce { tetherDampingTime "
            << tetherDampingTime_ << "; tetherSpringTime " << tetherSpringTime_
            << "; tetherMaxGain " << tetherMaxGain_ << "; }: give the"
            << " tethers' time scales in seconds and their largest gain per"
            << " step, all positive (their force -(v/t_v + xi/t_x^2)/D)"
            << exit(FatalIOError);
    }
    const word& scheme = map_.ddtScheme();
    if (scheme != "Euler" && scheme != "backward")
    {
        FatalIOErrorInFunction(coeffs)
            << "fvOption " << owner_ << ": implicitForce takes the"
            << " fluid's response over the step under the Euler and"
            << " backward time schemes, not ddt(U) " << scheme
            << " (system/fvSchemes): use one of them, or remove"
            << " implicitForce" << exit(FatalIOError);
    }
}


Foam::scalar Foam::carriedImplicitForce::tetherRates
(
    const scalar dt,
    scalar& dampingRate,
    scalar& springRate
) const
{
    dampingRate = 1/tetherDampingTime_;
    springRate = 1/sqr(tetherSpringTime_);
    const scalar gain = response(dt)*(dampingRate + dt*springRate);
    const scalar scale = gain > tetherMaxGain_ ? tetherMaxGain_/gain : 1;
    dampingRate *= scale;
    springRate *= scale;
    return scale;
}


Foam::tmp<Foam::vectorField> Foam::carriedImplicitForce::force
(
    const vectorField& x,
    const vectorField& free,
    const scalar lookAhead,
    const scalarField& tetherDamping,
    const carriedCouplingMap::stiffnessMap& stiffness
) const
{
    auto tF = tmp<vectorField>::New();
    vectorField& F = tF.ref();
    string why;
    if (!stiffness(cmptMultiply(x, free), F, why))
    {
        FatalErrorInFunction
            << "fvOption " << owner_ << ": the leaflets' stiffness for the"
            << " implicit force: " << why.c_str() << exit(FatalError);
    }
    F *= lookAhead;
    forAll(F, i)
    {
        if (tetherDamping[i] > 0)
        {
            F[i] -= tetherDamping[i]*x[i];
        }
    }
    return tF;
}


Foam::label Foam::carriedImplicitForce::solve
(
    const vectorField& r,
    const vectorField& free,
    const scalar a,
    const scalar lookAhead,
    const scalarField& tetherDamping,
    const carriedCouplingMap::stiffnessMap& stiffness,
    const carriedCouplingMap::forceFluxMap& forceFlux,
    const carriedCouplingMap::velocityMap& velocity,
    vectorField& x
)
{
    // the unknowns' components: the free ones and the tethers'
    vectorField mask(free);
    forAll(mask, i)
    {
        if (tetherDamping[i] > 0)
        {
            mask[i] = vector::one;
        }
    }
    const label maxIter = iterations_;
    const scalar tol = tolerance_;
    scalar& residual = lastResidual_;
    x.setSize(r.size());
    x = Zero;
    const scalar rNorm = Foam::sqrt(sum(magSqr(cmptMultiply(r, mask))));
    residual = 0;
    if (!(rNorm > 0))
    {
        lastIterations_ = 0;
        return 0;
    }
    // GMRES with twice-orthogonalised Arnoldi; the small least-squares
    // problem min |rNorm e_1 - H y| solved afresh each iteration (QR).
    // The solid is the same on every rank: no reductions
    PtrList<vectorField> Q(maxIter + 1);
    Q.set(0, new vectorField(cmptMultiply(r, mask)/rNorm));
    Eigen::MatrixXd H = Eigen::MatrixXd::Zero(maxIter + 1, maxIter);
    Eigen::VectorXd y;
    label k = 0;
    residual = 1;
    for (; k < maxIter && residual > tol; ++k)
    {
        // Q_k - a D force(Q_k) (without tethers Q_k + a L D K_T Q_k)
        clockTime clock;
        const vectorField Fk
        (
            force(Q[k], free, lookAhead, tetherDamping, stiffness)
        );
        map_.countStiffness(clock.timeIncrement());
        vectorField v
        (
            cmptMultiply
            (
                Q[k]
              - a*map_.respond(Fk, forceFlux, velocity, projectionTolerance_),
                mask
            )
        );
        H(k + 1, k) = carriedCouplingMap::orthogonalise(Q, k, v, H);
        Eigen::VectorXd g = Eigen::VectorXd::Zero(k + 2);
        g(0) = rNorm;
        const Eigen::MatrixXd Hk = H.topLeftCorner(k + 2, k + 1);
        y = Hk.colPivHouseholderQr().solve(g);
        residual = (g - Hk*y).norm()/rNorm;
        // the Krylov space holds the solution (a happy breakdown)
        if (!(H(k + 1, k) > 1e-12*H.col(k).norm()))
        {
            ++k;
            break;
        }
        Q.set(k + 1, new vectorField(v/H(k + 1, k)));
    }
    for (label i = 0; i < y.size(); ++i)
    {
        x += y(i)*Q[i];
    }
    lastIterations_ = k;
    return k;
}


// ************************************************************************* //
