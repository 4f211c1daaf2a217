"""Conformance checks for result types: :class:`ResultChecks` and :func:`result_types`."""
from __future__ import annotations

import importlib
import math
import os
import tempfile
import warnings
from dataclasses import fields, is_dataclass
from typing import Any, ClassVar

import numpy as np

__all__ = ["ResultChecks", "result_types", "RESULT_MODULES"]

#: modules whose dataclasses with a ``meta`` field are result types (every one must implement
#: the result protocol, :class:`contactlab.effects._protocol.Result`)
RESULT_MODULES = ("contactlab.effects.normal", "contactlab.effects.adhesion",
                  "contactlab.effects.tangential", "contactlab.effects.torsion",
                  "contactlab.effects.viscoelastic", "contactlab.effects.path",
                  "contactlab.effects.fretting", "contactlab.effects.wear",
                  "contactlab.effects.law", "contactlab.effects.stress",
                  "contactlab.effects.stress_tangential", "contactlab.effects.stress_history",
                  "contactlab.scene.run",
                  "contactlab.fit.result")


def result_types() -> list[type]:
    """Every result type of contactlab: the dataclasses with a ``meta`` field defined in
    :data:`RESULT_MODULES` (a new result type is found here whether or not it follows the
    protocol, so a test over this list fails for one that does not)."""
    out = []
    for name in RESULT_MODULES:
        mod = importlib.import_module(name)
        for obj in vars(mod).values():
            if (isinstance(obj, type) and obj.__module__ == name and is_dataclass(obj)
                    and any(f.name == "meta" for f in fields(obj))):
                out.append(obj)
    return out


def _read(path: str) -> tuple[list[str], list[str], dict[str, np.ndarray]]:
    """Comment lines, header cells and columns of a CSV written by ``to_csv`` (read with the
    package's own table reader, which skips ``#`` lines)."""
    from ..numeric.tables import read_columns
    with open(path, newline="") as fh:
        text = fh.read().splitlines()
    comments = [line for line in text if line.startswith("#")]
    header = next(line for line in text if not line.startswith("#")).split(",")
    _, cols = read_columns(path, dimension=lambda n: "ignore")
    return comments, header, cols


class ResultChecks:
    """Mixin of conformance tests for a result object (the result protocol).

    Subclass it in a test module (class name starting with ``Test``) and implement
    :meth:`make_result` (or set the class attribute ``result``). pytest then collects:

    * ``test_protocol``: ``to_dict`` gives a dict; ``notes`` is a tuple of str; ``model_error``
      is >= 0 and never NaN (``inf`` only with a basis saying no bound is known), the largest of
      ``model_errors``; ``model_error_basis`` is text; ``units`` names a unit for every column;
    * ``test_to_csv_round_trip``: ``to_csv`` writes ``name [unit]`` headers with the class's
      units, values that read back bit for bit through the package's CSV reader, and every note
      as a ``# notes: ...`` line;
    * ``test_to_csv_never_overwrites``: a second ``to_csv`` to the same path raises
      :class:`~contactlab.errors.ParameterError` and leaves the file; ``overwrite=True``
      replaces it;
    * ``test_to_dataframe_attrs`` (with pandas): the same columns, units, notes and model error
      in ``df.attrs``;
    * ``test_cite``: ``result.cite()`` is :func:`contactlab.cite` of the result;
    * ``test_plot`` (``plots = True``, with matplotlib): ``plot()`` draws without error;
    * ``test_exact_route`` (``exact = True``): ``model_error == 0.0``.

    Attributes
    ----------
    result : object or None
        The instance under test (alternative to :meth:`make_result`).
    plots : bool
        The type has a ``plot`` method to check.
    exact : bool or None
        The result comes from an exact route (model error 0), an approximate one (False: model
        error > 0), or either (None).
    """

    result: ClassVar[Any] = None
    plots: ClassVar[bool] = False
    exact: ClassVar[bool | None] = None
    # the made result, per test class (set on first use: declared only, so that a subclass
    # never sees its parent's in its own __dict__)
    _cached: ClassVar[Any]

    def make_result(self) -> Any:
        """The result under test (default: the class attribute ``result``)."""
        return self.result

    def _result(self) -> Any:
        cache = type(self).__dict__.get("_cached")
        if cache is None:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                cache = self.make_result()
            type(self)._cached = cache
        return cache

    def test_protocol(self) -> None:
        from ..effects._protocol import Result
        r = self._result()
        assert isinstance(r, Result), f"{type(r).__name__} does not implement the protocol"
        assert isinstance(r.to_dict(), dict)
        assert isinstance(r.notes, tuple) and all(isinstance(n, str) for n in r.notes)
        me = np.asarray(r.model_error, float)
        assert not np.any(np.isnan(me)) and np.all(me >= 0)
        errs = r.model_errors
        if errs:
            worst = max(float(np.max(np.asarray(v, float))) for v in errs.values())
            assert float(np.max(me)) == worst
        else:
            assert r.model_error == 0.0
        if np.any(np.isinf(me)):
            assert "no" in r.model_error_basis and "bound" in r.model_error_basis
        assert isinstance(r.model_error_basis, str) and r.model_error_basis
        cols = r._columns()
        missing = [c for c in cols if c not in type(r).units]
        assert not missing, f"{type(r).__name__}.units lacks {missing}"

    def test_to_csv_round_trip(self) -> None:
        r = self._result()
        cols = r._columns()
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "result.csv")
            assert os.fspath(r.to_csv(path)) == path
            comments, header, back = _read(path)
        units = type(r).units
        assert header == [f"{k} [{units[k]}]" if units.get(k) else k for k in cols]
        for k, v in cols.items():
            np.testing.assert_array_equal(back[k], np.asarray(v, float).ravel())
        for note in r.notes:
            assert f"# notes: {' '.join(note.split())}" in comments
        if float(np.max(np.asarray(r.model_error, float))) > 0:
            assert any(c.startswith("# model_error: ") for c in comments)

    def test_to_csv_never_overwrites(self) -> None:
        from ..errors import ParameterError
        r = self._result()
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "result.csv")
            with open(path, "w") as fh:
                fh.write("not mine\n")
            try:
                r.to_csv(path)
            except ParameterError as err:
                assert "overwrite=True" in str(err)
            else:
                raise AssertionError("to_csv() replaced an existing file")
            with open(path) as fh:
                assert fh.read() == "not mine\n"
            r.to_csv(path, overwrite=True)
            with open(path) as fh:
                assert fh.read() != "not mine\n"

    def test_to_dataframe_attrs(self) -> None:
        try:
            import pandas  # noqa: F401
        except ImportError:        # pragma: no cover - pandas is an optional extra
            return
        r = self._result()
        df = r.to_dataframe()
        cols = r._columns()
        assert list(df.columns) == list(cols)
        assert df.attrs["units"] == {k: type(r).units[k] for k in cols}
        assert df.attrs["notes"] == list(r.notes)
        me = float(np.max(np.asarray(r.model_error, float)))
        assert df.attrs["model_error"] == (me if math.isfinite(me) else "inf")

    def test_cite(self) -> None:
        from ..citations import cite
        r = self._result()
        try:
            want = cite(r, format="text", file=None)
        except Exception as err:      # noqa: BLE001 - a result whose sources are not recorded
            try:
                r.cite(format="text", file=None)
            except type(err):
                return
            raise AssertionError("cite() differs from contactlab.cite()") from None
        assert r.cite(format="text", file=None) == want

    def test_plot(self) -> None:
        if not self.plots:
            return
        try:
            import matplotlib
        except ImportError:        # pragma: no cover - matplotlib is an optional extra
            return
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        r = self._result()
        out = r.plot() if not callable(getattr(r, "figure", None)) else r.figure()
        assert out is not None
        plt.close("all")

    def test_exact_route(self) -> None:
        if self.exact is None:
            return
        r = self._result()
        if self.exact:
            assert r.model_error == 0.0 and r.model_errors == {}
        else:
            assert float(np.max(np.asarray(r.model_error, float))) > 0
