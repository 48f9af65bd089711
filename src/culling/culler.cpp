// SPDX-License-Identifier: MIT
#include "culling/culler.h"

namespace occu {

const char *visibility_name(Visibility v)
{
    switch (v) {
    case Visibility::visible: return "visible";
    case Visibility::occluded: return "occluded";
    case Visibility::view_culled: return "view_culled";
    }
    return "?";
}

Frame::Frame(const Camera &camera_, int viewport_width, int viewport_height, const VisibilityTruth *truth_)
    : camera(camera_), view_projection(camera_.view_projection()), frustum(view_projection), width(viewport_width),
      height(viewport_height), truth(truth_)
{
}

std::optional<Footprint> Frame::occlusion_candidate(NodeTest &t) const
{
    t.result = Visibility::visible;
    if (frustum.classify(t.box) == Frustum::Side::outside) {
        t.result = Visibility::view_culled;
        return std::nullopt;
    }
    return footprint(t.box);
}

}  // namespace occu
