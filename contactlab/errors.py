"""Every exception and warning contactlab raises.

Messages follow one form: the parameter, the value, what is allowed and, where it helps, the fix,
e.g. ``nu=0.7 is invalid: Poisson's ratio must satisfy -1 < nu <= 0.5.``
"""
from __future__ import annotations

__all__ = [
    "ContactlabError",
    "ParameterError",
    "TabulatedDataError",
    "MemoryBudgetError",
    "TimeBudgetError",
    "OutsideTheoryError",
    "UnknownNameError",
    "PluginError",
    "SceneError",
    "UnitError",
    "StrategyUnavailableError",
    "MissingParameterError",
    "ConvergenceError",
    "NotSupportedError",
    "EffectNotPlannedError",
    "WorkerError",
    "ContactlabWarning",
    "ValidityWarning",
    "PluginWarning",
    "failed_part_way",
]


class ContactlabError(Exception):
    """Base class of every contactlab exception.

    Attributes
    ----------
    partial : object or None
        Set by a run that failed part-way (``Contact.simulate``, ``Scene.run``): what it
        computed before the failing step, a result of the run's own type with its series cut at
        that step and ``meta["status"] == "partial"``. None otherwise.
    failed_at : dict or None
        Where such a run failed: ``step`` (0-based index, the first step not computed),
        ``n_steps``, ``time`` (s) and the load-path ``segment``, or the ``stage`` after the
        path (``"fields"``, ``"wear"``, ``"fretting_map"``).
    """

    partial: object = None
    failed_at: dict | None = None


class ParameterError(ContactlabError, ValueError):
    """A parameter value is outside its allowed domain."""


class TabulatedDataError(ParameterError):
    """Tabulated (measured) data are unusable: unsorted, duplicate, non-finite, too short."""


class MemoryBudgetError(ParameterError):
    """A request would allocate more memory than the budget allows (steps × springs × series).

    Raise the budget with :func:`contactlab.set_memory_budget` or the environment variable
    ``CONTACTLAB_MEMORY_BUDGET`` (bytes; suffixes ``K``, ``M``, ``G`` allowed).
    """


class TimeBudgetError(ParameterError):
    """A request would run longer than the time budget allows (estimated before any work from a
    calibrated cost per unit of work: map points, wear steps, history and path steps; for a
    sweep, whose point is the user's function, from its first points, timed).

    Raise the budget with :func:`contactlab.set_time_budget` or the environment variable
    ``CONTACTLAB_TIME_BUDGET`` (seconds; suffixes ``s``, ``min``, ``h`` allowed; ``inf`` for none).
    """


class OutsideTheoryError(ContactlabError, ValueError):
    """The requested state lies outside the theory the model implements.

    Examples: a transformed profile g(x) that decreases inside the contact (ring contact), a
    sphere contact radius reaching the sphere radius, a contact leaving a tabulated profile.
    """


class UnknownNameError(ContactlabError, ValueError):
    """A name (profile type, material type, method, strategy) is not known."""


class PluginError(ContactlabError, TypeError):
    """A plugin class breaks the contract of the kind it registers for."""


class SceneError(ContactlabError, ValueError):
    """A scene failed validation. ``issues`` holds (key path, value, allowed) triples."""

    def __init__(self, message: str, issues: list[tuple[str, object, str]] | None = None):
        super().__init__(message)
        self.issues = list(issues or [])


class UnitError(SceneError, ParameterError):
    """A quantity carries a unit that is unknown or of the wrong dimension.

    Raised for scene files and for Python arguments alike (``Elastic(E="5 deg")``), so it is
    both a :class:`SceneError` (with ``issues``) and a :class:`ParameterError`.
    """


class StrategyUnavailableError(ContactlabError, ValueError):
    """A numerical route (``strategy=``) was forced that this object does not offer."""


class MissingParameterError(ContactlabError, ValueError):
    """A symbolic expression still has unbound symbols where numbers are needed."""


class ConvergenceError(ContactlabError, RuntimeError):
    """An iterative solve or an adaptive quadrature did not reach its tolerance."""


class NotSupportedError(ContactlabError, NotImplementedError):
    """The combination asked for is valid physics but not implemented (or not in the theory)."""


class EffectNotPlannedError(ContactlabError, AttributeError):
    """An output was asked for that the scene's plan did not include."""


class WorkerError(ContactlabError, RuntimeError):
    """A worker process of a sweep died (killed, out of memory, a native crash) more often than
    the sweep restarts its workers; the points it finished are kept (and stored)."""


class ContactlabWarning(UserWarning):
    """Base class of contactlab warnings."""


class ValidityWarning(ContactlabWarning):
    """A result leaves the validity range of the model that produced it."""


class PluginWarning(ContactlabWarning):
    """A plugin could not be loaded, or clashes with another one; it was skipped."""


def failed_part_way(err: ContactlabError, where: str, partial: object = None,
                    **failed_at: object) -> ContactlabError:
    """Name where a run failed in ``err``'s message and attach what it computed; returns ``err``.

    The error keeps its type and traceback; its message becomes ``"<where>: <original message>"``
    (the original is kept once: a caller higher up that names the step in its own terms
    replaces the lower-level prefix rather than adding to it).
    """
    detail = getattr(err, "_detail", None)
    if detail is None:
        detail = str(err)
        err._detail = detail          # type: ignore[attr-defined]
    err.args = (f"{where}: {detail}",)
    err.partial = partial
    err.failed_at = dict(failed_at)
    return err
