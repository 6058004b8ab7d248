"""Fits that return FitResult objects (values, 1-sigma errors, the report): profile, albedo, slab, rxt, gaussians,
burley -- the `bssrdf fit` commands."""
from ._bssrdf import fit as _compiled

profile = _compiled.profile
albedo = _compiled.albedo
slab = _compiled.slab
rxt = _compiled.rxt
gaussians = _compiled.gaussians
burley = _compiled.burley

__all__ = ["profile", "albedo", "slab", "rxt", "gaussians", "burley"]
