"""Build a typical instance of a registered class from its declared ``Param.typical`` ranges."""
from __future__ import annotations

import math
from typing import Any

__all__ = ["typical_instance"]


def typical_instance(cls: type[Any]) -> Any:
    """Instantiate ``cls`` with the centre of each parameter's typical range.

    Parameters
    ----------
    cls : type
        A profile or material class whose ``params`` are scalar.

    Returns
    -------
    object
        ``cls(**{p.name: centre})``: the geometric mean of a positive range, the arithmetic
        mean otherwise.

    Raises
    ------
    TypeError
        If the class takes a non-scalar parameter (a table, a list of terms): write the
        instance by hand instead.

    Examples
    --------
    >>> from contactlab.profiles import Paraboloid
    >>> typical_instance(Paraboloid)
    Paraboloid(R=0.001)
    """
    kwargs = {}
    for p in cls.params:
        lo, hi = (float(v) for v in p.typical)
        if lo > 0 and hi > 0:
            kwargs[p.name] = float(f"{math.sqrt(lo * hi):.6g}")
        else:
            kwargs[p.name] = 0.5 * (lo + hi)
    return cls(**kwargs)
