"""Parameter specifications, the checks every public constructor runs, and the memory and time
budgets.

A :class:`Param` says what a parameter is (name, symbol, unit, domain, a typical range); the
``check_*`` helpers turn a user value into a float or array and raise
:class:`~contactlab.errors.ParameterError` naming the parameter, the value and the allowed set
(:mod:`contactlab.params.checks`); :func:`check_memory` and :func:`check_time` hold a computation
a user sized against the budgets (:mod:`contactlab.params.budgets`).
"""
from __future__ import annotations

from .budgets import (DEFAULT_MEMORY_BUDGET, DEFAULT_TIME_BUDGET, MEMORY_BUDGET_ENV,
                      TIME_BUDGET_ENV, check_memory, check_time, memory_budget,
                      set_memory_budget, set_time_budget, time_budget)
from .checks import (CACHE_KEYS, LENGTH_BOUNDS, MODULUS_BOUNDS, PLAIN_TYPES, QUANTITY_UNITS,
                     FieldsEqual, Param, ParamIdentity, as_checked_array, check_bounds,
                     as_float_array, as_real, broadcast_inputs, check_count,
                     check_finite, check_flag, check_in_range, check_positive,
                     check_result_finite, exactly_one, name_list, scalar_or_array, step_indices,
                     to_si, to_si_values, values_equal, without_caches)

__all__ = ["Param", "ParamIdentity", "LENGTH_BOUNDS", "MODULUS_BOUNDS", "check_bounds",
           "check_positive", "check_finite", "check_in_range",
           "as_float_array", "as_real", "as_checked_array", "broadcast_inputs", "check_count",
           "check_result_finite", "exactly_one", "scalar_or_array", "step_indices", "check_flag",
           "name_list", "memory_budget", "set_memory_budget", "check_memory",
           "DEFAULT_MEMORY_BUDGET", "MEMORY_BUDGET_ENV", "time_budget", "set_time_budget",
           "check_time", "DEFAULT_TIME_BUDGET", "TIME_BUDGET_ENV", "values_equal", "FieldsEqual",
           "QUANTITY_UNITS", "to_si", "to_si_values", "PLAIN_TYPES", "CACHE_KEYS",
           "without_caches"]
