/*---------------------------------------------------------------------------*\
    isfem: immersed smoothed finite element method (tests)
-------------------------------------------------------------------------------
Application
    testValveBeat

Description
    Feeds a valve's time series to valveBeat (src/fsiCoupling/
    functionObjects/valveMetrics/valveBeat.H) as valveMetrics does and
    prints the rows of the beats (the beats.dat format) on stdout.

    The series file, one sample per line in time order ('#' comments):

        f t Q dp pAorta vJet    a step's flow sample (SI)
        v t GOA stress          a row's valve sample (SI)

    A beat is finished when a flow sample passes its end, and the last
    one when the series reaches its end.

Usage
    testValveBeat <series> -period 0.8 -rho 1060 [-openFraction 0.1]
        [-start 0]

\*---------------------------------------------------------------------------*/

#include "argList.H"
#include "IFstream.H"
#include "IStringStream.H"
#include "valveBeat.H"

using namespace Foam;

int main(int argc, char *argv[])
{
    argList::noBanner();
    argList::noParallel();
    argList::noCheckProcessorDirectories();
    argList::addArgument("series");
    argList::addOption("period", "T", "the beat's period [s]");
    argList::addOption("rho", "rho", "the fluid's density [kg/m3]");
    argList::addOption("openFraction", "f", "default 0.1");
    argList::addOption("start", "t", "the first beat's start (default 0)");
    argList args(argc, argv, false, false, false);

    const fileName series(args[1]);
    valveBeat beat
    (
        args.get<scalar>("period"),
        args.get<scalar>("rho"),
        args.getOrDefault<scalar>("openFraction", 0.1),
        args.getOrDefault<scalar>("start", 0)
    );

    IFstream is(series);
    if (!is.good())
    {
        FatalErrorInFunction
            << "cannot read the series " << series << exit(FatalError);
    }

    valveBeat::writeHeader(Info());
    autoPtr<valveBeat::metrics> previous;
    auto finish = [&]()
    {
        if (beat.complete(1e-9*(beat.end() - beat.start())))
        {
            const valveBeat::metrics m = beat.evaluate();
            valveBeat::writeRow(Info(), m, previous.get());
            previous.reset(new valveBeat::metrics(m));
        }
        else
        {
            Info<< "# beat " << beat.beat() + 1 << " incomplete" << nl;
            previous.clear();
        }
        beat.next();
    };

    string line;
    scalar tLast = -GREAT;
    label lineNo = 0;
    while (is.good() && !is.eof())
    {
        is.getLine(line);
        ++lineNo;
        const auto hash = line.find('#');
        if (hash != string::npos)
        {
            line.resize(hash);
        }
        if (line.find_first_not_of(" \t\r") == string::npos)
        {
            continue;
        }
        IStringStream ls(line);
        word kind;
        ls >> kind;
        scalar t;
        ls >> t;
        if (kind == "f")
        {
            scalar Q, dp, pAorta, vJet;
            ls >> Q >> dp >> pAorta >> vJet;
            const scalar tol = 1e-9*(beat.end() - beat.start());
            while (t > beat.end() + tol)
            {
                finish();
            }
            beat.addFlow(t, Q, dp, pAorta, vJet);
        }
        else if (kind == "v")
        {
            scalar GOA, stress;
            ls >> GOA >> stress;
            beat.addValve(t, GOA, stress);
        }
        else
        {
            FatalErrorInFunction
                << series << " line " << lineNo << ": unknown kind '" << kind
                << "' (f or v)" << exit(FatalError);
        }
        tLast = max(tLast, t);
    }
    if (tLast >= beat.end() - 1e-9*(beat.end() - beat.start()))
    {
        finish();
    }

    return 0;
}


// ************************************************************************* //
