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

// Draws `box` grown by about 1.5 pixels at its distance from the eye of
// `camera`, in a viewport `viewport_height` pixels high.
void draw_proxy_box(const Aabb &box, const Camera &camera, int viewport_height);

}  // namespace occu
