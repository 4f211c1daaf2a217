"""``import contactlab`` stays light: the sweep extras load only when a sweep runs."""
import subprocess
import sys


def test_import_contactlab_loads_no_sweep_extra():
    code = ("import sys, contactlab; assert callable(contactlab.sweep); "
            "print(sorted(m for m in ('pandas', 'pyarrow', 'xarray', 'dask', 'distributed', "
            "'tqdm') if m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "[]"
