// Runs a scene file's description (unidist/adapters/scene.h) in a btDiscreteDynamicsWorld with the plugin
// registered: every body is a unidist shape (primitives included) except a half-space, which becomes a
// btStaticPlaneShape. A dynamic body's rigid body sits at its centre of mass with principal axes (a compound
// holds the shape at the offset when the model's frame is not that); the reported poses are the models' own.
#pragma once

#include "unidist/adapters/scene.h"

namespace unidist::bullet {

/// Fixed steps of scene.dt (stepSimulation(dt, 1, dt)). Throws InputError for a scene the engine cannot run.
SimResult runScene(const Scene& scene, const SimOptions& options = {});

}  // namespace unidist::bullet
