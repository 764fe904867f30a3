"""Imported once by the worker pool's forkserver (:data:`rollspring.web.workers.PRELOAD`): loads
the scientific stack and rollspring, and runs one small simulation so that the compiled kernels
are in memory. Every worker forked from the forkserver starts with all of it, warm."""

import scipy.integrate  # the libraries the rest of rollspring loads on demand
import scipy.optimize  # noqa: F401

import rollspring.outputs  # noqa: F401
from rollspring.service import documents  # noqa: F401 - SymPy, Matplotlib: loaded once here
from rollspring.web import jobs

jobs.warm_up()
