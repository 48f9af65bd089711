// SPDX-License-Identifier: MIT
#include "traversal/policies.h"

#include <algorithm>

namespace occu {

FrameTesting VisibleNodeList::begin_frame(const FrameOutlook &frame)
{
    last_.resize(frame.nodes.size(), 0);
    now_.assign(frame.nodes.size(), 0);
    return FrameTesting::full;
}

NodeTesting VisibleNodeList::node_testing(std::uint32_t node, bool leaf, FrameTesting frame) const
{
    (void)leaf;
    const bool assumed = frame == FrameTesting::full && last_[node] && (frame_ + node) % retest_period_ != 0;
    return assumed ? NodeTesting::assumed_visible : NodeTesting::test;
}

void VisibleNodeList::end_frame(const FrameStats &stats)
{
    (void)stats;
    last_.swap(now_);
    ++frame_;
}

FrameTesting SwitchOff::begin_frame(const FrameOutlook &frame)
{
    nodes_ = &frame.nodes;
    hidden_.resize(frame.nodes.size(), 0);
    cut_ = false;
    scheduled_probe_ = off_ && frames_to_probe_ <= 1;
    probe_ = scheduled_probe_ || (off_ && frame.frustum_triangles &&
                                  double(frame.frustum_triangles()) > unjudged_view * double(judged_view_triangles_));
    if (off_ && !scheduled_probe_)
        --frames_to_probe_;
    return !off_ ? FrameTesting::full : probe_ ? FrameTesting::probe : FrameTesting::off;
}

NodeTesting SwitchOff::node_testing(std::uint32_t node, bool leaf, FrameTesting frame) const
{
    (void)frame;
    return probe_ && leaf && !hidden_[node] ? NodeTesting::skipped : NodeTesting::test;
}

void SwitchOff::visible(std::uint32_t node)
{
    if (!testing() || !hidden_[node])
        return;
    // Its children were hidden with it: the leaves among them are worth a
    // probe's tests.
    const HierarchyNode &n = (*nodes_)[node];
    for (std::uint32_t c = 0; c < n.child_count; ++c)
        hidden_[n.first_child + c] = 1;
}

void SwitchOff::occluded(std::uint32_t node)
{
    hidden_[node] = 1;
}

bool SwitchOff::stop_testing(const FrameStats &so_far)
{
    if (!probe_ || so_far.nodes_tested < settings_.probe_nodes)
        return false;
    cut_ = true;
    judged_triangles_ = so_far.triangles;
    judged_occluded_ = so_far.triangles_occluded;
    return true;
}

void SwitchOff::end_frame(const FrameStats &stats)
{
    if (!stats.occlusion_tested)
        return;
    const double triangles_drawn = double(cut_ ? judged_triangles_ : stats.triangles);
    const double triangles_occluded = double(cut_ ? judged_occluded_ : stats.triangles_occluded);
    const bool was_off = off_;
    balance_ = (was_off ? 0.0 : carried * balance_) + triangles_occluded - settings_.min_gain * triangles_drawn;
    off_ = balance_ < 0.0;
    if (!off_)
        return;
    // The view judged: every triangle in the frustum was drawn or lies in
    // an occluded subtree, tested or not.
    const std::uint64_t view = stats.triangles + stats.triangles_occluded;
    judged_view_triangles_ = was_off ? std::max(judged_view_triangles_, view) : view;
    // A probe of a larger view leaves the schedule as it was: it judged
    // that view, not the wait.
    if (was_off && !scheduled_probe_)
        return;
    // Switching off waits the base period; a scheduled probe that finds
    // occlusion still not worth it waits twice as long as before.
    const std::uint32_t base = std::max<std::uint32_t>(1, settings_.probe_period);
    wait_ = was_off ? std::min(std::max(base, settings_.max_probe_period), 2 * std::max(base, wait_)) : base;
    frames_to_probe_ = wait_;
}

}  // namespace occu
