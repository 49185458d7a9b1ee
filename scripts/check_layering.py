#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Checks that module dependencies point down only (issue 16).

Every #include "subfab/<m>/..." (public header) or "<m>/..." (private header
under src/) in src/<module>/ and include/subfab/<module>/ must name the module
itself or one it may use, as listed in ALLOWED (the same graph as the DEPS of
src/CMakeLists.txt). apps/ and tests/ sit above every module. A file in a
folder that is not a known module is an error too, so a new module has to be
placed here. Exit 0 when clean, 1 with one line per offending include.
Run by `make test`; by hand: python3 scripts/check_layering.py
"""
import os
import re
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

# module -> modules it may include (besides itself), bottom to top.
ALLOWED = {
    "core": set(),
    "mesh": {"core"},
    "checks": {"core", "mesh"},
    "geometry": {"core", "mesh"},
    "validate": {"core", "mesh", "checks", "geometry"},
    "fidelity": {"core", "mesh", "geometry", "checks"},
    "repair": {"core", "mesh", "geometry", "checks"},
    "decompose": {"core", "mesh", "checks", "geometry", "validate", "fidelity"},
    "unfold": {"core", "mesh", "checks", "geometry"},
    "mill": {"core", "mesh"},
    "view": {"core", "mesh"},
    "hex": {"core", "mesh", "checks", "geometry"},
}

INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"')


def module_of_include(path):
    parts = path.split("/")
    if parts[0] == "subfab" and len(parts) > 2:
        return parts[1]
    if len(parts) > 1:
        return parts[0]
    return None  # same-folder include


def main():
    errors = []
    checked = 0
    for top in (os.path.join(ROOT, "src"), os.path.join(ROOT, "include", "subfab")):
        for module in sorted(os.listdir(top)):
            folder = os.path.join(top, module)
            if not os.path.isdir(folder):
                continue
            if module not in ALLOWED:
                errors.append(f"{os.path.relpath(folder, ROOT)}: unknown module '{module}' (add it to ALLOWED)")
                continue
            for dirpath, _, files in os.walk(folder):
                for name in sorted(files):
                    if not name.endswith((".h", ".cpp")):
                        continue
                    file = os.path.join(dirpath, name)
                    with open(file, encoding="utf-8") as f:
                        for lineno, line in enumerate(f, 1):
                            m = INCLUDE.match(line)
                            if not m:
                                continue
                            checked += 1
                            dep = module_of_include(m.group(1))
                            if dep is None or dep == module:
                                continue
                            if dep not in ALLOWED:
                                errors.append(f"{os.path.relpath(file, ROOT)}:{lineno}: includes '{m.group(1)}' "
                                              f"from unknown module '{dep}'")
                            elif dep not in ALLOWED[module]:
                                errors.append(f"{os.path.relpath(file, ROOT)}:{lineno}: {module} includes "
                                              f"'{m.group(1)}' ({dep} is not below {module})")
    for e in errors:
        print(e)
    print(f"layering: {checked} includes checked, {len(errors)} pointing up or sideways")
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main())
