/*---------------------------------------------------------------------------*\
    isfem: immersed smoothed finite element method (fsiCoupling)
\*---------------------------------------------------------------------------*/

#include "immersedSolidProbes.H"
#include "OSspecific.H"

// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::immersedSolidProbes::immersedSolidProbes(const immersedSolid& solid)
{
    const dictionary& probes =
        solid.dict().subOrEmptyDict("output").subOrEmptyDict("probes");
    names_ = probes.toc();
    positions_.setSize(names_.size());
    element_.setSize(names_.size(), -1);
    weights_.setSize(names_.size());

    const pointField& X = solid.points0();
    const List<solidTet>& tets = solid.elements();
    forAll(names_, i)
    {
        const point p(probes.get<point>(names_[i]));
        positions_[i] = p;
        scalar best = -GREAT;
        forAll(tets, e)
        {
            const solidTet& t = tets[e];
            const vector a(X[t[1]] - X[t[0]]);
            const vector b(X[t[2]] - X[t[0]]);
            const vector c(X[t[3]] - X[t[0]]);
            const scalar det = a & (b ^ c);
            if (mag(det) < VSMALL)
            {
                continue;
            }
            // barycentric coordinates by Cramer's rule
            const vector r(p - X[t[0]]);
            const scalar w1 = (r & (b ^ c))/det;
            const scalar w2 = (a & (r ^ c))/det;
            const scalar w3 = (a & (b ^ r))/det;
            const scalar w0 = 1 - w1 - w2 - w3;
            const scalar m = min(min(w0, w1), min(w2, w3));
            if (m > best)
            {
                best = m;
                element_[i] = e;
                weights_[i] = FixedList<scalar, 4>({w0, w1, w2, w3});
            }
        }
        if (element_[i] < 0 || best < -1e-6)
        {
            FatalIOErrorInFunction(probes)
                << "Probe '" << names_[i] << "' at " << p << " in "
                << probes.name() << " is not inside the solid's reference"
                << " mesh (" << solid.dict().get<fileName>("mesh") << "):"
                << " give a point of the undeformed solid"
                << exit(FatalIOError);
        }
    }
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

Foam::tmp<Foam::vectorField> Foam::immersedSolidProbes::displacements
(
    const immersedSolid& solid
) const
{
    auto tu = tmp<vectorField>::New(size(), Zero);
    vectorField& u = tu.ref();
    const pointField& X = solid.points0();
    const pointField& x = solid.points();
    forAll(u, i)
    {
        const solidTet& t = solid.elements()[element_[i]];
        for (label k = 0; k < 4; ++k)
        {
            u[i] += weights_[i][k]*(x[t[k]] - X[t[k]]);
        }
    }
    return tu;
}


void Foam::immersedSolidProbes::write
(
    const immersedSolid& solid,
    const Time& runTime
)
{
    if (names_.empty() || !Pstream::master())
    {
        return;
    }
    if (!file_.valid())
    {
        const fileName dir
        (
            (Pstream::parRun() ? runTime.path()/".." : runTime.path())
           /"postProcessing"/"solidProbes"
           /runTime.timeName(runTime.startTime().value())
        );
        mkDir(dir);
        file_.reset(new OFstream(dir/"displacement.dat"));
        OFstream& os = file_();
        os  << "# displacement [m] of solid material points (reference"
            << " position):";
        forAll(names_, i)
        {
            os  << ' ' << names_[i] << ' ' << positions_[i];
        }
        os  << nl << "# time";
        for (const word& n : names_)
        {
            os  << ' ' << n << "_x " << n << "_y " << n << "_z";
        }
        os  << endl;
    }
    OFstream& os = file_();
    os.precision(10);
    const vectorField u(displacements(solid));
    os  << runTime.value();
    for (const vector& ui : u)
    {
        os  << ' ' << ui.x() << ' ' << ui.y() << ' ' << ui.z();
    }
    os  << endl;
}


// ************************************************************************* //
