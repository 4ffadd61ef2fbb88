/*---------------------------------------------------------------------------*\
    isfem: immersed smoothed finite element method (fsiCoupling)
\*---------------------------------------------------------------------------*/

#include "IQNILS.H"
#include "Time.H"
#include "scalarMatrices.H"
#include "OFstream.H"
#include "IFstream.H"
#include "OSspecific.H"
#include "addToRunTimeSelectionTable.H"

// * * * * * * * * * * * * * * Static Data Members * * * * * * * * * * * * * //

namespace Foam
{
namespace couplingSchemes
{
    defineTypeNameAndDebug(IQNILS, 0);
    addToRunTimeSelectionTable(couplingScheme, IQNILS, dictionary);
}
}


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::couplingSchemes::IQNILS::IQNILS
(
    const dictionary& dict,
    const string& owner,
    const Time& time
)
:
    couplingScheme(dict, owner, time),
    relaxation_(0.5),
    reuse_(4),
    previousResidual_(),
    previousOutput_(),
    Vcols_(),
    Wcols_(),
    stepCols_()
{
    IQNILS::read(dict);
}


// * * * * * * * * * * * * * Private Member Functions  * * * * * * * * * * * //

void Foam::couplingSchemes::IQNILS::dropOldColumns()
{
    const label oldest = time_.timeIndex() - reuse_;
    label first = 0;
    while (first < stepCols_.size() && stepCols_[first] < oldest)
    {
        ++first;
    }
    if (first > 0)
    {
        PtrList<vectorField> V(Vcols_.size() - first);
        PtrList<vectorField> W(Wcols_.size() - first);
        DynamicList<label> st(stepCols_.size() - first);
        for (label j = first; j < Vcols_.size(); ++j)
        {
            V.set(j - first, Vcols_.set(j, nullptr));
            W.set(j - first, Wcols_.set(j, nullptr));
            st.append(stepCols_[j]);
        }
        Vcols_.transfer(V);
        Wcols_.transfer(W);
        stepCols_.transfer(st);
    }
}


void Foam::couplingSchemes::IQNILS::appendColumn
(
    const vectorField& r,
    const vectorField& F
)
{
    if (iteration_ > 0)
    {
        Vcols_.append(new vectorField(r - previousResidual_));
        Wcols_.append(new vectorField(F - previousOutput_));
        stepCols_.append(time_.timeIndex());
    }
    previousResidual_ = r;
    previousOutput_ = F;
    dropOldColumns();
}


void Foam::couplingSchemes::IQNILS::quasiNewton
(
    const vectorField& r,
    const vectorField& free,
    vectorField& guess,
    const scalar omega
) const
{
    const label m = Vcols_.size();
    if (m == 0)
    {
        guess += omega*r;
        return;
    }

    // normal equations of the least-squares problem, newest columns first;
    // a column (nearly) dependent on the newer ones is left out (the
    // filtering of Haelterman et al. 2016, by its Gram-Schmidt remainder)
    List<label> use;
    List<vectorField> Q;
    for (label j = m - 1; j >= 0; --j)
    {
        vectorField q(Vcols_[j]);
        const scalar norm0 = Foam::sqrt(sum(magSqr(q)));
        for (const vectorField& qi : Q)
        {
            q -= (sum(qi & q))*qi;
        }
        const scalar norm = Foam::sqrt(sum(magSqr(q)));
        if (norm > 1e-8*norm0 && norm0 > VSMALL)
        {
            Q.append(vectorField(q/norm));
            use.append(j);
        }
    }
    // alpha from the QR factors: V_use = Q R, R alpha = -Q^T r
    const label k = use.size();
    scalarSquareMatrix R(k, Zero);
    scalarField rhs(k, Zero);
    for (label a = 0; a < k; ++a)
    {
        rhs[a] = -sum(Q[a] & r);
        for (label b = a; b < k; ++b)
        {
            R(a, b) = sum(Q[a] & Vcols_[use[b]]);
        }
    }
    scalarField alpha(k, Zero);
    for (label a = k - 1; a >= 0; --a)
    {
        scalar v = rhs[a];
        for (label b = a + 1; b < k; ++b)
        {
            v -= R(a, b)*alpha[b];
        }
        alpha[a] = v/R(a, a);
    }
    // x_{k+1} = x_k + omega (r + V alpha) + (W - V) alpha: Eq. 14's
    // xt_k + W alpha = x_k + (r + V alpha) + (W - V) alpha with the part
    // of r the columns do not model, r + V alpha, relaxed by
    // couplingRelaxation as the first iteration's whole r. Taken whole
    // (omega = 1), that part moved the flag's modes whose added mass
    // exceeds its own by a factor above 1 (the fluid's answer to them is
    // large and opposite): the residual of the second iteration often
    // grew (Turek-Hron FSI1 near its steady state, 3.08 iterations per
    // step against 2.5-2.7 relaxed by 0.1-0.5; FSI2 at 1.47 s: 0.09
    // updated to an inverted element).
    vectorField remainder(r);
    for (label a = 0; a < k; ++a)
    {
        remainder += alpha[a]*Vcols_[use[a]];
    }
    guess = cmptMultiply(free, guess) + omega*remainder;
    for (label a = 0; a < k; ++a)
    {
        guess += alpha[a]*(Wcols_[use[a]] - Vcols_[use[a]]);
    }
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

void Foam::couplingSchemes::IQNILS::read(const dictionary& dict)
{
    couplingScheme::read(dict);
    relaxation_ = dict.getOrDefault<scalar>("couplingRelaxation", 0.5);
    reuse_ = dict.getOrDefault<label>("couplingReuse", 4);
    if (maxIterations_ < 2 || relaxation_ <= 0 || reuse_ < 0)
    {
        FatalIOErrorInFunction(dict)
            << owner_.c_str() << ": couplingScheme IQNILS needs couplingIterations"
            << " above 1 (" << maxIterations_ << "), a positive"
            << " couplingRelaxation (" << relaxation_ << ") and a"
            << " couplingReuse not negative (" << reuse_ << ")"
            << exit(FatalIOError);
    }
}


bool Foam::couplingSchemes::IQNILS::update
(
    const vectorField& output,
    const vectorField& free,
    vectorField& guess
)
{
    // Residual of the fixed point G = F(G) (the force handed to the solid
    // against the one the fluid gave back), over the replicated solid and
    // the components its constraints leave free
    const vectorField F(cmptMultiply(free, output));
    const vectorField r(F - cmptMultiply(free, guess));
    const scalar magF = Foam::sqrt(sum(magSqr(F)));
    residual_ = Foam::sqrt(sum(magSqr(r)))/max(magF, VSMALL);
    Info<< owner_.c_str() << ": coupling iteration " << iteration_ + 1
        << ", force residual " << residual_ << endl;
    const bool converged = residual_ < tolerance_;
    if (converged || iteration_ + 1 >= maxIterations_)
    {
        if (!converged)
        {
            WarningInFunction
                << "The coupling did not converge in " << maxIterations_
                << " iterations at t = " << time_.value()
                << " (force residual " << residual_ << ", tolerance "
                << tolerance_ << "): the step is taken as it is and the"
                << " quasi-Newton columns are dropped" << endl;
            // The columns of a step that stalled model its noise, not the
            // map: kept, they threw the next step's first update far off.
            // The next step starts with a relaxation, as the first one.
            dropHistory();
        }
        else
        {
            // the last pass's differences model the map too (preCICE's
            // BaseQNAcceleration::iterationsConverged): without them a
            // step of two passes would leave no column
            appendColumn(r, F);
            // the next step's first force: the accepted one corrected by
            // the columns, x_k + (W - V) alpha, the quasi-Newton update
            // without the relaxed part the columns do not model. The
            // fluid's force F(x_k) would be farther from this step's
            // fixed point where the flag's added mass exceeds its own
            // (F - x* = J (x_k - x*), |J| above 1)
            quasiNewton(r, free, guess, 0);
        }
        return true;
    }

    appendColumn(r, F);
    quasiNewton(r, free, guess, relaxation_);
    return false;
}


Foam::tmp<Foam::vectorField>
Foam::couplingSchemes::IQNILS::lastIterate() const
{
    return tmp<vectorField>::New(previousOutput_ - previousResidual_);
}


void Foam::couplingSchemes::IQNILS::dropHistory()
{
    Vcols_.clear();
    Wcols_.clear();
    stepCols_.clear();
}


void Foam::couplingSchemes::IQNILS::writeState(const fileName& dir) const
{
    // every rank its own copy, as the solid's state
    OFstream os(dir/"couplingColumns");
    os.precision(17);
    os  << labelList(stepCols_) << nl;
    forAll(Vcols_, j)
    {
        os  << Vcols_[j] << nl << Wcols_[j] << nl;
    }
}


void Foam::couplingSchemes::IQNILS::readState
(
    const fileName& dir,
    const label nPoints
)
{
    const fileName file(dir/"couplingColumns");
    if (!isFile(file))
    {
        return;
    }
    IFstream is(file);
    const labelList steps(is);
    Vcols_.setSize(steps.size());
    Wcols_.setSize(steps.size());
    forAll(steps, j)
    {
        Vcols_.set(j, new vectorField(is));
        Wcols_.set(j, new vectorField(is));
        if (Vcols_[j].size() != nPoints || Wcols_[j].size() != nPoints)
        {
            FatalIOErrorInFunction(is)
                << file << " has columns of " << Vcols_[j].size() << " and "
                << Wcols_[j].size() << " values for " << nPoints
                << " solid nodes: it belongs to another solid mesh. Remove"
                << " it (the coupling iterations then start without the"
                << " last steps' columns) or restart from a time written"
                << " with this mesh" << exit(FatalIOError);
        }
    }
    stepCols_ = steps;
    Info<< owner_.c_str() << ": " << steps.size()
        << " coupling-iteration columns read from " << file << endl;
}


// ************************************************************************* //
