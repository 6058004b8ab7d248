"""bssrdf: subsurface-scattering diffusion profiles, references, fits and lookup tables.

The same library as the ``bssrdf`` command line, with numpy arrays in and out::

    import bssrdf
    skin = bssrdf.materials.get("Skin1")
    p = bssrdf.profile(skin, r=[0.1, 0.5, 1.0])      # the registry's default model (exact)
    p.values                                          # channels x radii, 1/mm^2
    bssrdf.Model("better-dipole").R(skin.medium, r)   # one call for any number of radii

Bad input raises ValueError with the command line's one-line message. docs/python.md has the tour.
"""
from ._bssrdf import *  # noqa: F401,F403
from ._bssrdf import __version__  # noqa: F401
from . import fit, materials  # noqa: F401
