/*---------------------------------------------------------------------------*\
  isfem: immersed smoothed finite element method for FSI (OpenFOAM side)
-------------------------------------------------------------------------------
Application
    isfemFoam

Description
    Immersed smoothed finite element method (IS-FEM) solver for
    fluid-structure interaction of heart valves (Yao et al., Comput Mech
    2012). Fluid: incompressible, laminar, on a fixed mesh, advanced by a
    CBS-equivalent projection (class cbsProjectionFluid, Steps I-III of
    Sect. 4.1). Momentum sources, the immersed coupling among them, come
    through fvOptions.

\*---------------------------------------------------------------------------*/

#include "fvCFD.H"
#include "cbsProjectionFluid.H"

// * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * //

int main(int argc, char *argv[])
{
    argList::addNote
    (
        "Immersed smoothed FEM solver for fluid-structure interaction;"
        " incompressible laminar fluid by a CBS-equivalent projection."
    );

    #include "addCheckCaseOptions.H"
    #include "setRootCaseLists.H"
    #include "createTime.H"
    #include "createMesh.H"

    cbsProjectionFluid fluid(mesh);
    fluid.setInitialDeltaT();

    Info<< "\nStarting time loop\n" << endl;

    while (runTime.run())
    {
        fluid.adjustDeltaT();

        ++runTime;
        Info<< "Time = " << runTime.timeName() << nl << endl;

        fluid.solve();

        runTime.write();
        runTime.printExecutionTime(Info);
    }

    Info<< "End\n" << endl;

    return 0;
}


// ************************************************************************* //
