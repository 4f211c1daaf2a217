"""Units in scene files: the grammar lives in :mod:`contactlab.numeric.units` (shared with the
CSV readers of profiles and load paths); this module re-exports it for scenes."""
from ..numeric.units import (DIMENSION_OF_SI_UNIT, SI_UNIT, UNITS, canonical_unit,
                             dimension_of_unit, format_quantity, parse_quantity, split_header,
                             unit_factor)

__all__ = ["UNITS", "DIMENSION_OF_SI_UNIT", "SI_UNIT", "parse_quantity", "format_quantity",
           "dimension_of_unit", "canonical_unit", "unit_factor", "split_header"]
