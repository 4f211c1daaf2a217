"""Every foundation path test runs with each backend of the compiled foundation kernels:
numpy (the reference) and numba (extra ``fast``; skipped when numba is not installed)."""
import pytest

from contactlab.foundation import _compiled


@pytest.fixture(autouse=True, params=["numpy", "numba"])
def foundation_backend(request):
    if request.param not in _compiled.available():
        pytest.skip("numba is not installed (extra 'fast')")
    _compiled.set_backend(request.param)
    yield request.param
    _compiled.set_backend(None)


def pytest_collection_modifyitems(items):
    """The foundation tests check the MDR springs against the MDR model's own closed forms and
    against each other, often twisted far beyond the model's validity against the exact solution:
    the ValidityWarning that simulate(method="mdr") then emits (effects.path.warn_mdr_path, tested
    in tests/unit/effects/test_mdr_path_warning.py) is expected here and ignored."""
    for item in items:
        if "tests/unit/foundation/" in str(item.fspath).replace("\\", "/"):
            item.add_marker(pytest.mark.filterwarnings(
                "ignore:MDR torsion springs outside their validity:"
                "contactlab.errors.ValidityWarning"))
