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
