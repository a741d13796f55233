// A scene's [[preload]] settled before any dynamic solve: the static contact
// problem (preload/static_contact.h) solved by the library's own dogleg, its
// state kept in the scene and the laws anchored at it. app::loadScene does
// it, so every interface (solve, sweep, study, Python) solves on the same
// operating point.
#pragma once

#include "eqhb/scenes/scene.h"

namespace eqhb::app {

// No-op for a scene without preload. Throws InputError naming "preload"
// (with the scene's file) when no contact holds the load.
void settleUnderPreload(Scene& scene);

}  // namespace eqhb::app
