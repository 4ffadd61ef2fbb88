/*---------------------------------------------------------------------------*\
    isfem: immersed smoothed finite element method (fsiCoupling)
\*---------------------------------------------------------------------------*/

#include "valveBeat.H"
#include "Ostream.H"
#include "error.H"
#include "SubList.H"

#include <cmath>
#include <limits>

// * * * * * * * * * * * * * * * * Local * * * * * * * * * * * * * * * * * //

namespace
{

//- Pa per mmHg (the project's constant: tutorials/aorticValve/0.orig/p)
const Foam::scalar paPerMmHg = 133.322;

const Foam::scalar notANumber = std::numeric_limits<Foam::scalar>::quiet_NaN();

//- Linear interpolation of (t, f) between samples i and i + 1 at time x
Foam::scalar lerp
(
    const Foam::UList<Foam::scalar>& t,
    const Foam::UList<Foam::scalar>& f,
    const Foam::label i,
    const Foam::scalar x
)
{
    const Foam::scalar dt = t[i + 1] - t[i];
    if (dt <= 0)
    {
        return f[i + 1];
    }
    return f[i] + (f[i + 1] - f[i])*(x - t[i])/dt;
}

//- A value, or nan written as "nan"
void column(Foam::Ostream& os, const Foam::scalar v)
{
    os  << Foam::token::TAB;
    if (std::isfinite(v))
    {
        os  << v;
    }
    else
    {
        os  << "nan";
    }
}

} // End anonymous namespace


// * * * * * * * * * * * * * Private Member Functions  * * * * * * * * * * * //

Foam::scalar Foam::valveBeat::integral
(
    const UList<scalar>& t,
    const UList<scalar>& f,
    const scalar a,
    const scalar b
)
{
    scalar sum = 0;
    for (label i = 0; i + 1 < t.size(); ++i)
    {
        const scalar lo = max(a, t[i]);
        const scalar hi = min(b, t[i + 1]);
        if (hi > lo)
        {
            sum += 0.5*(hi - lo)*(lerp(t, f, i, lo) + lerp(t, f, i, hi));
        }
    }
    return sum;
}


void Foam::valveBeat::interval
(
    const UList<scalar>& t,
    const UList<scalar>& f,
    const label i,
    const scalar level,
    scalar& a,
    scalar& b
)
{
    auto crossing = [&](const label j)
    {
        // level between f[j] and f[j + 1]
        const scalar df = f[j + 1] - f[j];
        return df == 0
            ? t[j]
            : t[j] + (t[j + 1] - t[j])*(level - f[j])/df;
    };

    label j = i;
    while (j > 0 && f[j - 1] > level)
    {
        --j;
    }
    a = j > 0 ? crossing(j - 1) : t[0];

    j = i;
    while (j + 1 < t.size() && f[j + 1] > level)
    {
        ++j;
    }
    b = j + 1 < t.size() ? crossing(j) : t[t.size() - 1];
}


void Foam::valveBeat::reset(const scalar start, const label beat)
{
    start_ = start;
    beat_ = beat;
}


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::valveBeat::valveBeat
(
    const scalar period,
    const scalar rho,
    const scalar openFraction,
    const scalar start
)
:
    period_(period),
    rho_(rho),
    openFraction_(openFraction),
    beat_(0),
    start_(start)
{
    if (!(period > 0) || !(rho > 0) || !(openFraction > 0 && openFraction < 1))
    {
        FatalErrorInFunction
            << "valveBeat: period " << period << " and rho " << rho
            << " must be positive, openFraction " << openFraction
            << " between 0 and 1" << exit(FatalError);
    }
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

bool Foam::valveBeat::complete(const scalar tol) const
{
    return t_.size() > 1 && t_[0] <= start_ + tol && t_.last() >= end() - tol;
}


void Foam::valveBeat::addFlow
(
    const scalar t,
    const scalar Q,
    const scalar dp,
    const scalar pAorta,
    const scalar vJet
)
{
    if (t_.size() && t <= t_.last())
    {
        return;     // a repeated time (a write after an execute)
    }
    t_.append(t);
    Q_.append(Q);
    dp_.append(dp);
    pAorta_.append(pAorta);
    vJet_.append(vJet);
}


void Foam::valveBeat::addValve
(
    const scalar t,
    const scalar GOA,
    const scalar stress
)
{
    if (tRow_.size() && t <= tRow_.last())
    {
        return;
    }
    tRow_.append(t);
    GOA_.append(GOA);
    stress_.append(stress);
}


Foam::valveBeat::metrics Foam::valveBeat::evaluate() const
{
    if (t_.size() < 2)
    {
        FatalErrorInFunction
            << "valveBeat: beat " << beat_ + 1 << " from t = " << start_
            << " has " << t_.size() << " flow samples; at least two needed"
            << exit(FatalError);
    }
    const scalar t0 = start_;
    const scalar t1 = end();

    metrics m;
    m.beat = beat_ + 1;
    m.start = t0;

    // the forward flow period around the beat's largest flow
    label iMax = -1;
    forAll(t_, i)
    {
        if (t_[i] >= t0 && t_[i] <= t1 && (iMax < 0 || Q_[i] > Q_[iMax]))
        {
            iMax = i;
        }
    }
    const scalar total = integral(t_, Q_, t0, t1);
    m.strokeVolume = total;
    m.cardiacOutput = total/period_;

    scalar tfs = notANumber;
    scalar tfe = notANumber;
    if (iMax >= 0 && Q_[iMax] > 0)
    {
        interval(t_, Q_, iMax, 0, tfs, tfe);
        tfs = max(tfs, t0);
        tfe = min(tfe, t1);
    }

    // the valve open around the largest GOA
    scalar tOpen = notANumber;
    scalar tClose = notANumber;
    m.maxGOA = notANumber;
    m.peakStress = notANumber;
    {
        label jMax = -1;
        scalar gMin = GREAT;
        forAll(tRow_, j)
        {
            if (tRow_[j] >= t0 && tRow_[j] <= t1)
            {
                if (jMax < 0 || GOA_[j] > GOA_[jMax])
                {
                    jMax = j;
                }
                gMin = min(gMin, GOA_[j]);
                m.peakStress =
                    std::isfinite(m.peakStress)
                  ? max(m.peakStress, stress_[j])
                  : stress_[j];
            }
        }
        if (jMax >= 0)
        {
            m.maxGOA = GOA_[jMax];
            if (GOA_[jMax] > gMin)
            {
                interval
                (
                    tRow_,
                    GOA_,
                    jMax,
                    gMin + openFraction_*(GOA_[jMax] - gMin),
                    tOpen,
                    tClose
                );
                tOpen = max(tOpen, t0);
                tClose = min(tClose, t1);
            }
        }
    }
    m.openingTime = tOpen - t0;
    m.closingTime = tClose - t0;

    if (std::isfinite(tfs))
    {
        m.forwardFlowTime = tfe - tfs;
        m.forwardVolume = integral(t_, Q_, tfs, tfe);
        // the closing volume until closure (none if closed before the
        // flow reverses, or closure unknown)
        const scalar tReg =
            std::isfinite(tClose) ? max(tfe, tClose) : tfe;
        m.closingVolume = -integral(t_, Q_, tfe, tReg);
        m.leakageVolume = -(total - integral(t_, Q_, tfs, tReg));
        m.regurgitantFraction =
            (m.closingVolume + m.leakageVolume)/m.forwardVolume;

        // pressure difference and flow over the forward flow period
        const scalar T = tfe - tfs;
        m.meanGradient = integral(t_, dp_, tfs, tfe)/T;
        List<scalar> Q2(Q_.size());
        forAll(Q_, i)
        {
            Q2[i] = sqr(Q_[i]);
        }
        m.Qrms = std::sqrt(integral(t_, Q2, tfs, tfe)/T);
        m.peakGradient = -GREAT;
        m.peakJetVelocity = -GREAT;
        forAll(t_, i)
        {
            if (t_[i] >= tfs && t_[i] <= tfe)
            {
                m.peakGradient = max(m.peakGradient, dp_[i]);
                m.peakJetVelocity = max(m.peakJetVelocity, vJet_[i]);
            }
        }
        // ISO 5840-3: EOA [cm2] = Q_rms [ml/s]/(51.6 sqrt(dp [mmHg]/rho
        // [g/cm3]))
        const scalar dpMmHg = m.meanGradient/paPerMmHg;
        m.EOA =
            dpMmHg > 0
          ? 1e-4*(m.Qrms*1e6)/(51.6*std::sqrt(dpMmHg/(rho_*1e-3)))
          : notANumber;
    }
    else
    {
        m.forwardFlowTime = 0;
        m.forwardVolume = 0;
        m.closingVolume = 0;
        m.leakageVolume = -total;
        m.regurgitantFraction = notANumber;
        m.meanGradient = notANumber;
        m.Qrms = notANumber;
        m.peakGradient = notANumber;
        m.peakJetVelocity = notANumber;
        m.EOA = notANumber;
    }

    // the aortic pressure over the beat
    m.aorticMax = -GREAT;
    m.aorticMin = GREAT;
    forAll(t_, i)
    {
        if (t_[i] >= t0 && t_[i] <= t1)
        {
            m.aorticMax = max(m.aorticMax, pAorta_[i]);
            m.aorticMin = min(m.aorticMin, pAorta_[i]);
        }
    }
    m.aorticMean = integral(t_, pAorta_, t0, t1)/period_;

    return m;
}


void Foam::valveBeat::next()
{
    const scalar t1 = end();
    // keep the samples from the last one at or before the new start
    auto keep = [t1](DynamicList<scalar>& t, List<DynamicList<scalar>*> fs)
    {
        label k = 0;
        forAll(t, i)
        {
            if (t[i] <= t1)
            {
                k = i;
            }
        }
        DynamicList<scalar> tNew(SubList<scalar>(t, t.size() - k, k));
        t.transfer(tNew);
        for (DynamicList<scalar>* f : fs)
        {
            DynamicList<scalar> fNew(SubList<scalar>(*f, f->size() - k, k));
            f->transfer(fNew);
        }
    };
    if (t_.size())
    {
        keep(t_, {&Q_, &dp_, &pAorta_, &vJet_});
    }
    if (tRow_.size())
    {
        keep(tRow_, {&GOA_, &stress_});
    }
    reset(t1, beat_ + 1);
}


void Foam::valveBeat::restartAt(const scalar t, const scalar origin)
{
    const label k = label(std::floor((t - origin)/period_ + 1e-9));
    reset(origin + k*period_, k);
    t_.clear();
    Q_.clear();
    dp_.clear();
    pAorta_.clear();
    vJet_.clear();
    tRow_.clear();
    GOA_.clear();
    stress_.clear();
}


void Foam::valveBeat::writeHeader(Ostream& os)
{
    os  << "# beat\tstart[s]\tSV[ml]\tCO[L/min]\tV_forward[ml]"
        << "\tV_closing[ml]\tV_leakage[ml]\tRF[%]\tdp_mean[mmHg]"
        << "\tdp_peak[mmHg]\tQ_rms[ml/s]\tEOA[cm2]\tGOA_max[mm2]"
        << "\tt_open[ms]\tt_close[ms]\tforwardFlow[ms]\tv_jet_peak[m/s]"
        << "\tstress_peak[kPa]\tp_aorta_max[mmHg]\tp_aorta_min[mmHg]"
        << "\tp_aorta_mean[mmHg]\tdSV[%]\tdp_aorta_mean[%]" << nl;
}


void Foam::valveBeat::writeRow
(
    Ostream& os,
    const metrics& m,
    const metrics* previous
)
{
    const scalar ml = 1e6;
    os  << m.beat;
    column(os, m.start);
    column(os, m.strokeVolume*ml);
    column(os, m.cardiacOutput*1e3*60);
    column(os, m.forwardVolume*ml);
    column(os, m.closingVolume*ml);
    column(os, m.leakageVolume*ml);
    column(os, m.regurgitantFraction*100);
    column(os, m.meanGradient/paPerMmHg);
    column(os, m.peakGradient/paPerMmHg);
    column(os, m.Qrms*ml);
    column(os, m.EOA*1e4);
    column(os, m.maxGOA*1e6);
    column(os, m.openingTime*1e3);
    column(os, m.closingTime*1e3);
    column(os, m.forwardFlowTime*1e3);
    column(os, m.peakJetVelocity);
    column(os, m.peakStress*1e-3);
    column(os, m.aorticMax/paPerMmHg);
    column(os, m.aorticMin/paPerMmHg);
    column(os, m.aorticMean/paPerMmHg);
    if (previous)
    {
        column(os, 100*(m.strokeVolume/previous->strokeVolume - 1));
        column(os, 100*(m.aorticMean/previous->aorticMean - 1));
    }
    else
    {
        column(os, notANumber);
        column(os, notANumber);
    }
    os  << nl;
}


// ************************************************************************* //
