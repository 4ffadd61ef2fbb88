/*---------------------------------------------------------------------------*\
    isfem: immersed smoothed finite element method (fsiCoupling)
\*---------------------------------------------------------------------------*/

#include "carriedImplicitForce.H"
#include "PtrList.H"

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


Foam::label Foam::carriedImplicitForce::solve
(
    const vectorField& r,
    const scalar s,
    const vectorField& free,
    const carriedCouplingMap::stiffnessMap& stiffness,
    const carriedCouplingMap::forceFluxMap& forceFlux,
    const carriedCouplingMap::velocityMap& velocity,
    vectorField& x
)
{
    const label maxIter = iterations_;
    const scalar tol = tolerance_;
    scalar& residual = lastResidual_;
    x.setSize(r.size());
    x = Zero;
    const scalar rNorm = Foam::sqrt(sum(magSqr(cmptMultiply(r, free))));
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
    Q.set(0, new vectorField(cmptMultiply(r, free)/rNorm));
    Eigen::MatrixXd H = Eigen::MatrixXd::Zero(maxIter + 1, maxIter);
    Eigen::VectorXd y;
    label k = 0;
    residual = 1;
    for (; k < maxIter && residual > tol; ++k)
    {
        vectorField v
        (
            Q[k]
          + s*cmptMultiply
            (
                map_.apply
                (
                    Q[k], stiffness, forceFlux, velocity, projectionTolerance_
                )(),
                free
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
