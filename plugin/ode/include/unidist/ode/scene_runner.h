// The ODE scene runner: a unidist::Scene (adapters/include/unidist/adapters/scene.h) simulated in an ODE world
// where every body is a unidist geom (primitives included: this runner exercises the plugin), except a static
// half-space, which becomes ODE's own non-placeable dCreatePlane.
//
// World set-up:
//  * dynamic bodies: mass from unidist::massProperties + principalInertia, the ODE body at the centre of mass
//    with principal axes (ODE wants a diagonalisable inertia about the body origin), the geom offset from the
//    body so that the geom frame is the model frame; initial velocities are those of the centre of mass;
//  * static bodies: a geom without a body; a half-space model must be static;
//  * contacts: up to 8 per pair, friction mu = sqrt(f1·f2) with ODE's friction pyramid (dContactApprox1),
//    restitution = max(r1, r2) above a small bounce velocity, no contact softness beyond the world's CFM so that
//    rest heights are exact up to the surface layer;
//  * surface layer: 1e-4 × the smallest dynamic body's bounding-box diagonal (resting bodies sink by this much);
//  * stepper: dWorldStep (the exact LCP solve; stacks of mixed bodies stay standing, docs/ode.md compares it
//    with dWorldQuickStep).
// The runner calls dInitODE2 / dCloseODE around the run (ODE counts nested initialisations; the runner serialises
// its own calls, so runs in several threads at once are safe, one world each) and unidist::ode::init(). Result: model-frame poses, centre-of-mass velocities, the deepest contact seen, the
// contact count of the last step and wall-clock steps per second (collision + solver).
#pragma once

#include "unidist/adapters/scene.h"

namespace unidist::ode {

/// Runs the scene; throws InputError for a dynamic half-space, a dynamic body without positive mass, or a
/// model without mass properties.
SimResult runScene(const Scene& scene, const SimOptions& options = {});

}  // namespace unidist::ode
