"""The type stubs are what the compiled module says (regenerated and compared), parse, and cover every public
name; every public function and class has a docstring."""
import ast
import inspect
import os
import subprocess
import sys

import bssrdf
from bssrdf import _bssrdf

HERE = os.path.dirname(os.path.abspath(__file__))
PACKAGE = os.path.join(HERE, "..", "bssrdf")


def test_stubs_are_up_to_date(tmp_path):
    subprocess.run([sys.executable, os.path.join(HERE, "..", "tools", "make_stubs.py"), str(tmp_path)], check=True)
    for name in ("__init__.pyi", "materials.pyi", "fit.pyi"):
        with open(os.path.join(PACKAGE, name)) as committed:
            assert (tmp_path / name).read_text() == committed.read(), (
                name + " is stale: run python/tools/make_stubs.py")


def test_stubs_parse_and_name_every_public_object():
    with open(os.path.join(PACKAGE, "__init__.pyi")) as f:
        tree = ast.parse(f.read())
    named = {n.name for n in tree.body if isinstance(n, (ast.ClassDef, ast.FunctionDef))}
    public = {n for n in dir(_bssrdf) if not n.startswith("_") and not inspect.ismodule(getattr(_bssrdf, n))
              and callable(getattr(_bssrdf, n))}
    assert public <= named, public - named


def test_every_public_object_has_a_docstring():
    missing = []
    for module in (_bssrdf, _bssrdf.materials, _bssrdf.fit):
        for name in dir(module):
            obj = getattr(module, name)
            if name.startswith("_") or inspect.ismodule(obj) or not callable(obj):
                continue
            doc = (obj.__doc__ or "").splitlines()
            text = [l for l in doc if l.strip() and not l.lstrip().startswith(name + "(")
                    and "Overloaded function" not in l]
            if not text:
                missing.append(module.__name__ + "." + name)
    assert not missing, missing
    assert bssrdf.__doc__ and bssrdf.materials.__doc__ and bssrdf.fit.__doc__
