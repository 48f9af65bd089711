// SPDX-License-Identifier: MIT
// The command line of every program that measures strategies in a
// measurement session (evaluation/measurement_session.h): walkthrough,
// occu-random-views and the benches. The options the session itself takes
// are parsed and checked here, once, with one message for each bad value
// (naming the option, what it wants and what it got); a program sets its
// own defaults in the struct, hands every "--name value" pair to take()
// first and handles the pairs take() leaves.
//
//   --strategies NAME[:key=value...],...   --set key=value (repeatable)
//   --size PIXELS|WIDTHxHEIGHT   --driver llvmpipe|softpipe   --allocator keep|system
//   --batch N   --coherence on|off   --switch-off F
//   --databases DIR   --make-databases required|all   --look flat|scene
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "culling/databases.h"
#include "evaluation/allocator.h"
#include "evaluation/measurement_session.h"
#include "gl/offscreen_context.h"

namespace occu {

struct SessionCommandLine {
    // Empty: the program's own list (which it checks with check_strategies).
    std::vector<std::string> strategies;
    std::vector<std::string> common;   // --set key=value, for every strategy that has the key
    // Frames of width x height pixels: --size N is N x N, --size WxH
    // (1280x720) any other; each side 16..max_size.
    int width = 512, height = 512;
    int max_size = 8192;               // the largest side --size takes
    // Sets both sides to `pixels`: a program's own default of square frames.
    void square(int pixels) { width = height = pixels; }
    // The frames' width over their height, the cameras' aspect ratio.
    float aspect() const { return float(width) / float(height); }
    // "512" for square frames, "1280x720" otherwise (as --size takes it).
    std::string size_name() const;
    gl::Driver driver = gl::Driver::llvmpipe;
    AllocatorPolicy allocator = AllocatorPolicy::keep_freed;
    int batch = 32;
    bool coherence = true;
    double switch_off = 0.5;
    std::string databases = default_database_directory();
    DatabaseProvider::Makes make_databases = DatabaseProvider::Makes::required;
    // --look; unset: the look the scene calls for (look_for).
    std::optional<Look> look;
    // The look of frames of scene `scene_name` (a program's --scene): --look
    // where given, else scene for a scene read from a file (a Quake III
    // level, a model), flat for the generated ones (city, field).
    Look look_for(const std::string &scene_name) const;
    // False for a program that sets the traversal and the strategies'
    // settings itself, per run (occu-bench-knobs sweeps them): it takes no
    // --batch, --coherence, --switch-off nor --set.
    bool traversal_options = true;

    // Takes `name` with `value` when it is one of the options above and
    // returns true; returns false for a name the program handles itself.
    // Throws std::invalid_argument naming the option, what it wants and
    // what it got.
    bool take(const std::string &name, const std::string &value);

    // Checks `specs` (the chosen strategies, or the program's own list)
    // with the --set settings before anything is built: throws
    // std::invalid_argument naming an unknown strategy or setting, a value
    // out of range, or a --set that none of them has.
    void check_strategies(const std::vector<std::string> &specs) const;

    // The session's options of these values; the databases come from
    // `databases` (made with database_provider(), it must outlive the
    // session).
    SessionOptions session_options(DatabaseProvider &databases) const;
    DatabaseProvider database_provider() const { return DatabaseProvider(databases, make_databases); }
};

}  // namespace occu
