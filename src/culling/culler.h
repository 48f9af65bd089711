// The one interface every culling strategy implements, so that demos and
// benchmarks select strategies by name (in the manner of Intel's Masked
// Occlusion Culling: clear, render occluders, test boxes).
//
// A frame: begin_frame(camera) clears the strategy's occlusion state; then
// the caller tests boxes (world-space AABBs) with test(), front to back,
// and tells the strategy what it drew with rendered(), which occlusion
// strategies use as occluders. Results:
//   visible      the box may contribute pixels: draw or descend into it;
//   visible_subtree  as visible, and its descendants are not worth testing
//                (the adaptive overlap test): draw them, culling only
//                against the view frustum;
//   occluded     nothing in the box can be seen (conservative strategies)
//                or contributes too little (approximate ones);
//   view_culled  the box lies outside the view frustum.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "camera/camera.h"
#include "geometry/aabb.h"

namespace occu {

enum class Visibility { visible, occluded, view_culled, visible_subtree };

const char *visibility_name(Visibility v);

class Hierarchy;

class Culler {
public:
    virtual ~Culler() = default;
    virtual std::string_view name() const = 0;
    // True when the strategy never culls a box with a visible pixel.
    virtual bool conservative() const = 0;
    virtual void begin_frame(const Camera &camera) = 0;
    virtual Visibility test(const Aabb &box) = 0;
    // Tests several boxes at once (strategies that batch, such as the
    // Occlusion Unit with one tile per box, override it).
    virtual void test_many(const std::vector<Aabb> &boxes, std::vector<Visibility> &results)
    {
        results.resize(boxes.size());
        for (std::size_t i = 0; i < boxes.size(); ++i)
            results[i] = test(boxes[i]);
    }
    // Tests nodes of `hierarchy` whose boxes are `boxes` (the traversal
    // calls this; strategies that can test a leaf by its own geometry
    // override it, the others test the boxes).
    virtual void test_nodes(const Hierarchy &hierarchy, const std::vector<std::uint32_t> &nodes,
                            const std::vector<Aabb> &boxes, std::vector<Visibility> &results)
    {
        (void)hierarchy;
        (void)nodes;
        test_many(boxes, results);
    }
    // The caller drew the contents of `box`.
    virtual void rendered(const Aabb &box) { (void)box; }
    // Occlusion passes (or queries) issued since begin_frame.
    virtual std::uint32_t passes() const { return 0; }
};

class SceneRenderer;
class OccluderDatabase;

// The knobs of the occlusion strategies (occlusion_unit_culler.h,
// opacity_map_culler.h).
struct CullerOptions {
    float adaptive_threshold = 0.0f;   // occu-hier: occluded when NOHC <= t * PHC; 0: exact
    double max_test_area = 0.25;       // occu-hier: boxes covering more of the viewport are not tested
    bool leaf_geometry = false;        // occu-hier: test leaves by their triangles, not their boxes (needs renderer)
    std::size_t occluders = 64;        // om-ps: leaves rendered as occluders
    std::uint32_t tolerance = 0;       // om-*, pc-*: hole pixels the overlap test ignores; 0: exact
    double coverage_ratio = 0.2;       // om-*, pc-*: adaptive overlap test; below it, descendants go untested
    int map_divisor = 4;               // om-*, pc-*: frame pixels per map pixel, each way (512 -> 128)
    const Hierarchy *hierarchy = nullptr;         // om-*, pc-*, mos-om draw occluders from these
    const SceneRenderer *renderer = nullptr;
    const OccluderDatabase *occluder_database = nullptr;   // mos-om, pc-mos
};

// Strategies by name: "none", "vfc", and with a current GL context that
// advertises GL_MESAX_occlusion_unit, "occu-hier" and "occu-hier-shared";
// with a context and options.hierarchy/renderer, "om-ps", "om-fh", "pc-ps",
// and with an occluder database too, "mos-om" and "pc-mos".
// Throws std::invalid_argument naming the unknown strategy and the known ones.
std::unique_ptr<Culler> make_culler(std::string_view name, const CullerOptions &options = {});
std::vector<std::string> culler_names();

}  // namespace occu
