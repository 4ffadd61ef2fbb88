/*---------------------------------------------------------------------------*\
  isfem: immersed smoothed finite element method for FSI (OpenFOAM side)
-------------------------------------------------------------------------------
Application
    isfemFoam

Description
    Immersed smoothed finite element method (IS-FEM) solver for
    fluid-structure interaction of heart valves (Yao et al., Comput Mech
    2012). Fluid: incompressible (laminar, or with OpenFOAM's turbulence
    models), on a fixed mesh, advanced by a CBS-equivalent projection
    (class cbsProjectionFluid, Steps I-III of Sect. 4.1). Momentum
    sources come through fvOptions; the immersed solids among them
    (fv::immersedMethod: the sharp fv::immersedForcing for thick or rigid
    bodies, the carried fv::immersedElasticForce for leaflets thinner than
    a cell) take part in the coupled step of Sect. 4.4 through
    Foam::immersedFsi. One time step:

      1. the step: the fluid's Courant (and diffusion) limit, then the
         immersed solids' (nodes within maxCo of their cell size);
      2. (3.1) the sharp solid advances to t^{n+1} under the force of the
         last step, sub-cycled at its stable step;
      3. (3.2) the FSI pairs and the covered cells;
      4. (3.3) the fluid step, Steps I-III; the immersed methods constrain
         the momentum equation (fvOptions) and answer the projection: the
         flux through the faces they hold, the cells they take out of the
         pressure equation, grad p with the wall pressure, the balanced
         force of the carried leaflets; Steps II-III repeat until every
         windkessel outlet's pressure agrees with the step's flow;
      5. (3.4) the end of the fluid step: the force of the final U and p
         on the sharp solid; the carried solid moves with the fluid and its
         stress becomes the next step's force. With coupling iterations
         (sharp method) 2-5 repeat until the force converges;
      6. the time's output, then the solids' probes, restart state and
         VTU output.

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
        " immersed solids through fvOptions (immersedForcing for thick or"
        " rigid bodies, immersedElasticForce for thin leaflets)."
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
            fluid.solve();          // (3.3) Steps I-III
        } while (!fsi.updateForce());   // (3.4) end of the fluid step

        runTime.write();
        fsi.write();            // solid state (restart) and VTU

        runTime.printExecutionTime(Info);
    }

    Info<< "End\n" << endl;

    return 0;
}


// ************************************************************************* //
