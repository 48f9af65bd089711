#include "culling/registry.h"

#include <stdexcept>

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

StrategyChoice choose_strategy(const std::string &spec, const std::vector<std::string> &common)
{
    const auto colon = spec.find(':');
    const std::string name = spec.substr(0, colon);
    if (name.empty())
        throw std::invalid_argument("empty strategy name in '" + spec + "'");
    const Found found = find(name);
    StrategyChoice choice{name, spec, found.family, Settings(name, &found.family->settings)};
    if (found.preset)
        choice.settings.set_all(found.preset->settings);
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
    std::unique_ptr<Culler> culler = choice.family->make(context, choice.settings);
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
