# SPDX-License-Identifier: MIT
"""patches/mesa/series as the Python tools read it: the patch file names in
order, each with the part it belongs to.

The series file: one patch file name per line, '#' starting a comment; a
comment line '# part SUITE: WHAT' opens a part (tools/check-mesa-series.sh
reads the same lines); patches before the first such line are part 'base'.
"""
import os
import re

PART = re.compile(r"^#\s*part\s+([A-Za-z0-9_-]+):")


def patches(series_dir):
    """[(patch file name, part SUITE)] of series_dir/series, in order."""
    result, part = [], "base"
    with open(os.path.join(series_dir, "series"), encoding="utf-8") as f:
        for line in f:
            m = PART.match(line)
            if m:
                part = m.group(1)
                continue
            name = line.split("#", 1)[0].strip()
            if name:
                result.append((name, part))
    return result
