"""Load paths: segments (ramp, hold, sinusoid, repeat, measured tables) and CSV input."""
from .base import GROUPS, QUANTITIES, UNITS, LoadPath, Samples, Segment
from .io import read_csv, write_csv
from .segments import Hold, Ramp, Repeat, Sinusoid, Table

__all__ = ["LoadPath", "Samples", "Segment", "Ramp", "Hold", "Sinusoid", "Repeat", "Table",
           "QUANTITIES", "GROUPS", "UNITS", "read_csv", "write_csv"]
