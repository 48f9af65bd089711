// SPDX-License-Identifier: MIT
// A measurement session's results as files and a table
// (evaluation/measurement_session.h): frames.csv, one row per strategy and
// frame, and summary.csv, one row per strategy, with the table printed
// beside it. Columns are found by name by their readers
// (tools/plot-walkthrough.sh, tools/report-walkthrough.sh, bench/lib.sh):
// new ones go at the end.
#pragma once

#include <fstream>
#include <string>

#include "evaluation/measurement_session.h"

namespace occu {

// The share of the scene's triangles a frame did not draw, in percent.
double culled_percent(std::uint64_t triangles, std::size_t scene_triangles);

// frames.csv: a session's observer. leaves_conditional: of leaves_drawn,
// those issued under conditional rendering on a tile (chc), which the GL
// drew only where its test found them visible; every other column counts
// them as drawn. page_faults: the process's minor page faults while the
// frame was drawn. culling_clock: what timed setup_ms and test_ms, wall or
// thread (SessionOptions::culling_clock; ms is always the wall clock's).
class FramesCsv {
public:
    // Throws std::runtime_error naming `path` when it cannot write it.
    FramesCsv(const std::string &path, std::string route, std::size_t scene_triangles, Clock clock = Clock::wall);
    void row(const SessionStrategy &strategy, const StrategyFrame &frame);
    // Throws std::runtime_error naming the file when it could not write it all.
    void close();

private:
    std::string path_, route_;
    std::size_t scene_triangles_;
    Clock clock_;
    std::ofstream out_;
};

// summary.csv at `path`, one row per strategy of `session` (`route` and
// `size` repeated in each), and the same as a table on standard output,
// with the strategies' notes under it. vs_vfc: vfc's mean ms / the
// strategy's; x_floor: the strategy's mean ms / ideal's; culling_clock:
// what timed setup_ms and test_ms (the session's culling_clock), with a
// line under the table when it is the thread's. Throws
// std::runtime_error naming the file when it cannot write it.
void write_summary(const MeasurementSession &session, const std::string &path, const std::string &route, const std::string &size);

}  // namespace occu
