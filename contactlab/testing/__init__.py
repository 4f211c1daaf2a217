"""Conformance checks that every profile and material, built-in or plugin, can run, and that
every result type follows the result protocol (:class:`ResultChecks`).

Subclass a mixin in a test module, give it an instance, and pytest collects its ``test_*``
methods (the pattern of astropy's model tests and PyBaMM's submodel tests)::

    from contactlab.testing import ProfileChecks

    class TestQuartic(ProfileChecks):
        def make_profile(self):
            return Quartic(c=1e9)

The mixins use only the public API (``profile.height``, ``profile.derivative``, ``profile.g``,
``profile.inverse_transform``, :class:`contactlab.Contact`, :func:`contactlab.effective_moduli`)
and compare against independent computations (``scipy.integrate.quad`` of the transform's
definition). They need no pytest at import; any test runner that collects ``test_*`` methods of
classes works. Tolerances are in :mod:`contactlab.testing.tolerances`, each with its reason, and
can be overridden per subclass.
"""
from .materials import MaterialChecks, bad_values
from .profiles import ProfileChecks, independent_transform
from .results import RESULT_MODULES, ResultChecks, result_types
from .typical import typical_instance

__all__ = ["ProfileChecks", "MaterialChecks", "ResultChecks", "independent_transform",
           "typical_instance", "bad_values", "result_types", "RESULT_MODULES"]
