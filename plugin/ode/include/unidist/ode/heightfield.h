// ODE heightfields (dHeightfieldClass) as contact partners of unidist geoms.
//
// ODE 0.16's heightfield collider serves only ODE's built-in classes, and a dHeightfieldDataID gives no public
// access to its samples, so the plugin cannot read a heightfield by itself. The user registers the numbers it
// already passed to dGeomHeightfieldDataBuildDouble (same order, without the copy flag: the plugin always keeps
// its own copy):
//
//   dGeomHeightfieldDataBuildDouble(data, heights, 0, width, depth, ws, ds, scale, offset, thickness, 0);
//   unidist::ode::describeHeightfield(data, heights, width, depth, ws, ds, scale, offset, thickness, 0);
//
// From then on every heightfield geom using `data` (dGeomHeightfieldGetHeightfieldData) collides with unidist
// geoms through the plugin's collider, in both dCollide argument orders, with ODE's conventions (geom.h).
// The model is ODE's surface in the heightfield's local frame (Y up, centred: x in [−width/2, width/2], z in
// [−depth/2, depth/2], height = sample·scale + offset, each cell split along the diagonal from sample (i+1, j) to
// (i, j+1) as ODE does), closed by side walls and a bottom at (lowest height − thickness) so that bodies that
// sink in get a penetration depth (unidist/adapters/ode_heightfield.h).
//
// Limits:
//  * a heightfield whose data was never described gives no contacts (as before), and no error;
//  * wrap (ODE's infinite tiling) is rejected with InputError, as are a null pointer, fewer than 2 samples per
//    side, a width / depth / thickness that is not finite and > 0, a non-finite scale or offset, NaN or infinite
//    samples (byte / short / float / callback data: convert the samples to double and describe those);
//  * ODE tells nobody when data is destroyed or rebuilt: call describeHeightfield again after rebuilding the data
//    (or when ODE hands out a destroyed data's address again), and forgetHeightfield when destroying it (frees
//    the model; otherwise it lives until the process ends or forgetHeightfield is called);
//  * registrations survive dCloseODE + dInitODE2 (the data belongs to the user, not to ODE's class tables).
// Thread safety: the registry is guarded by a mutex and holds shared_ptr models, so a describe / forget on one
// thread while another collides is safe (the collision uses the model it looked up).
#pragma once

#include "unidist/mesh.h"

#include <ode/ode.h>

#include <memory>

namespace unidist::ode {

/// Registers (or replaces) the model of `data`; see above for the frame and the validation (InputError).
void describeHeightfield(dHeightfieldDataID data, const double* heights, double width, double depth, int widthSamples,
                         int depthSamples, double scale, double offset, double thickness, int wrap);

/// Drops the registration of `data` (nothing happens when it has none). Its heightfields give no contacts again.
void forgetHeightfield(dHeightfieldDataID data);

/// The registered model of `data` (in the heightfield's local frame), or null.
std::shared_ptr<const TriangleMesh> heightfieldModel(dHeightfieldDataID data);

/// Number of registered heightfield data (for tests).
std::size_t heightfieldCount();

}  // namespace unidist::ode
