"""A profile plugin installed as a package (tests/plugins/contactlab_example_plugin, installed by
CI) is usable by name from a scene file, with numbers matching the equivalent built-in profile."""
from __future__ import annotations

import importlib.util

import numpy as np
import pytest

import contactlab as cl
from contactlab.scene import Scene

from tests.tolerances import QUADRATURE

pytestmark = pytest.mark.skipif(
    importlib.util.find_spec("contactlab_example_plugin") is None,
    reason="install with: pip install ./tests/plugins/contactlab_example_plugin")

SCENE = """
[profile]
type = "quartic"
c = 1e9

[materials]
body1 = { type = "elastic", E = "70 GPa", nu = 0.33 }
body2 = { type = "rigid" }

[[load_path]]
ramp = { force = "20 N", steps = 5 }

[outputs]
series = ["force", "depth", "radius"]
"""


def test_plugin_profile_by_name_in_a_scene():
    cl.registry.registry.refresh()
    res = Scene.loads(SCENE).run()
    ref = cl.Contact(cl.profiles.PowerLaw(c=1e9, n=4),
                     materials=(cl.Elastic(E=70e9, nu=0.33), cl.Rigid())).normal(
        force=np.asarray(res.series["force"]))
    # the plugin defines only f(r): its transform is the quadrature route
    assert np.allclose(res.series["radius"], ref.radius, rtol=QUADRATURE, atol=0)
    assert np.allclose(res.series["depth"], ref.depth, rtol=QUADRATURE, atol=0)
