"""``import contactlab`` loads no heavy module it does not need at once (issue: start-up time).

scipy.special alone costs ~0.1 s of import; sympy, matplotlib, pandas and dask more. Each is
imported on first use inside the function that needs it. Run in a fresh interpreter so that
nothing this test session imported earlier can hide a regression.
"""
from __future__ import annotations

import json
import subprocess
import sys

import numpy as np
import pytest

HEAVY = ("scipy.special", "scipy.integrate", "sympy", "matplotlib", "pandas", "pyarrow",
         "xarray", "dask", "distributed", "tqdm", "contactlab.sweeps", "multiprocessing",
         "concurrent.futures")


@pytest.fixture(scope="module")
def loaded_after_import() -> set[str]:
    code = ("import json, sys; import contactlab; "
            f"print(json.dumps([m for m in {list(HEAVY)!r} if m in sys.modules]))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    return set(json.loads(out.stdout.strip().splitlines()[-1]))


@pytest.mark.parametrize("module", HEAVY)
def test_heavy_module_not_imported_with_contactlab(loaded_after_import: set[str], module: str) -> None:
    assert module not in loaded_after_import, f"import contactlab loads {module}"


def test_lazy_top_level_names_resolve() -> None:
    import contactlab
    from contactlab import sweeps
    assert contactlab.sweep is sweeps.sweep
    assert contactlab.fretting_map_sweep is sweeps.fretting_map_sweep
    assert {"sweep", "fretting_map_sweep"} <= set(dir(contactlab))
    with pytest.raises(AttributeError, match="no_such_name"):
        contactlab.no_such_name


def test_wear_operators_import_scipy_special_on_first_use() -> None:
    """The lazily imported ``ellipk`` still serves the wear operators (not a stubbed import)."""
    from contactlab.physics import wear
    ops = wear.operators(1e-3, 8)
    assert ops and all(np.all(np.isfinite(np.asarray(v, float))) for v in ops.values())
