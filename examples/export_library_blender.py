#!/usr/bin/env python3
"""Export the whole materials library (bundled, plus your own with --db) as one Blender script.

    python3 examples/export_library_blender.py [OUT.py] [--db DIR] [--unit m] [--method fixed-radius]

Run the result in Blender: blender --python OUT.py (or use the bssrdf add-on's panel per material).
"""
import argparse

import bssrdf

p = argparse.ArgumentParser()
p.add_argument("out", nargs="?", default="bssrdf-library.py")
p.add_argument("--db", default="")
p.add_argument("--unit", default="m")
p.add_argument("--method", default="fixed-radius")
args = p.parse_args()

library = bssrdf.materials.all(db=args.db)
script = bssrdf.materials.export(library, to="blender", unit=args.unit, blender_method=args.method, db=args.db,
                                 output=args.out)
notes = [line for line in script.splitlines() if line.startswith("#   NOTE")]
print("wrote %s: %d materials, %d notes where Cycles cannot follow the medium" % (args.out, len(library), len(notes)))
