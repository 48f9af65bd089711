// SPDX-License-Identifier: MIT
#include "culling/registry.h"

#include <algorithm>
#include <map>
#include <mutex>
#include <stdexcept>

#include "culling/chained_culler.h"

namespace occu {

namespace {

struct Found {
    const StrategyFamily *family = nullptr;
    const StrategyPreset *preset = nullptr;
};

Found find(const std::string &name)
{
    for (const StrategyFamily &f : strategy_families()) {
        if (f.name == name)
            return {&f, nullptr};
        for (const StrategyPreset &p : f.presets)
            if (p.name == name)
                return {&f, &p};
    }
    std::string known;
    for (const std::string &n : strategy_names())
        known += (known.empty() ? "" : ", ") + n;
    throw std::invalid_argument("unknown culling strategy '" + name + "' (known: " + known + ")");
}

// The family of a chain of `stages` (registry.h), made once per sequence
// of families and kept for the program's life (choices point to it).
const StrategyFamily *chain_family(const std::vector<const StrategyFamily *> &stages)
{
    static std::mutex mutex;
    static std::map<std::string, std::unique_ptr<StrategyFamily>> chains;
    std::string name, paper, summary;
    for (const StrategyFamily *f : stages) {
        if (f->traversal.own_traversal)
            throw std::invalid_argument(f->name + " walks the hierarchy itself (its own traversal) and cannot be a "
                                                  "stage of a chain of strategies");
        name += (name.empty() ? "" : "+") + f->name;
        paper += (paper.empty() ? "" : "; then ") + f->paper;
        summary += (summary.empty() ? "" : ", then on what it leaves visible: ") + f->summary;
    }
    const std::lock_guard<std::mutex> lock(mutex);
    std::unique_ptr<StrategyFamily> &chain = chains[name];
    if (chain)
        return chain.get();
    chain = std::make_unique<StrategyFamily>();
    StrategyFamily &c = *chain;
    c.name = name;
    c.paper = paper;
    c.summary = summary;
    c.stages = stages;
    c.conservative = true;
    // Never switched off: a switched-off frame is view-frustum culled
    // without calling the culler (traversal/policies.h), which would drop
    // the first stage's answers with the later stages' tests.
    c.traversal.switch_off = false;
    for (const StrategyFamily *f : stages) {
        c.conservative = c.conservative && f->conservative;
        c.needs_truth = c.needs_truth || f->needs_truth;
        c.traversal.coherence = c.traversal.coherence || f->traversal.coherence;
        c.scene_requirements.insert(c.scene_requirements.end(), f->scene_requirements.begin(),
                                    f->scene_requirements.end());
        for (const DatabaseNeed &d : f->databases)
            if (std::none_of(c.databases.begin(), c.databases.end(),
                             [&d](const DatabaseNeed &e) { return e.setting == d.setting; }))
                c.databases.push_back(d);
        for (const SettingSpec &s : f->settings)
            if (std::none_of(c.settings.begin(), c.settings.end(),
                             [&s](const SettingSpec &e) { return e.name == s.name; }))
                c.settings.push_back(s);
    }
    return chain.get();
}

// A family's flags in words, as help and the markdown table list them.
std::string properties(const StrategyFamily &f)
{
    std::string p = std::string(f.conservative ? "conservative" : "approximate") +
                    (f.traversal.coherence ? ", temporal coherence" : "") +
                    (f.traversal.switch_off ? ", switch-off" : "") + (f.needs_truth ? ", needs the oracle" : "");
    for (const SceneRequirement &r : f.scene_requirements)
        p += ", needs " + r.what;
    for (const DatabaseNeed &d : f.databases)
        p += ", reads " + d.setting;
    return p;
}

// A markdown table cell: a '|' would end the cell.
std::string cell(const std::string &text)
{
    std::string c;
    for (char ch : text)
        c += ch == '|' ? std::string("\\|") : std::string(1, ch);
    return c;
}

std::pair<std::string, std::string> split_assignment(const std::string &item)
{
    const auto eq = item.find('=');
    if (eq == std::string::npos || eq == 0)
        throw std::invalid_argument("setting '" + item + "' is not key=value");
    return {item.substr(0, eq), item.substr(eq + 1)};
}

}  // namespace

std::vector<StrategyFamily> with_occluder_sources(std::vector<StrategyFamily> families)
{
    for (StrategyFamily &f : families)
        for (const OccluderSourceUse &use : f.occluder_sources) {
            for (const SettingSpec &s : use.source->settings)
                if (std::none_of(f.settings.begin(), f.settings.end(),
                                 [&s](const SettingSpec &e) { return e.name == s.name; }))
                    f.settings.push_back(s);
            for (DatabaseNeed d : use.source->databases)
                if (std::none_of(f.databases.begin(), f.databases.end(),
                                 [&d](const DatabaseNeed &e) { return e.setting == d.setting; })) {
                    if (use.used_by)
                        d.read_by = use.used_by;
                    f.databases.push_back(d);
                }
        }
    return families;
}

StrategyChoice choose_strategy(const std::string &spec, const std::vector<std::string> &common)
{
    const auto colon = spec.find(':');
    const std::string name = spec.substr(0, colon);
    if (name.empty())
        throw std::invalid_argument("empty strategy name in '" + spec + "'");
    std::vector<Found> stages;
    for (std::size_t at = 0, plus;; at = plus + 1) {
        plus = name.find('+', at);
        const std::string stage = name.substr(at, plus == std::string::npos ? plus : plus - at);
        if (stage.empty())
            throw std::invalid_argument("empty strategy name in the chain '" + name + "'");
        stages.push_back(find(stage));
        if (plus == std::string::npos)
            break;
    }
    const StrategyFamily *family = stages.front().family;
    if (stages.size() > 1) {
        std::vector<const StrategyFamily *> families;
        for (const Found &f : stages)
            families.push_back(f.family);
        family = chain_family(families);
    }
    StrategyChoice choice{name, spec, family, Settings(name, &family->settings)};
    for (const Found &f : stages)
        if (f.preset)
            choice.settings.set_all(f.preset->settings);
    for (const std::string &c : common) {
        const auto [key, value] = split_assignment(c);
        if (choice.settings.knows(key))
            choice.settings.set(key, value);
    }
    if (colon != std::string::npos)
        choice.settings.set_all(spec.substr(colon + 1));
    return choice;
}

void check_common_settings(const std::vector<StrategyChoice> &chosen, const std::vector<std::string> &common)
{
    for (const std::string &c : common) {
        const std::string key = split_assignment(c).first;
        bool known = false;
        std::string names;
        for (const StrategyChoice &s : chosen) {
            known = known || s.settings.knows(key);
            names += (names.empty() ? "" : ", ") + s.name;
        }
        if (!known)
            throw std::invalid_argument("no chosen strategy (" + names + ") has a setting '" + key + "'");
    }
}

std::string StrategyFamily::refusal(const Scene &scene) const
{
    for (const SceneRequirement &r : scene_requirements)
        if (!r.met(scene))
            return name + " needs " + r.what + "; this scene has none";
    return "";
}

Strategy make_strategy(const std::string &spec, const StrategyContext &context, const std::vector<std::string> &common)
{
    StrategyChoice choice = choose_strategy(spec, common);
    if (const std::string why = choice.family->refusal(context.scene); !why.empty())
        throw std::invalid_argument(why);
    std::unique_ptr<Culler> culler;
    if (choice.family->stages.empty()) {
        culler = choice.family->make(context, choice.settings);
    } else {
        std::vector<std::pair<std::string, std::unique_ptr<Culler>>> stages;
        for (const StrategyFamily *f : choice.family->stages)
            stages.emplace_back(f->name, f->make(context, choice.settings));
        culler = std::make_unique<ChainedCuller>(std::move(stages));
    }
    return {std::move(choice), std::move(culler)};
}

std::vector<std::string> strategy_names()
{
    std::vector<std::string> names;
    for (const StrategyFamily &f : strategy_families()) {
        names.push_back(f.name);
        for (const StrategyPreset &p : f.presets)
            if (!p.former_name)
                names.push_back(p.name);
    }
    return names;
}

std::vector<std::string> distinct_strategy_names()
{
    std::vector<std::string> names;
    for (const StrategyFamily &f : strategy_families()) {
        const std::string defaults = choose_strategy(f.name).settings.changed();
        bool repeated = false;
        for (const StrategyPreset &p : f.presets)
            repeated = repeated || (!p.former_name && choose_strategy(p.name).settings.changed() == defaults);
        if (!repeated)
            names.push_back(f.name);
        for (const StrategyPreset &p : f.presets)
            if (!p.former_name)
                names.push_back(p.name);
    }
    return names;
}

std::string strategies_help()
{
    std::string h;
    for (const StrategyFamily &f : strategy_families()) {
        h += "  " + f.name + ": " + f.summary + "\n      " + f.paper + "; " + properties(f) + "\n";
        for (const SceneRequirement &r : f.scene_requirements)
            h += "      needs " + r.what + "\n";
        for (const DatabaseNeed &d : f.databases)
            h += "      reads " + d.setting + " (" + d.name + (d.required ? ", made when not given" : ", made with --make-databases all") + ")\n";
        std::string former;
        for (const StrategyPreset &p : f.presets) {
            if (!p.former_name)
                h += "      " + p.name + " = " + f.name + (p.settings.empty() ? "" : ":" + p.settings) + "\n";
            else
                former += (former.empty() ? "" : ", ") + p.name;
        }
        if (!former.empty())
            h += "      (former names, still accepted: " + former + ")\n";
        for (const SettingSpec &s : f.settings)
            h += "      " + s.describe() + "\n";
    }
    return h;
}

std::string strategies_markdown()
{
    std::string t = "| family | presets | paper | what it does | settings (default) | properties |\n"
                    "|---|---|---|---|---|---|\n";
    for (const StrategyFamily &f : strategy_families()) {
        std::string presets, former;
        for (const StrategyPreset &p : f.presets) {
            std::string &list = p.former_name ? former : presets;
            list += (list.empty() ? "`" : ", `") + p.name + "`" + (p.settings.empty() ? "" : " (`" + p.settings + "`)");
        }
        if (!former.empty())
            presets += (presets.empty() ? "" : "; ") + ("former names, still accepted: " + former);
        std::string settings;
        for (const SettingSpec &s : f.settings) {
            // "`key=default` (range; role): help"
            const std::string d = s.describe();
            const std::size_t open = d.find(" (");
            settings += (settings.empty() ? "" : "<br>") + ("`" + d.substr(0, open) + "`" + d.substr(open));
        }
        t += "| `" + f.name + "` | " + cell(presets) + " | " + cell(f.paper) + " | " + cell(f.summary) + " | " +
             cell(settings) + " | " + cell(properties(f)) + " |\n";
    }
    return t;
}

}  // namespace occu
