// SPDX-License-Identifier: MIT
// Supporting planes (Coorg and Teller; Moeller and Haines, "Occlusion
// Culling Algorithms", section "Shadow Culling"): see family.h.
#include "strategies/coorg_teller_supporting_planes/family.h"

#include <algorithm>
#include <limits>
#include <optional>
#include <vector>

#include "occluders/shadow_occluders.h"
#include "occluders/sources.h"
#include "spatial/hierarchy.h"
#include "strategies/coorg_teller_supporting_planes/supporting_planes.h"

namespace occu::strategies {

namespace {

constexpr std::uint32_t no_occluder = std::numeric_limits<std::uint32_t>::max();

class SupportingPlaneCuller final : public Culler {
public:
    SupportingPlaneCuller(const StrategyContext &context, const Settings &settings)
        : occluders_(context.scene, settings),
          count_(std::size_t(settings.integer("occluders"))), cache_on_(settings.on("plane-cache")),
          last_culler_(context.hierarchy.nodes().size(), no_occluder), slot_(occluders_.id_limit(), -1)
    {
        if (cache_on_)
            table_.resize(slots);
    }

    void begin_frame(const Frame &frame) override
    {
        frame_.emplace(frame);
        eye_ = glm::dvec3(frame.camera.position);
        for (const Active &a : active_)
            slot_[a.occluder.id] = -1;
        active_.clear();
        for (const ShadowOccluder &o : occluders_.choose(frame, count_)) {
            Active a{o, 0u};
            if (o.face < 0) {
                // An aggregate's silhouette, and so its supporting planes,
                // depend on which of its faces the eye sees: the region the
                // eye is in is part of the key.
                const Aabb &box = occluders_.boxes()[o.box];
                const auto front = front_faces(eye_, box, shadow_margin(std::max(magnitude(eye_), magnitude(box))));
                if (!front)
                    continue;
                a.front = *front;
            }
            slot_[o.id] = int(active_.size());
            active_.push_back(a);
        }
    }

    void test(std::vector<NodeTest> &tests) override
    {
        const Frame &f = *frame_;
        for (NodeTest &t : tests) {
            if (!f.occlusion_candidate(t) || active_.empty())
                continue;
            // As shadow: the occluder that culled this node last goes first.
            std::uint32_t &last = last_culler_[t.node];
            const int first = last == no_occluder ? -1 : slot_[last];
            if (first >= 0 && viewer_inside(active_[std::size_t(first)], t)) {
                t.result = Visibility::occluded;
                continue;
            }
            for (int i = 0; i < int(active_.size()); ++i)
                if (i != first && viewer_inside(active_[std::size_t(i)], t)) {
                    t.result = Visibility::occluded;
                    last = active_[std::size_t(i)].occluder.id;
                    break;
                }
        }
    }

    CullerStats stats() const override { return {}; }

private:
    struct Active {
        ShadowOccluder occluder;
        unsigned front;   // an aggregate's front faces (geometry/convex_region.h's front_faces)
    };

    // A pair (occluder id and node, an aggregate's front faces) and its
    // planes: pool_[first .. first + count), with their margin.
    struct Slot {
        std::uint64_t key = 0;
        unsigned front = 0;
        std::uint32_t first = 0, count = 0;
        double margin = 0.0;
        bool used = false;
    };
    // Pairs kept: at most half the slots (40 bytes each, and up to 12
    // planes of 32 bytes in the pool).
    static constexpr std::size_t slots = std::size_t(1) << 17;

    std::optional<ConvexRegion> planes_of(const Active &a, const Aabb &box) const
    {
        const Aabb &occluder = occluders_.boxes()[a.occluder.box];
        if (a.occluder.face < 0)
            return box_supporting_planes(occluder, a.front, box);
        return polygon_supporting_planes(box_face(occluder, a.occluder.face), box);
    }

    // The chapter: "An object is occluded if the viewer is inside all of
    // the supporting planes". The planes of an occluder and a node do not
    // depend on the eye, so they are made at the pair's first test and kept
    // (Coorg and Teller keep them too, and revisit them only when the
    // viewer crosses one); a frame tests only the eye against them.
    bool viewer_inside(const Active &a, const NodeTest &t)
    {
        if (!cache_on_) {
            const auto planes = planes_of(a, t.box);
            return planes && planes->holds(eye_);
        }
        const Slot &s = cached(a, t);
        if (s.count == 0)
            return false;   // no planes: no viewer sees this node hidden by this occluder
        const double margin = std::max(s.margin, shadow_margin(magnitude(eye_)));
        for (std::uint32_t i = s.first; i < s.first + s.count; ++i)
            if (!(pool_[i].distance(eye_) > margin))
                return false;
        return true;
    }

    // The pair's slot in an open-addressing table (linear probing), its
    // planes in pool_: a flat table, because a lookup that misses the
    // processor's caches costs about what making the planes again does.
    const Slot &cached(const Active &a, const NodeTest &t)
    {
        // Half full: start again (the pairs of the frames to come are
        // mostly those of this one, and come back in a frame or two).
        if (cached_ >= slots / 2) {
            std::fill(table_.begin(), table_.end(), Slot{});
            pool_.clear();
            cached_ = 0;
        }
        const std::uint64_t key = std::uint64_t(a.occluder.id) << 32 | t.node;
        std::uint64_t h = (key ^ (std::uint64_t(a.front) << 58)) * 0x9E3779B97F4A7C15ull;
        for (std::size_t i = std::size_t(h >> 40) & (slots - 1);; i = (i + 1) & (slots - 1)) {
            Slot &s = table_[i];
            if (s.used && s.key == key && s.front == a.front)
                return s;
            if (!s.used) {
                s = Slot{key, a.front, std::uint32_t(pool_.size()), 0, 0.0, true};
                if (const auto planes = planes_of(a, t.box)) {
                    s.count = std::uint32_t(planes->count);
                    s.margin = planes->margin;
                    pool_.insert(pool_.end(), planes->planes.begin(), planes->planes.begin() + planes->count);
                }
                ++cached_;
                return s;
            }
        }
    }

    ShadowOccluders occluders_;
    std::size_t count_;
    bool cache_on_;
    std::vector<std::uint32_t> last_culler_;   // per node, the occluder that culled it last
    std::vector<int> slot_;                    // per occluder id, its place in active_ this frame, or -1
    glm::dvec3 eye_{0.0};
    std::vector<Active> active_;
    std::vector<Slot> table_;
    std::vector<HalfSpace> pool_;
    std::size_t cached_ = 0;
    std::optional<Frame> frame_;
};

}  // namespace

StrategyFamily supporting_plane_family()
{
    StrategyFamily f;
    f.name = "planes";
    f.paper = "Coorg and Teller 1997 (Moeller and Haines, shadow culling)";
    f.summary = "the viewer inside every supporting plane of a large skin occluder and a box, planes kept per pair";
    f.traversal.switch_off = true;   // its tests: each node against each occluder's planes (0.9 ms a frame on dense)
    // The cache, and shadow's occluders.
    f.settings = {on_off_setting("plane-cache", true, SettingSpec::Role::choice,
                                 "keep each occluder-node pair's supporting planes across frames; off: make them at "
                                 "every test")};
    f.occluder_sources = {{&shadow_occluder_source()}, {&skin_occluder_source()}};
    f.presets = {
        {"planes-faces", "aggregate=off"},
    };
    // Supporting planes made at every test instead of kept per pair.
    f.test_variants = {StrategyTestVariant("planes:plane-cache=off")};
    f.make = [](const StrategyContext &context, const Settings &settings) -> std::unique_ptr<Culler> {
        return std::make_unique<SupportingPlaneCuller>(context, settings);
    };
    return f;
}

}  // namespace occu::strategies
