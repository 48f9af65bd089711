// SPDX-License-Identifier: MIT
// The strategy registry: every culling strategy the programs can run, one
// entry per family (the list: src/strategies/registry.cpp), each from its
// own folder under src/strategies/. Programs learn strategies, their papers and their
// settings from here; a family parses its own settings.
//
// A strategy is named on the command line as NAME[:key=value...], NAME a
// family or one of its presets (a preset is the family with some settings),
// e.g. "om-ps", "om:selection=fh:occluders=32", "ou:tolerance=0.05".
// NAME may also chain strategies, STAGE+STAGE[+...] (each a family or
// preset): each stage tests only the nodes the stages before it left
// visible (culling/chained_culler.h), e.g. "bsp-pvs+ou-shared" (a level's
// PVS, then the unit's tests on what it leaves). A chain is a family made
// of its stages': conservative when all are, the scene requirements and
// databases of all, temporal coherence where a stage wants it, and their
// settings together (a key two stages know takes one value for both); the
// settings after NAME and each stage's preset apply. A chain is never
// switched off (a switched-off frame would drop every stage, the first
// one's set too): its later stages test in every frame.
#pragma once

#include <cstddef>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "culling/culler.h"
#include "culling/database_file.h"
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

// The traversal's policies across frames (traversal/policies.h) a family
// wants; the programs apply them where their options allow.
struct TraversalWants {
    // Temporal coherence (the visible node list): for tests that are
    // occlusion queries the rasterizer answers, each waiting for the frame
    // drawn so far; it saves tests. Tests on the CPU cost too little to
    // trade culling for.
    bool coherence = false;
    // The adaptive switch-off: for those, and for families whose occlusion
    // work costs time every frame on the CPU (occluders drawn in
    // begin_frame, or tests that are not cheap); it saves that work where
    // occlusion culls little.
    bool switch_off = false;
    // The share of the switch-off's least gain (--switch-off F: the
    // triangles occlusion tests must cull, as a share of those drawn) that
    // this family's tests must reach to stay on: 1 for tests that stall
    // drawing while they wait for their answers; less for tests whose
    // answers come while drawing goes on (chc), which pay at a smaller gain.
    double switch_off_share = 1.0;
    // The family walks the hierarchy itself in the frames it tests in full
    // (an OwnTraversal, traversal/traversal.h): it cannot be a later stage
    // of a chain, which hands a stage only what the stages before it left.
    bool own_traversal = false;
};

// A property a scene must have for a family to run on it.
struct SceneRequirement {
    std::string what;   // "2.5D occluders (...)": said when a scene lacks it
    bool (*met)(const Scene &scene) = nullptr;
};

// What a database is made for: a strategy's settings, on its scene, for
// frames of width x height.
struct DatabaseRequest {
    const StrategyContext &context;
    const Settings &settings;
    int width, height;
};

// A database a family reads, named by one of its path settings. When that
// setting is empty, a strategy that requires the database cannot run; one
// that does not makes what it needs itself, at start or during the run
// (a cost the figures then include). The resource provider
// (culling/databases.h) makes or finds one by its provenance.
struct DatabaseNeed {
    std::string setting;      // the path setting
    std::string name;         // what it is, for messages ("occluder database")
    bool required = false;
    // Whether a strategy of these settings reads it (null: every one).
    bool (*read_by)(const Settings &settings) = nullptr;
    // Everything the database's contents depend on (culling/database_file.h):
    // its algorithm, the settings it is made with, the scene and hierarchy
    // it serves, the library's code and the Mesa build when GL makes it.
    // Two databases of one provenance are the same database.
    DatabaseProvenance (*provenance)(const DatabaseRequest &request) = nullptr;
    // Makes it and writes it to `path` with that provenance; may draw with
    // the context's GL.
    void (*make)(const DatabaseRequest &request, const std::string &path) = nullptr;

    bool read_by_settings(const Settings &settings) const { return !read_by || read_by(settings); }
};

// A per-frame source of occluders that several families draw from
// (occluders/sources.h: skins, a level's brushes, the scene's own
// triangles, shadow culling's large occluders): the settings and databases
// it reads, declared once by the source. A family that takes occluders
// from it names it among its occluder_sources, as it names its databases
// and scene requirements, and the registry gives the family the source's
// settings and databases after its own (with_occluder_sources).
struct OccluderSource {
    std::string name;   // what it is, for messages ("occluder skins")
    std::vector<SettingSpec> settings;
    std::vector<DatabaseNeed> databases;
};

// A family's use of a source: whether a strategy of these settings takes
// occluders from it (null: every one); the source's databases are read
// only then.
struct OccluderSourceUse {
    const OccluderSource *source = nullptr;
    bool (*used_by)(const Settings &settings) = nullptr;
};

// A variant of a family that the registry-wide tests of conservative
// culling draw beside the registry's names (tests/integration/
// strategy_variants.h): on routes and hard cases every frame of it must
// lose no visible pixel against the unculled frame, on both drivers. A
// family declares the variants its settings need tested (a setting that
// changes what is culled, a traversal it must survive), so that a new
// setting is tested by an edit of the family's folder alone.
struct StrategyTestVariant {
    std::string spec;           // NAME[:key=value...], NAME the family or one of its presets
    std::size_t batch = 16;     // nodes tested together
    // Policies across the frames of a route (traversal/policies.h):
    // temporal coherence; a switch-off that switches off after the first
    // frame and probes as soon as it may (its probes test inner
    // nodes only, and must stay exact).
    bool coherence = false;
    bool probing_switch_off = false;
    // Claims on the triangles the variant draws over a test's frames: at
    // most `share` times what `spec` draws (a registry name or a test
    // variant, in batches of 16 without policies across frames).
    struct Bound {
        std::string spec;
        double share = 1.0;
    };
    std::vector<Bound> draws_at_most;

    explicit StrategyTestVariant(std::string spec_) : spec(std::move(spec_)) {}
    StrategyTestVariant &in_batches_of(std::size_t nodes)
    {
        batch = nodes;
        return *this;
    }
    StrategyTestVariant &with_coherence()
    {
        coherence = true;
        return *this;
    }
    StrategyTestVariant &with_probing_switch_off()
    {
        probing_switch_off = true;
        return *this;
    }
    StrategyTestVariant &drawing_at_most(std::string other, double share = 1.0)
    {
        draws_at_most.push_back({std::move(other), share});
        return *this;
    }
};

struct StrategyFamily {
    std::string name;
    std::string paper;     // the paper and sections it implements
    std::string summary;
    bool conservative = true;      // never removes a visible pixel with tolerance=0
    bool needs_truth = false;      // culls with the oracle's answer (Frame::truth)
    TraversalWants traversal;
    std::vector<SceneRequirement> scene_requirements;
    std::vector<DatabaseNeed> databases;
    std::vector<SettingSpec> settings;
    // The shared occluder sources it draws from, in order; their settings
    // and databases join the two lists above (with_occluder_sources).
    std::vector<OccluderSourceUse> occluder_sources;
    std::vector<StrategyPreset> presets;
    std::vector<StrategyTestVariant> test_variants;   // above; the family's names are tested without listing them
    std::unique_ptr<Culler> (*make)(const StrategyContext &context, const Settings &settings) = nullptr;
    // A chain's stages, first to last (above); empty for a registered family.
    std::vector<const StrategyFamily *> stages;

    // Why the family cannot run on `scene` ("pvs needs 2.5D occluders
    // (...); this scene has none"); empty when it can.
    std::string refusal(const Scene &scene) const;
};

const std::vector<StrategyFamily> &strategy_families();

// `families` each with the settings and databases of its occluder sources
// added after its own (a setting or database the family declares itself
// is kept, not added twice), for strategy_families() to list.
std::vector<StrategyFamily> with_occluder_sources(std::vector<StrategyFamily> families);

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
// Makes the strategy `spec` for `context`. Throws std::invalid_argument as
// choose_strategy does, and naming what the scene lacks when the family
// refuses it (StrategyFamily::refusal); a family's own checks throw what
// they throw (a required database not given: std::invalid_argument).
Strategy make_strategy(const std::string &spec, const StrategyContext &context,
                       const std::vector<std::string> &common = {});

// Names that choose_strategy takes and help lists (families, presets).
std::vector<std::string> strategy_names();
// Every strategy once: strategy_names() without a family's own name where
// one of its presets means the same settings (om and om-ps).
std::vector<std::string> distinct_strategy_names();
// The families, their papers, presets and settings, for --help.
std::string strategies_help();
// The same as one markdown table, a row per family (docs/strategies.md's
// table is this text, and a test keeps it so).
std::string strategies_markdown();

}  // namespace occu
