"""Conformance checks for materials: :class:`MaterialChecks`."""
from __future__ import annotations

import math
from typing import Any, ClassVar

from .profiles import _param_kwargs, _perturbed, _rebuild

__all__ = ["MaterialChecks", "bad_values"]

_BAD = {
    "positive": (0.0, -1.0, math.nan, math.inf, "abc"),
    "nonnegative": (-1.0, math.nan, math.inf, "abc"),
    "real": (math.nan, math.inf, -math.inf, "abc"),
}


def bad_values(domain: str) -> tuple[Any, ...]:
    """Values outside a :class:`~contactlab.params.Param` domain (every domain rejects NaN,
    infinities and non-numbers).

    Examples
    --------
    >>> bad_values("positive")
    (0.0, -1.0, nan, inf, 'abc')
    """
    return _BAD[domain]


class MaterialChecks:
    """Mixin of conformance tests for a :class:`~contactlab.materials.Material` subclass.

    Subclass it in a test module (class name starting with ``Test``) and implement
    :meth:`make_material` (or set the class attribute ``material``). pytest then collects:

    * ``test_pair_moduli_positive_and_symmetric``: ``effective_moduli`` against an elastic body,
      a rigid body and itself gives finite positive ``E*``, ``G*``, ``G_t``, the same in either
      order (elastic materials); a viscoelastic material raises
      :class:`~contactlab.errors.NotSupportedError` instead, a rigid one paired with itself
      :class:`~contactlab.errors.ParameterError`;
    * ``test_repr_eq_hash``: a rebuilt copy is equal with equal hash and repr; a copy with one
      parameter doubled is not equal;
    * ``test_bad_parameters_raise``: every declared parameter, set to each of
      :func:`bad_values` of its domain, raises :class:`~contactlab.errors.ParameterError`
      whose message names the parameter.

    Attributes
    ----------
    material : Material or None
        The instance under test (alternative to :meth:`make_material`).

    Examples
    --------
    >>> import contactlab as cl
    >>> class TestSteel(MaterialChecks):
    ...     material = cl.Elastic(E=210e9, nu=0.3)
    >>> TestSteel().test_bad_parameters_raise()
    """

    material: ClassVar[Any] = None

    def make_material(self) -> Any:
        """Return the material instance under test (default: the ``material`` attribute)."""
        if self.material is None:
            raise NotImplementedError(
                f"{type(self).__name__}: set the class attribute `material` or implement "
                "make_material().")
        return self.material

    def test_pair_moduli_positive_and_symmetric(self) -> None:
        import contactlab as cl
        from contactlab.errors import NotSupportedError, ParameterError
        m = self.make_material()
        for other in (cl.Elastic(E=1e9, nu=0.3), cl.Rigid(), _rebuild(m)):
            if m.is_viscoelastic:
                _expect_raise(NotSupportedError, cl.effective_moduli, m, other)
                _expect_raise(NotSupportedError, cl.effective_moduli, other, m)
                continue
            if isinstance(other, cl.Rigid) and isinstance(m, cl.Rigid):
                _expect_raise(ParameterError, cl.effective_moduli, m, other)
                continue
            ab, ba = cl.effective_moduli(m, other), cl.effective_moduli(other, m)
            for name in ("normal", "tangential", "torsional"):
                v = getattr(ab, name)
                assert math.isfinite(v) and v > 0, f"{m!r} with {other!r}: {name} modulus {v!r}"
                assert v == getattr(ba, name), f"{m!r} with {other!r}: {name} modulus not symmetric"
            assert ab.elastically_similar == ba.elastically_similar

    def test_repr_eq_hash(self) -> None:
        m = self.make_material()
        twin = _rebuild(m)
        assert twin == m and hash(twin) == hash(m) and repr(twin) == repr(m)
        assert type(m).__name__ in repr(m)
        other = _perturbed(m)
        if other is not None:
            assert other != m, f"{other!r} compares equal to {m!r}"

    def test_bad_parameters_raise(self) -> None:
        from contactlab.errors import ParameterError
        m = self.make_material()
        kwargs = _param_kwargs(m)
        for p in type(m).params:
            good = kwargs[p.name]
            for bad in bad_values(p.domain):
                value = [bad] * len(good) if isinstance(good, (list, tuple)) else bad
                err = _expect_raise(ParameterError, type(m), **{**kwargs, p.name: value})
                assert p.name in str(err), f"ParameterError for {p.name}={value!r} does not " \
                    f"name the parameter: {err}"


def _expect_raise(exc: type[BaseException], func: Any, *args: Any, **kwargs: Any) -> BaseException:
    try:
        func(*args, **kwargs)
    except exc as err:
        return err
    raise AssertionError(f"{getattr(func, '__name__', func)}(*{args!r}, **{kwargs!r}) did not raise "
                         f"{exc.__name__}")
