"""The status of a run, with a message, for single runs, batches and sweep stores: one set of
statuses, spelled as stable codes (:class:`Status`) and as labels (:class:`RunStatus`).

:class:`Status` holds the stable codes: ``BatchResult.status`` is an int8 array of its values
and a sweep store's ``status`` variable the same codes with the CF attributes ``flag_values`` /
``flag_meanings`` (:data:`FLAG_VALUES`, :data:`FLAG_MEANINGS`). ``Trajectory.status`` is a
:class:`RunStatus`, the same statuses valued by their labels (a ``str`` enum: it compares with
``"finished"`` … and goes into JSON as the label); its :attr:`~RunStatus.code` is the
:class:`Status`.
"""

from __future__ import annotations

from enum import IntEnum, StrEnum

__all__ = ["FLAG_MEANINGS", "FLAG_VALUES", "RunStatus", "Status"]


class Status(IntEnum):
    """How a run ended. The values are stable (they are stored in files)."""

    #: every body rolled to the end
    FINISHED = 0
    #: the state overflowed (a step far too long, a diverging system); metrics meaningless
    NONFINITE = 1
    #: a body's needed friction reached mu_s N (the first event of the run)
    SLIP = 2
    #: a body's normal force fell below 0 (the first event of the run)
    LIFTOFF = 3
    #: the energy error exceeded its tolerance (single runs)
    ENERGY_ERROR = 4
    #: the run's values overflow double precision (e.g. a frequency or an inertia that is not
    #: finite); not integrated
    INVALID = 5
    #: the run's linear frequency is beyond what the (common) step can resolve; not integrated
    UNRESOLVED = 6

    @property
    def label(self) -> str:
        """The status as a lower-case name: ``finished``, ``nonfinite``, ``slip``, ``liftoff``,
        ``energy_error``, ``invalid``, ``unresolved``."""
        return self.name.lower()

    @property
    def message(self) -> str:
        """What the status means, in one sentence."""
        return _MESSAGES[self]

    @classmethod
    def from_label(cls, label: str) -> Status:
        """The status named ``label`` (``"slip"`` -> :attr:`SLIP`)."""
        try:
            return cls[label.upper()]
        except KeyError:
            raise ValueError(
                f"unknown status {label!r}; one of {', '.join(s.label for s in cls)}"
            ) from None


_MESSAGES = {
    Status.FINISHED: "every body rolled to the end",
    Status.NONFINITE: "the state became non-finite: the step cannot resolve the motion (or the "
    "system diverges); the metrics are meaningless",
    Status.SLIP: "a body's needed friction reached mu_s N: it starts to slip",
    Status.LIFTOFF: "a body's normal force fell below zero: it lifts off",
    Status.ENERGY_ERROR: "the energy error exceeded its tolerance: the step does not resolve "
    "the motion",
    Status.INVALID: "the run's values overflow double precision; it was not integrated",
    Status.UNRESOLVED: "the run's linear frequency is beyond what the step can resolve; it was "
    "not integrated",
}


class RunStatus(StrEnum):
    """How a single run ended (``Trajectory.status``): :class:`Status` valued by its
    :attr:`~Status.label`. A ``str``: ``trajectory.status == "slip"`` holds and JSON writes
    ``"slip"``; :attr:`code` is the stable :class:`Status` (what a store keeps)."""

    FINISHED = "finished"
    NONFINITE = "nonfinite"
    SLIP = "slip"
    LIFTOFF = "liftoff"
    ENERGY_ERROR = "energy_error"
    INVALID = "invalid"
    UNRESOLVED = "unresolved"

    @property
    def code(self) -> Status:
        """The :class:`Status` of the same name (its stable integer value)."""
        return Status[self.name]

    @property
    def message(self) -> str:
        """What the status means, in one sentence (:attr:`Status.message`)."""
        return _MESSAGES[self.code]


# one status, two spellings: the same names, in the same order
assert [(s.name, s.value) for s in RunStatus] == [(s.name, s.label) for s in Status]

#: CF ``flag_values`` of a stored status variable (every code, in order).
FLAG_VALUES: tuple[int, ...] = tuple(int(s) for s in Status)
#: CF ``flag_meanings``: the labels, space-separated, in the order of :data:`FLAG_VALUES`.
FLAG_MEANINGS: str = " ".join(s.label for s in Status)
