"""A module executed from its spec by hand (:func:`exec_spec`), as the import system does it:
registered in ``sys.modules`` while its code runs, removed again when that fails. For the
modules the simulation loads itself: SciPy's BLAS check module alone (:mod:`rollspring.simulate`)
and the generated batch kernels (:mod:`rollspring.simulate.batch.cache`)."""

from __future__ import annotations

import importlib.util
import sys
from importlib.machinery import ModuleSpec
from types import ModuleType

__all__ = ["exec_spec"]


def exec_spec(spec: ModuleSpec) -> ModuleType:
    """The module of ``spec``, executed under ``spec.name`` in :data:`sys.modules` (so that the
    imports of that name while it runs find it); on any failure it is removed again and the
    exception raised."""
    assert spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module
    try:
        spec.loader.exec_module(module)
    except BaseException:
        del sys.modules[spec.name]
        raise
    return module
