"""The measured-media database: bundled materials plus your own (``db=``): get, list, all, export, from_fit."""
from ._bssrdf import materials as _compiled

get = _compiled.get
list = _compiled.list  # noqa: A001 -- the command's name: `bssrdf materials list`
all = _compiled.all  # noqa: A001
export = _compiled.export
from_fit = _compiled.from_fit

__all__ = ["get", "list", "all", "export", "from_fit"]
