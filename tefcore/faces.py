"""Public faces of packages: names defined in their modules, loaded on first use.

A package's face is the short list of names its reader needs (as
``scipy.linalg`` is the face of its private modules).  The names stay in the
modules that define them; the face maps each to its module and loads it on
first access (PEP 562), so importing a package costs nothing until a name is
used, and ``python -m tefcore.paper.run.commands`` does not load the whole
paper layer through its parents.

Examples
--------
>>> import types
>>> face = types.ModuleType("planted")
>>> getattr_, dir_ = lazy_face(face, {"sqrt": "math"})
>>> getattr_("sqrt")(9.0)
3.0
>>> "sqrt" in dir_()
True
"""

from __future__ import annotations

import importlib

__all__ = ["lazy_face"]


def lazy_face(module, api: dict[str, str]):
    """``(__getattr__, __dir__)`` of a package whose public names live in its modules.

    Parameters
    ----------
    module : module
        The package (``sys.modules[__name__]`` in its ``__init__``).
    api : dict
        Public name -> absolute name of the module that defines it.

    Returns
    -------
    tuple of callable
        The module-level ``__getattr__`` (loads the defining module, caches the
        name in the package) and ``__dir__``.
    """

    def __getattr__(name: str):
        if name in api:
            value = getattr(importlib.import_module(api[name]), name)
            setattr(module, name, value)  # later look-ups skip this function
            return value
        raise AttributeError(f"module {module.__name__!r} has no attribute {name!r}")

    def __dir__() -> list[str]:
        return sorted(set(vars(module)) | set(api))

    return __getattr__, __dir__
