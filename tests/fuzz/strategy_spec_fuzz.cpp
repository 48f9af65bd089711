// SPDX-License-Identifier: MIT
// Fuzzes strategy names and settings (culling/registry.h): any text is
// either a strategy of the registry with valid settings or refused with
// std::invalid_argument.
#include <stdexcept>
#include <string>
#include <vector>

#include "culling/registry.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t *data, std::size_t size)
{
    const std::string text(reinterpret_cast<const char *>(data), size);
    // The first line is the strategy, the rest common settings, one a line.
    const std::size_t end = text.find('\n');
    std::vector<std::string> common;
    for (std::size_t at = end; at != std::string::npos && at < text.size();) {
        const std::size_t next = text.find('\n', at + 1);
        common.push_back(text.substr(at + 1, next == std::string::npos ? std::string::npos : next - at - 1));
        at = next;
    }
    try {
        const occu::StrategyChoice choice = occu::choose_strategy(text.substr(0, end), common);
        (void)choice.conservative();
        (void)choice.settings.changed();
    } catch (const std::invalid_argument &) {
    }
    return 0;
}
