/*---------------------------------------------------------------------------*\
    isfem: immersed smoothed finite element method (fsiCoupling)
\*---------------------------------------------------------------------------*/

#include "rigidSolid.H"
#include "addToRunTimeSelectionTable.H"

// * * * * * * * * * * * * * * Static Data Members * * * * * * * * * * * * * //

namespace Foam
{
namespace immersedSolids
{
    defineTypeNameAndDebug(rigid, 0);
    addToRunTimeSelectionTable(immersedSolid, rigid, dictionary);
}
}


// * * * * * * * * * * * * * Private Member Functions  * * * * * * * * * * * //

void Foam::immersedSolids::rigid::moveTo(const scalar t)
{
    vector d(Zero);
    vector v(Zero);
    if (velocity_.valid())
    {
        d = velocity_->integrate(t0_, t);
        v = velocity_->value(t);
    }
    scalar theta = 0;
    scalar omega = 0;
    if (omega_.valid())
    {
        theta = omega_->integrate(t0_, t);
        omega = omega_->value(t);
    }

    // Rodrigues: R = c I + s [k]x + (1 - c) k k
    const vector& k = axis_;
    const scalar c = Foam::cos(theta);
    const scalar s = Foam::sin(theta);
    const tensor K
    (
        0, -k.z(), k.y(),
        k.z(), 0, -k.x(),
        -k.y(), k.x(), 0
    );
    const tensor R(c*I + s*K + (1 - c)*sqr(k));

    const point centre(origin_ + d);
    forAll(points_, i)
    {
        points_[i] = centre + (R & (points0_[i] - origin_));
        velocities_[i] = v + omega*(k ^ (points_[i] - centre));
    }
    time_ = t;
}


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::immersedSolids::rigid::rigid
(
    const Time& runTime,
    const IOdictionary& dict
)
:
    immersedSolid(runTime, dict),
    t0_(dict.getOrDefault<scalar>("meshTime", 0)),
    storedTime_(runTime.value()),
    velocity_(),
    origin_(Zero),
    axis_(0, 0, 1),
    omega_()
{
    checkKeywords(dict_, wordList({"type", "mesh", "meshTime", "motion"}));

    if (dict_.found("motion"))
    {
        const dictionary& m = dict_.subDict("motion");
        checkKeywords(m, wordList({"velocity", "origin", "axis", "omega"}));

        if (m.found("velocity"))
        {
            velocity_ = Function1<vector>::New("velocity", m);
        }
        if (m.found("omega"))
        {
            omega_ = Function1<scalar>::New("omega", m);
            origin_ = m.get<point>("origin");
            axis_ = m.get<vector>("axis");
            if (mag(axis_) < VSMALL)
            {
                FatalIOErrorInFunction(m)
                    << "Entry 'axis' in " << m.name() << " must not be zero"
                    << exit(FatalIOError);
            }
            axis_ /= mag(axis_);
        }
    }

    moveTo(runTime.value());
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

void Foam::immersedSolids::rigid::advance(const scalar dt)
{
    moveTo(time_ + dt);
}


// ************************************************************************* //
