#!/usr/bin/env python3
"""The library's layers only look down: no file includes a header of a layer above its own.

Run by ctest (layers.only_look_down). The layers, lowest first, are listed in docs/architecture.md;
each rule below names a part of the tree and the headers it must not include."""
import pathlib
import re
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent
# (files whose path starts with one of these, headers they must not include)
UP = {
    "models": ["model_registry", "model_choice", "lut/", "advise/", "image/", "fit/", "io/", "derived_quantities"],
    "core": ["model_registry", "model_choice", "lut/", "advise/", "image/", "fit/", "io/"],
    "registry": ["model_choice", "lut/", "advise/", "image/", "fit/", "io/", "derived_quantities"],
    "tables": ["lut/table_kinds", "advise/", "fit/"],
    "image": ["lut/table_kinds", "advise/"],
    "library": ["cli_common", "commands.hpp", "lut_kinds"],
}
PARTS = {
    "models": ["include/bssrdf/models/", "src/models/", "include/bssrdf/model.hpp", "src/model.cpp"],
    "core": ["include/bssrdf/adding_doubling/", "src/adding_doubling/", "include/bssrdf/montecarlo", "src/montecarlo/",
             "src/medium.cpp", "src/fresnel.cpp", "src/single_scattering.cpp", "src/transport_total.cpp",
             "src/validity.cpp", "src/quadrature.cpp", "src/hankel.cpp", "src/profile.cpp"],
    "registry": ["include/bssrdf/model_registry.hpp", "src/model_registry.cpp"],
    "tables": ["include/bssrdf/lut/", "src/lut/"],
    "image": ["include/bssrdf/image/", "src/image/"],
    "library": ["include/bssrdf/", "src/"],
}
EXCEPT = {"tables": ["include/bssrdf/lut/table_kinds.hpp", "src/lut/table_kinds.cpp"]}  # the kinds' entry points sit above image/

include = re.compile(r'#include\s+[<"](?:bssrdf/)?([^>"]+)[>"]')
problems = []
for path in sorted(list(ROOT.glob("src/**/*.[ch]pp")) + list(ROOT.glob("include/**/*.hpp"))):
    rel = path.relative_to(ROOT).as_posix()
    if rel.startswith("src/cli/"):
        continue
    for part, prefixes in PARTS.items():
        if not any(rel.startswith(p) for p in prefixes) or rel in EXCEPT.get(part, []):
            continue
        for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
            m = include.search(line)
            if m and any(m.group(1).startswith(up) for up in UP[part]):
                problems.append(f"{rel}:{number}: {part} includes {m.group(1)}, a layer above it")
for p in problems:
    print(p)
print(f"layers: {len(problems)} upward includes")
sys.exit(1 if problems else 0)
