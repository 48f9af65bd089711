#include "culling/culler.h"

#include <optional>
#include <stdexcept>

#include "culling/occlusion_unit_culler.h"
#include "culling/opacity_map_culler.h"

namespace occu {

const char *visibility_name(Visibility v)
{
    switch (v) {
    case Visibility::visible: return "visible";
    case Visibility::occluded: return "occluded";
    case Visibility::view_culled: return "view_culled";
    case Visibility::visible_subtree: return "visible_subtree";
    }
    return "?";
}

namespace {

// Draws everything: the reference every other strategy is compared with.
class NoCulling final : public Culler {
public:
    std::string_view name() const override { return "none"; }
    bool conservative() const override { return true; }
    void begin_frame(const Camera &) override {}
    Visibility test(const Aabb &) override { return Visibility::visible; }
};

// View-frustum culling only (Moeller and Haines: the baseline of the
// occlusion culling comparisons).
class ViewFrustumCulling final : public Culler {
public:
    std::string_view name() const override { return "vfc"; }
    bool conservative() const override { return true; }
    void begin_frame(const Camera &camera) override { frustum_.emplace(camera.view_projection()); }
    Visibility test(const Aabb &box) override
    {
        return frustum_->classify(box) == Frustum::Side::outside ? Visibility::view_culled : Visibility::visible;
    }

private:
    std::optional<Frustum> frustum_;
};

}  // namespace

std::vector<std::string> culler_names()
{
    return {"none", "vfc", "occu-hier", "occu-hier-shared", "om-ps", "om-fh", "mos-om", "pc-ps", "pc-mos"};
}

std::unique_ptr<Culler> make_culler(std::string_view name, const CullerOptions &options)
{
    if (name == "occu-hier")
        return std::make_unique<OcclusionUnitCuller>(options, false);
    if (name == "occu-hier-shared")
        return std::make_unique<OcclusionUnitCuller>(options, true);
    const bool opacity_map = name == "om-ps" || name == "om-fh" || name == "mos-om";
    const bool pixelwise = name == "pc-ps" || name == "pc-mos";
    if (opacity_map || pixelwise) {
        if (!options.hierarchy || !options.renderer)
            throw std::invalid_argument(std::string(name) + " needs the hierarchy and renderer it draws occluders from");
        OpacityMapOptions om;
        om.occluders = options.occluders;
        om.tolerance = options.tolerance;
        om.coverage_ratio = options.coverage_ratio;
        if (options.map_divisor < 1)
            throw std::invalid_argument("map divisor " + std::to_string(options.map_divisor) + " is below 1");
        om.divisor = options.map_divisor;
        om.pixelwise = pixelwise;
        om.criterion = name == "om-fh"                       ? OccluderCriterion::first_hit
                       : name == "mos-om" || name == "pc-mos" ? OccluderCriterion::minimum_occluder_set
                                                              : OccluderCriterion::projected_size;
        if (om.criterion == OccluderCriterion::minimum_occluder_set) {
            if (!options.occluder_database)
                throw std::invalid_argument(std::string(name) +
                                            " needs an occluder database (made by occu-preprocess; --occluder-db FILE)");
            om.database = options.occluder_database;
        }
        return std::make_unique<OpacityMapCuller>(*options.hierarchy, *options.renderer, om);
    }
    if (name == "none")
        return std::make_unique<NoCulling>();
    if (name == "vfc")
        return std::make_unique<ViewFrustumCulling>();
    std::string known;
    for (const std::string &n : culler_names())
        known += (known.empty() ? "" : ", ") + n;
    throw std::invalid_argument("unknown culling strategy '" + std::string(name) + "' (known: " + known + ")");
}

}  // namespace occu
