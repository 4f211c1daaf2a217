"""Conformance checks for profiles: :class:`ProfileChecks` and the independent transform."""
from __future__ import annotations

import itertools
from typing import Any, ClassVar

import numpy as np
from scipy import integrate

from . import tolerances as tol

__all__ = ["ProfileChecks", "independent_transform"]


def independent_transform(profile: Any, x: float, epsrel: float = 1e-12) -> float:
    """MDR transform of ``profile`` at one point by ``scipy.integrate.quad``.

    Evaluates the definition ``g(x) = |x| ∫_0^{|x|} f'(r)/sqrt(x²-r²) dr`` after the substitution
    ``r = |x| sin θ``, which removes the inverse-square-root singularity at ``r = |x|``:
    ``g(x) = |x| ∫_0^{π/2} f'(|x| sin θ) dθ``. The interval is split at ``θ = asin(b/|x|)`` for
    every slope jump ``b`` the profile declares (``breakpoints``, ``flat_radius``).

    Parameters
    ----------
    profile : Profile
        Any profile; only its public ``derivative`` (f') and domain declarations are used.
    x : float
        Coordinate, m.
    epsrel : float
        Relative tolerance passed to ``quad``.

    Returns
    -------
    float
        g(x), m.

    References
    ----------
    V. L. Popov, M. Heß, Method of Dimensionality Reduction in Contact Mechanics and Friction,
    Springer 2015, eq. (3.7). doi:10.1007/978-3-642-53876-6

    Examples
    --------
    >>> from contactlab.profiles import Paraboloid
    >>> round(independent_transform(Paraboloid(R=0.01), 1e-3) / (1e-3**2 / 0.01), 12)
    1.0
    """
    x = abs(float(x))
    if x == 0.0:
        return 0.0
    jumps = sorted({float(b) for b in (*profile.breakpoints, profile.flat_radius) if 0 < b < x})
    cuts = [0.0] + [float(np.arcsin(b / x)) for b in jumps] + [0.5 * np.pi]

    def fprime(theta: float) -> float:
        return float(profile.derivative(x * np.sin(theta)))

    total = 0.0
    for t0, t1 in itertools.pairwise(cuts):
        if t1 > t0:
            total += integrate.quad(fprime, t0, t1, epsabs=0.0, epsrel=epsrel, limit=200)[0]
    return x * total


class ProfileChecks:
    """Mixin of conformance tests for a :class:`~contactlab.profiles.Profile` subclass.

    Subclass it in a test module (class name starting with ``Test``) and implement
    :meth:`make_profile` (or set the class attribute ``profile``). pytest then collects:

    * ``test_height_broadcasts`` / ``test_g_broadcasts``: output shape equals input shape
      (scalar, 1D, 2D);
    * ``test_height_zero_on_axis``: f(0) = 0;
    * ``test_height_non_decreasing``: f non-decreasing over the probe radii;
    * ``test_g_matches_independent_quadrature``: g against :func:`independent_transform`;
    * ``test_inverse_transform_round_trip``: ``inverse_transform(r)`` against ``height(r)``;
    * ``test_force_increases_with_depth``: ``Contact.normal(depth=...)`` force strictly
      increasing;
    * ``test_depth_force_depth_round_trip``: ``normal(force=F).depth`` equals the depth that
      gave ``F``;
    * ``test_repr_eq_hash``: a rebuilt copy is equal with equal hash and repr; a copy with one
      parameter changed is not equal.

    Attributes
    ----------
    profile : Profile or None
        The instance under test (alternative to :meth:`make_profile`).
    length_scale : float
        Radial extent probed beyond the flat centre, m (default 1e-4 m, clipped to the
        profile's ``max_radius``/``wall_radius``). Override for profiles on other scales.
    E, nu : float
        Elastic body pressed by the profile (Pa, 1) in the contact checks.
    rtol_transform, rtol_inverse, rtol_round_trip : float
        Tolerances, see :mod:`contactlab.testing.tolerances`.

    Examples
    --------
    >>> from contactlab.profiles import Paraboloid
    >>> class TestParaboloid(ProfileChecks):
    ...     profile = Paraboloid(R=0.01)
    >>> TestParaboloid().test_g_matches_independent_quadrature()
    """

    profile: ClassVar[Any] = None
    length_scale: ClassVar[float] = 1e-4
    E: ClassVar[float] = 1e9
    nu: ClassVar[float] = 0.3
    #: fractions of the probed interval
    fractions: ClassVar[tuple[float, ...]] = (0.05, 0.2, 0.45, 0.7, 0.95)
    rtol_transform: ClassVar[float] = tol.TRANSFORM
    rtol_inverse: ClassVar[float] = tol.INVERSE
    rtol_round_trip: ClassVar[float] = tol.ROUND_TRIP

    # ------------------------------------------------------------------ hooks
    def make_profile(self) -> Any:
        """Return the profile instance under test (default: the ``profile`` attribute)."""
        if self.profile is None:
            raise NotImplementedError(
                f"{type(self).__name__}: set the class attribute `profile` or implement "
                "make_profile().")
        return self.profile

    def probe_radii(self, profile: Any) -> np.ndarray:
        """Radii (m) where height and transform are probed: ``[0, r_max)``.

        ``r_max = min(flat_radius + length_scale, max_radius, wall_radius)``.
        """
        r_max = min(profile.flat_radius + self.length_scale, profile.max_radius,
                    profile.wall_radius)
        return r_max * np.asarray(self.fractions)

    def contact_radii(self, profile: Any) -> np.ndarray:
        """Contact radii (m) for the depth checks: beyond the flat centre, inside the domain."""
        lo = profile.flat_radius
        hi = min(lo + self.length_scale, profile.max_radius)
        return lo + (hi - lo) * np.asarray(self.fractions)

    def probe_depths(self, profile: Any) -> np.ndarray:
        """Increasing depths (m): ``g`` at :meth:`contact_radii`, or, for a profile whose contact
        radius is fixed by a wall (flat punch), 1e-3 of the wall radius times ``fractions``."""
        if np.isfinite(profile.wall_radius):
            return 1e-3 * profile.wall_radius * np.asarray(self.fractions)
        return np.asarray(profile.g(self.contact_radii(profile)), dtype=float)

    def make_contact(self, profile: Any) -> Any:
        """The contact used by the force checks: ``profile`` on an elastic half-space."""
        import contactlab as cl
        return cl.Contact(profile, materials=(cl.Elastic(E=self.E, nu=self.nu), cl.Rigid()))

    # ------------------------------------------------------------------ geometry
    def test_height_broadcasts(self) -> None:
        p = self.make_profile()
        r = self.probe_radii(p)
        _check_broadcasting(p.height, r, "height")

    def test_g_broadcasts(self) -> None:
        p = self.make_profile()
        x = self.probe_radii(p)
        _check_broadcasting(p.g, x, "g")
        assert np.array_equal(p.g(-x), p.g(x)), "g(-x) != g(x): g must be even"

    def test_height_zero_on_axis(self) -> None:
        p = self.make_profile()
        assert float(p.height(0.0)) == 0.0, f"{p!r}: f(0) = {float(p.height(0.0))!r}, not 0"

    def test_height_non_decreasing(self) -> None:
        p = self.make_profile()
        r = np.linspace(0.0, float(self.probe_radii(p)[-1]), 257)
        f = p.height(r)
        assert np.all(np.isfinite(f)), f"{p!r}: non-finite heights"
        assert np.all(np.diff(f) >= 0), f"{p!r}: f decreases between probe radii"

    # ------------------------------------------------------------------ transform
    def test_g_matches_independent_quadrature(self) -> None:
        p = self.make_profile()
        x = self.probe_radii(p)
        got = np.asarray(p.g(x), dtype=float)
        expect = np.array([independent_transform(p, xi) for xi in x])
        _assert_close(got, expect, self.rtol_transform, f"{p!r}: g vs quad of its definition")
        assert np.all(np.diff(got) >= 0), f"{p!r}: g decreases (ring contact) at the probe radii"

    def test_inverse_transform_round_trip(self) -> None:
        p = self.make_profile()
        r = self.probe_radii(p)
        _assert_close(p.inverse_transform(r), p.height(r), self.rtol_inverse,
                      f"{p!r}: inverse_transform(r) vs height(r)")

    # ------------------------------------------------------------------ normal contact
    def test_force_increases_with_depth(self) -> None:
        p = self.make_profile()
        d = self.probe_depths(p)
        assert np.all(d > 0) and np.all(np.diff(d) > 0), f"{p!r}: probe depths {d!r} not increasing"
        state = self.make_contact(p).normal(depth=d)
        F = np.asarray(state.force, dtype=float)
        assert F.shape == d.shape
        assert np.all(F > 0) and np.all(np.diff(F) > 0), f"{p!r}: force {F!r} not increasing"

    def test_depth_force_depth_round_trip(self) -> None:
        p = self.make_profile()
        d = self.probe_depths(p)
        c = self.make_contact(p)
        back = c.normal(force=c.normal(depth=d).force).depth
        _assert_close(back, d, self.rtol_round_trip, f"{p!r}: depth -> force -> depth")

    # ------------------------------------------------------------------ identity
    def test_repr_eq_hash(self) -> None:
        p = self.make_profile()
        twin = _rebuild(p)
        assert twin == p and hash(twin) == hash(p) and repr(twin) == repr(p)
        assert type(p).__name__ in repr(p)
        other = _perturbed(p)
        if other is not None:
            assert other != p, f"{other!r} compares equal to {p!r}"


# ---------------------------------------------------------------------- helpers
def _check_broadcasting(func: Any, x: np.ndarray, what: str) -> None:
    flat = np.asarray(func(x), dtype=float)
    assert flat.shape == x.shape, f"{what}: shape {flat.shape} for input {x.shape}"
    grid = np.asarray(func(x.reshape(1, -1).repeat(2, axis=0)), dtype=float)
    assert grid.shape == (2, x.size), f"{what}: shape {grid.shape} for input (2, {x.size})"
    assert np.array_equal(grid[1], flat), f"{what}: a 2D input changes the values"
    one = np.asarray(func(float(x[2])))
    assert one.shape == (), f"{what}: shape {one.shape} for a scalar input"
    assert float(one) == flat[2], f"{what}: scalar and array evaluation differ"


def _assert_close(got: Any, expect: Any, rtol: float, what: str) -> None:
    got = np.asarray(got, dtype=float)
    expect = np.asarray(expect, dtype=float)
    scale = np.max(np.abs(expect)) if expect.size else 0.0
    bound = rtol * np.abs(expect) + tol.FLOOR * scale
    err = np.abs(got - expect)
    assert got.shape == expect.shape, f"{what}: shape {got.shape} != {expect.shape}"
    assert np.all(np.isfinite(got)), f"{what}: non-finite values {got!r}"
    assert np.all(err <= bound), (
        f"{what}: max relative error {np.max(err / np.maximum(np.abs(expect), 1e-300)):.3g} "
        f"> rtol {rtol:g}")


def _param_kwargs(obj: Any) -> dict[str, Any]:
    return {p.name: getattr(obj, p.name) for p in type(obj).params}


def _rebuild(obj: Any) -> Any:
    return type(obj)(**_param_kwargs(obj))


def _perturbed(obj: Any) -> Any:
    """A copy with the first positive scalar parameter doubled (None if there is none)."""
    kwargs = _param_kwargs(obj)
    for p in type(obj).params:
        value = kwargs[p.name]
        if p.domain == "positive" and isinstance(value, (int, float)) and not isinstance(value, bool):
            try:
                return type(obj)(**{**kwargs, p.name: 2.0 * value})
            except ValueError:
                continue      # doubling leaves the domain of a coupled parameter
    return None
