// The strategy registry: every culling strategy the programs can run, one
// entry per family (the list: src/strategies/registry.cpp), each from its
// own folder under src/strategies/. Programs learn strategies, their papers and their
// settings from here; a family parses its own settings.
//
// A strategy is named on the command line as NAME[:key=value...], NAME a
// family or one of its presets (a preset is the family with some settings),
// e.g. "om-ps", "om:selection=fh:occluders=32", "ou:tolerance=0.05".
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "culling/culler.h"
#include "culling/settings.h"

namespace occu {

class Hierarchy;
struct Scene;
class SceneRenderer;

// What every strategy may use, given once for all its frames.
struct StrategyContext {
    const Scene &scene;              // the meshes the hierarchy was built over
    const Hierarchy &hierarchy;
    const SceneRenderer &renderer;   // draws occluders and proxies (needs the GL context)
};

struct StrategyPreset {
    std::string name;
    std::string settings;   // "key=value:..."
    bool former_name = false;   // an older name kept working; not listed in help
};

struct StrategyFamily {
    std::string name;
    std::string paper;     // the paper and sections it implements
    std::string summary;
    bool conservative = true;      // never removes a visible pixel with tolerance=0
    // Its tests are occlusion queries the rasterizer answers, each waiting
    // for the frame drawn so far: the traversal's temporal coherence and
    // adaptive switch-off (traversal/policies.h), which save tests, apply.
    // Tests on the CPU cost too little to trade culling for.
    bool queries_rasterizer = false;
    // Its occlusion work costs time every frame on the CPU (occluders
    // drawn in begin_frame, or tests that are not cheap): the adaptive
    // switch-off, which saves that work where occlusion culls little,
    // applies.
    bool costs_per_frame = false;
    // The share of the switch-off's least gain (--switch-off F: the
    // triangles occlusion tests must cull, as a share of those drawn) that
    // this family's tests must reach to stay on: 1 for tests that stall
    // drawing while they wait for their answers; less for tests whose
    // answers come while drawing goes on (chc), which pay at a smaller gain.
    double switch_off_share = 1.0;
    bool needs_truth = false;      // culls with the oracle's answer (Frame::truth)
    std::vector<SettingSpec> settings;
    std::vector<StrategyPreset> presets;
    std::unique_ptr<Culler> (*make)(const StrategyContext &context, const Settings &settings) = nullptr;
};

const std::vector<StrategyFamily> &strategy_families();

// A strategy chosen by name, its settings parsed, not yet built.
struct StrategyChoice {
    std::string name;   // the family or preset, without settings
    std::string spec;   // as given: the name and its own settings (not the common ones)
    const StrategyFamily *family;
    Settings settings;
    bool conservative() const { return family->conservative && settings.exact(); }
    // How results name the strategy: as it was given.
    const std::string &label() const { return spec; }
};

// Parses "NAME[:key=value...]"; `common` ("key=value") apply where the
// family has the key. Throws std::invalid_argument naming an unknown
// strategy (and the known ones) or setting (and the family's).
StrategyChoice choose_strategy(const std::string &spec, const std::vector<std::string> &common = {});
// Throws std::invalid_argument when one of `common` is known to none of the strategies.
void check_common_settings(const std::vector<StrategyChoice> &chosen, const std::vector<std::string> &common);

struct Strategy {
    StrategyChoice choice;
    std::unique_ptr<Culler> culler;
};
Strategy make_strategy(const std::string &spec, const StrategyContext &context,
                       const std::vector<std::string> &common = {});

// Names that choose_strategy takes and help lists (families, presets).
std::vector<std::string> strategy_names();
// The families, their papers, presets and settings, for --help.
std::string strategies_help();
// The same as one markdown table, a row per family (README's strategies
// table is this text, and a test keeps it so).
std::string strategies_markdown();

}  // namespace occu
