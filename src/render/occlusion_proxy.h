// SPDX-License-Identifier: MIT
// Drawing a node's proxy for an occlusion test (a pass of the Occlusion
// Unit, an occlusion query): the proxy must pass the depth test wherever
// what it holds would. Content can lie on the box's faces, and far away a
// few centimetres are below both the depth buffer's and float z's
// resolution; so the test uses LEQUAL and a polygon offset of a few depth
// units towards the eye, back faces culled (Bartz et al. 1998, section 3:
// the precondition for meaningful counts), and the box grows by about a
// pixel at its distance, so that snapping and edge rules at the silhouette
// cannot drop a pixel the content covers.
#pragma once

#include <optional>

#include "camera/camera.h"
#include "geometry/aabb.h"
#include "gl/state.h"

namespace occu {

// The depth and polygon state of proxy tests, for the scope's life (the
// caller's state comes back at its end).
class ProxyTestState {
public:
    ProxyTestState();

private:
    gl::AttribScope saved_;
};

// The proxy a test draws for `box`: the box grown by about 1.5 pixels at
// its distance from the eye of `camera` (whose view-projection matrix is
// `view_projection`), in a viewport `viewport_height` pixels high. Empty
// when the grown box holds the eye or reaches in front of the near plane,
// as it does when a pixel spans more than two thirds of the distance (a
// viewport of a few pixels, a field of view near 180 degrees) or the box
// nearly touches the near plane: with back faces culled and the near plane
// clipping, the proxy would then lose the front faces that cover what the
// box holds, and the test would find hidden what may be seen. Callers take
// such a box as visible untested, like a box without a footprint.
std::optional<Aabb> proxy_box(const Aabb &box, const Camera &camera, const glm::mat4 &view_projection,
                              int viewport_height);

// Draws a proxy (from proxy_box) with the state of ProxyTestState.
void draw_proxy_box(const Aabb &proxy);

}  // namespace occu
