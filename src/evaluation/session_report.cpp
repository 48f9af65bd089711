// SPDX-License-Identifier: MIT
#include "evaluation/session_report.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <stdexcept>

namespace occu {

double culled_percent(std::uint64_t triangles, std::size_t scene_triangles)
{
    return 100.0 * (1.0 - double(triangles) / double(std::max<std::size_t>(1, scene_triangles)));
}

FramesCsv::FramesCsv(const std::string &path, std::string route, std::size_t scene_triangles, Clock clock)
    : path_(path), route_(std::move(route)), scene_triangles_(scene_triangles), clock_(clock), out_(path)
{
    if (!out_)
        throw std::runtime_error("cannot write '" + path + "'");
    out_ << "strategy,route,frame,ms,triangles,leaves_drawn,nodes_tested,passes,view_culled,occluded,"
            "culled_percent,oracle_visible_leaves,oracle_occluded_leaves,occluded_leaves_culled,"
            "visible_leaves_culled,wrong_pixels,setup_ms,test_ms,leaves_conditional,page_faults,culling_clock\n";
}

void FramesCsv::row(const SessionStrategy &strategy, const StrategyFrame &f)
{
    const FrameStats &st = f.stats;
    const VisibilityTruth *truth = f.frame->truth;
    out_ << strategy.label << ',' << route_ << ',' << f.index << ',' << f.ms << ',' << st.triangles << ','
         << st.leaves_drawn << ',' << st.nodes_tested << ',' << st.passes << ',' << st.nodes_view_culled << ','
         << st.nodes_occluded << ',' << culled_percent(st.triangles, scene_triangles_) << ','
         << (truth ? truth->visible.size() : 0) << ',' << f.quality.occluded << ',' << f.quality.occluded_culled << ','
         << f.quality.visible_culled << ',' << f.loss.lost << ',' << st.setup_ms << ',' << st.test_ms << ','
         << st.leaves_conditional << ',' << f.page_faults << ',' << clock_name(clock_) << '\n';
}

void FramesCsv::close()
{
    if (!out_.flush())
        throw std::runtime_error("cannot write '" + path_ + "'");
}

namespace {

std::string ratio(double a, double b)
{
    if (a <= 0 || b <= 0)
        return "-";
    char s[32];
    std::snprintf(s, sizeof(s), "%.2f", a / b);
    return s;
}

}  // namespace

void write_summary(const MeasurementSession &session, const std::string &path, const std::string &route, const std::string &size)
{
    const double vfc_ms = session.reference_ms("vfc"), ideal_ms = session.reference_ms("ideal");
    std::ofstream csv(path);
    csv << "strategy,family,conservative,frames,mean_ms,median_ms,triangles,passes,vs_vfc,x_floor,"
           "efficiency_percent,visible_leaves_culled,wrong_pixels_per_frame,setup_ms,test_ms,route,size,"
           "page_faults_per_frame,culling_clock\n";
    std::printf("\n%-22s %9s %9s %10s %7s %7s %8s %10s %8s %8s %8s %8s\n", "strategy", "mean ms", "median", "triangles",
                "passes", "vs vfc", "x floor", "efficiency", "vis cull", "wrong px", "setup ms", "test ms");
    const bool oracle = session.has_oracle();
    for (const SessionStrategy &s : session.strategies()) {
        const Measured &m = s.measured;
        const double mean = m.mean_ms();
        const bool conservative = s.strategy.choice.conservative();
        const std::string vs_vfc = ratio(vfc_ms, mean), x_floor = ratio(mean, ideal_ms);
        char efficiency[32] = "-", wrong[32] = "-";
        if (const auto e = m.efficiency_percent())
            std::snprintf(efficiency, sizeof(efficiency), "%.1f", *e);
        if (s.checks_pixels)
            std::snprintf(wrong, sizeof(wrong), "%.1f", m.per_frame(double(m.lost_pixels)));
        const std::string visible_culled = oracle ? std::to_string(m.visible_culled) : "-";
        csv << s.label << ',' << s.strategy.choice.family->name << ',' << (conservative ? "yes" : "no") << ','
            << m.frames() << ',' << mean << ',' << m.median_ms() << ',' << m.per_frame(m.triangles) << ','
            << m.per_frame(m.passes) << ',' << vs_vfc << ',' << x_floor << ',' << efficiency << ',' << visible_culled
            << ',' << wrong << ',' << m.per_frame(m.setup_ms) << ',' << m.per_frame(m.test_ms) << ',' << route << ','
            << size << ',' << m.per_frame(double(m.page_faults)) << ',' << clock_name(session.culling_clock()) << '\n';
        std::printf("%-22s %9.2f %9.2f %10.0f %7.1f %7s %8s %9s%s %8s %8s %8.2f %8.2f\n", s.label.c_str(), mean,
                    m.median_ms(), m.per_frame(m.triangles), m.per_frame(m.passes),
                    (vs_vfc == "-" ? vs_vfc : vs_vfc + "x").c_str(), (x_floor == "-" ? x_floor : x_floor + "x").c_str(),
                    efficiency, std::strcmp(efficiency, "-") ? "%" : " ", visible_culled.c_str(), wrong,
                    m.per_frame(m.setup_ms), m.per_frame(m.test_ms));
    }
    if (!csv.flush())
        throw std::runtime_error("cannot write '" + path + "'");
    if (session.culling_clock() == Clock::thread)
        std::printf("setup ms, test ms: the main thread's CPU time (--clock thread), without llvmpipe's threads nor\n"
                    "the waits for them; mean ms, median: the wall clock's.\n");
    for (const std::string &note : session.notes())
        std::printf("%s\n", note.c_str());
}

}  // namespace occu
