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
    through fvOptions; with an immersed solid (fv::immersedForcing) each
    time step is the coupled step of Sect. 4.4, phase by phase
    (Foam::immersedFsi).

\*---------------------------------------------------------------------------*/

#include "fvCFD.H"
#include "cbsProjectionFluid.H"
#include "immersedFsi.H"

// * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * //

int main(int argc, char *argv[])
{
    argList::addNote
    (
        "Immersed smoothed FEM solver for fluid-structure interaction;"
        " incompressible laminar fluid by a CBS-equivalent projection,"
        " immersed solids through fvOptions (immersedForcing)."
    );

    #include "addCheckCaseOptions.H"
    #include "setRootCaseLists.H"
    #include "createTime.H"
    #include "createMesh.H"

    cbsProjectionFluid fluid(mesh);
    immersedFsi fsi(mesh);
    fluid.setInitialDeltaT();

    Info<< "\nStarting time loop\n" << endl;

    // One coupled time step, paper Sect. 4.4 (immersedFsi.H)
    while (runTime.run())
    {
        fluid.adjustDeltaT();
        fsi.adjustDeltaT();

        ++runTime;
        Info<< "Time = " << runTime.timeName() << nl << endl;

        // the coupling iterates the step until the force handed to the
        // solid is the one the fluid gives back (immersedForcing.H)
        do
        {
            fsi.advanceSolid();     // (3.1) solid to t^{n+1}
            fsi.searchPairs();      // (3.2) FSI pairs, covered cells
            fluid.solve();          // (3.3) projection, u = u_s covered
        } while (!fsi.updateForce());   // (3.4) FSI force on the solid

        runTime.write();
        fsi.write();            // solid state (restart) and VTU

        runTime.printExecutionTime(Info);
    }

    Info<< "End\n" << endl;

    return 0;
}


// ************************************************************************* //
