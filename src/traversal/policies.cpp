#include "traversal/policies.h"

#include <algorithm>

namespace occu {

void VisibleNodeList::begin_frame(std::size_t nodes)
{
    last_.resize(nodes, 0);
    now_.assign(nodes, 0);
}

void VisibleNodeList::end_frame()
{
    last_.swap(now_);
    ++frame_;
}

bool SwitchOff::begin_frame()
{
    probe_ = off_ && frames_to_probe_ <= 1;
    if (off_ && !probe_)
        --frames_to_probe_;
    return !off_ || probe_;
}

void SwitchOff::end_frame(bool tested, double triangles_drawn, double triangles_occluded)
{
    if (!tested)
        return;
    const bool was_off = off_;
    off_ = triangles_occluded < settings_.min_gain * triangles_drawn;
    if (!off_)
        return;
    // Switching off waits the base period; a probe that finds occlusion
    // still not worth it waits twice as long as before.
    const std::uint32_t base = std::max<std::uint32_t>(1, settings_.probe_period);
    wait_ = was_off ? std::min(std::max(base, settings_.max_probe_period), 2 * std::max(base, wait_)) : base;
    frames_to_probe_ = wait_;
}

}  // namespace occu
