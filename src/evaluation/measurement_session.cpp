// SPDX-License-Identifier: MIT
#include "evaluation/measurement_session.h"

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <stdexcept>
#include <utility>

#include "cli/progress.h"
#include "gl/gl_headers.h"
#include "gl/offscreen_context.h"
#include "gl/state.h"

namespace occu {

namespace {

std::uint64_t minor_page_faults()
{
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return std::uint64_t(usage.ru_minflt);
}

// splitmix64: a fixed sequence for a seed, the same on every platform
// (std::shuffle's is the library's).
std::uint64_t next_random(std::uint64_t &state)
{
    std::uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}

}  // namespace

TraversalPolicies::TraversalPolicies(const StrategyFamily &family, bool coherence_on, double min_gain)
{
    if (family.traversal.coherence && coherence_on)
        coherence.emplace();
    if (family.traversal.switch_off && min_gain > 0.0) {
        SwitchOff::Settings s;
        s.min_gain = min_gain * family.traversal.switch_off_share;
        switch_off.emplace(s);
    }
}

TraversalOptions TraversalPolicies::options(std::size_t batch)
{
    TraversalOptions t;
    t.batch = batch;
    if (coherence)
        t.policies.push_back(&*coherence);
    if (switch_off)
        t.policies.push_back(&*switch_off);
    return t;
}

double Measured::mean_ms() const
{
    double t = 0;
    for (double x : ms)
        t += x;
    return per_frame(t);
}

double Measured::median_ms() const
{
    std::vector<double> sorted = ms;
    std::sort(sorted.begin(), sorted.end());
    return sorted.empty() ? 0.0 : sorted[sorted.size() / 2];
}

double Measured::least_ms() const
{
    return ms.empty() ? 0.0 : *std::min_element(ms.begin(), ms.end());
}

std::optional<double> Measured::efficiency_percent() const
{
    if (!occluded)
        return std::nullopt;
    return 100.0 * double(occluded_culled) / double(occluded);
}

void Measured::pool(const Measured &o)
{
    ms.insert(ms.end(), o.ms.begin(), o.ms.end());
    nodes_tested.insert(nodes_tested.end(), o.nodes_tested.begin(), o.nodes_tested.end());
    triangles += o.triangles;
    passes += o.passes;
    setup_ms += o.setup_ms;
    test_ms += o.test_ms;
    occluded += o.occluded;
    occluded_culled += o.occluded_culled;
    visible_culled += o.visible_culled;
    lost_pixels += o.lost_pixels;
    tied_pixels += o.tied_pixels;
    page_faults += o.page_faults;
}

MeasurementSession::MeasurementSession(const SceneSetup &scene, gl::OffscreenContext &context,
                                       const SessionOptions &options)
    : scene_(scene), gl_(context), options_(options), width_(context.width()), height_(context.height()),
      renderer_(scene_.scene(), scene_.hierarchy(), options.look),
      unculled_strategy_(make_strategy("none", {scene_.scene(), scene_.hierarchy(), renderer_})),
      order_state_(options.order_seed)
{
    control_allocator(options_.allocator);
    if (options_.oracle)
        oracle_.emplace(renderer_, scene_.hierarchy());
}

MeasurementSession::~MeasurementSession() = default;

std::string MeasurementSession::add_unless_refused(const std::string &spec, const std::vector<std::string> &common,
                                                   const std::string &label)
{
    if (std::string why = choose_strategy(spec, common).family->refusal(scene_.scene()); !why.empty())
        return why;
    add(spec, common, label);
    return {};
}

SessionStrategy &MeasurementSession::add(const std::string &spec, const std::vector<std::string> &common,
                                         const std::string &label, std::size_t batch)
{
    const StrategyChoice choice = choose_strategy(spec, common);
    if (choice.family->needs_truth && !oracle_)
        throw std::invalid_argument(spec + " needs the oracle");
    if (const std::string why = choice.family->refusal(scene_.scene()); !why.empty())
        throw std::invalid_argument(why);
    std::vector<std::string> settings = common;
    if (options_.databases)
        for (const std::string &s : options_.databases->settings_for(choice, context(), width_, height_))
            settings.push_back(s);
    return add(make_strategy(spec, context(), settings), label.empty() ? spec : label, batch);
}

SessionStrategy &MeasurementSession::add(Strategy strategy, const std::string &label, std::size_t batch)
{
    const StrategyChoice &choice = strategy.choice;
    if (choice.family->needs_truth && !oracle_)
        throw std::invalid_argument(label + " needs the oracle");
    const bool checks_pixels =
        options_.lost_pixels == SessionOptions::PixelCheck::all ||
        (options_.lost_pixels == SessionOptions::PixelCheck::approximate && !choice.conservative());
    TraversalPolicies policies(*choice.family, options_.coherence, options_.switch_off);
    strategies_.push_back(
        {label, std::move(strategy), std::move(policies), batch ? batch : options_.batch, checks_pixels, {}});
    return strategies_.back();
}

void MeasurementSession::set_frame_state() const
{
    glViewport(0, 0, width_, height_);
    glEnable(GL_DEPTH_TEST);
    glEnable(GL_CULL_FACE);
    glClearColor(options_.clear_colour[0], options_.clear_colour[1], options_.clear_colour[2],
                 options_.clear_colour[3]);
}

// Fisher and Yates' shuffle.
std::vector<std::size_t> MeasurementSession::shuffled_order()
{
    std::vector<std::size_t> order(strategies_.size());
    for (std::size_t i = 0; i < order.size(); ++i)
        order[i] = i;
    for (std::size_t i = order.size(); i > 1; --i)
        std::swap(order[i - 1], order[next_random(order_state_) % i]);
    return order;
}

void MeasurementSession::measure(std::size_t index, const Camera &camera, const Observer &observer)
{
    const Hierarchy &hierarchy = scene_.hierarchy();
    const std::size_t pixels = std::size_t(width_) * std::size_t(height_);
    // The oracle's answer first, untimed (it overwrites the framebuffer;
    // ideal draws from it), then the unculled frame where pixels are checked.
    set_frame_state();
    std::optional<VisibilityTruth> truth;
    if (oracle_)
        truth = oracle_->see(camera, width_, height_);
    const Frame frame(camera, width_, height_, truth ? &*truth : nullptr);
    const bool checks_pixels =
        std::any_of(strategies_.begin(), strategies_.end(), [](const SessionStrategy &s) { return s.checks_pixels; });
    if (checks_pixels) {
        set_frame_state();
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        gl::load_camera(camera);
        TraversalOptions plain;
        plain.batch = options_.batch;
        render_hierarchy(renderer_, hierarchy, *unculled_strategy_.culler, frame, plain);
        glFinish();
        unculled_.assign(gl_.pixels(), gl_.pixels() + 4 * pixels);
    }

    for (std::size_t k : shuffled_order()) {
        SessionStrategy &s = strategies_[k];
        set_frame_state();
        TraversalOptions traversal = s.policies.options(s.batch);
        traversal.clock = options_.culling_clock;
        StrategyFrame out;
        out.index = index;
        out.frame = &frame;
        const std::uint64_t faults = minor_page_faults();
        const auto start = std::chrono::steady_clock::now();
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        gl::load_camera(camera);
        out.stats = render_hierarchy(renderer_, hierarchy, *s.strategy.culler, frame, traversal);
        glFinish();
        out.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        out.page_faults = minor_page_faults() - faults;

        if (truth)
            out.quality = compare_with_truth(*truth, out.stats.drawn);
        if (s.checks_pixels) {
            // A strategy that ordered the frame itself is compared with its
            // own reference; the others first with the common unculled frame.
            // The reference overwrites the frame, which is put back for the observer.
            const bool own_order = orders_frame(*s.strategy.culler) && out.stats.occlusion_tested;
            culled_.assign(gl_.pixels(), gl_.pixels() + 4 * pixels);
            out.loss = count_lost_pixels(renderer_, hierarchy, camera, out.stats.drawn,
                                         own_order ? nullptr : unculled_.data(), gl_.pixels(), pixels);
            out.pixels_checked = true;
            std::memcpy(gl_.pixels_mutable(), culled_.data(), culled_.size());
        }

        Measured &m = s.measured;
        m.ms.push_back(out.ms);
        m.nodes_tested.push_back(out.stats.nodes_tested);
        m.triangles += double(out.stats.triangles);
        m.passes += out.stats.passes;
        m.setup_ms += out.stats.setup_ms;
        m.test_ms += out.stats.test_ms;
        m.occluded += out.quality.occluded;
        m.occluded_culled += out.quality.occluded_culled;
        m.visible_culled += out.quality.visible_culled;
        m.lost_pixels += out.loss.lost;
        m.tied_pixels += out.loss.tied;
        m.page_faults += out.page_faults;
        if (observer)
            observer(s, out);
    }
}

void MeasurementSession::walk(const std::vector<Camera> &cameras, const std::string &what, const Observer &observer)
{
    for (std::size_t f = 0; f < cameras.size(); ++f) {
        measure(f, cameras[f], observer);
        progress(what, long(f + 1), long(cameras.size()));
    }
}

double MeasurementSession::reference_ms(const std::string &family) const
{
    for (const SessionStrategy &s : strategies_)
        if (s.strategy.choice.family->name == family && s.strategy.choice.settings.changed().empty())
            return s.measured.mean_ms();
    return 0.0;
}

std::vector<std::string> MeasurementSession::notes() const
{
    std::vector<std::string> notes;
    for (const SessionStrategy &s : strategies_)
        if (const std::string note = s.strategy.culler->note(); !note.empty())
            notes.push_back(s.label + ": " + note);
    return notes;
}

}  // namespace occu
