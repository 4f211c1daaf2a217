"""Spring state of a :class:`contactlab.effects.law.ContactLaw`, allocated per contact that needs
it: :class:`SpringPool`.

A contact runs on its MDR springs only once its normal load changes; in a granular packing most
contacts never do. The pool holds the spring rows of those contacts only: ``slot[c]`` is the row
of contact ``c`` (``-1``: not on springs), ``owner[s]`` the contact of row ``s``. Rows
``[0, used)`` are in use; the arrays grow geometrically (doubling) when a step switches more
contacts than they hold, and a contact that leaves its springs (separation, ``reset``) gives its
row back by moving the last row into the hole, so the rows in use stay dense. Results never
depend on which row a contact holds (contacts are independent), and the law's ``state`` gives
the spring state per contact (:meth:`SpringPool.full`), independent of the rows. Arrays of 4 MB
and more are anonymous memory maps in base pages (:func:`_mapped`: a switch of many contacts
writes them for the first time, and huge pages made that write stall; ``tracemalloc`` does not
count these maps).
"""
from __future__ import annotations

import mmap

import numpy as np

from ..params import check_memory

__all__ = ["SpringPool", "SPRING_FIELDS", "pool_row_bytes"]

#: the spring state per contact: name -> (dtype, per spring?)
SPRING_FIELDS = {"spr_cover": (np.float64, False), "spr_depth": (np.float64, False),
                 "spr_k": (np.int64, False), "spr_S": (np.float64, True),
                 "spr_tan": (np.float64, True), "spr_tor": (np.float64, True),
                 "spr_x_tan": (np.float64, False), "spr_x_tor": (np.float64, False)}
#: smallest number of rows allocated at the first switch
_MIN_ROWS = 64


def pool_row_bytes(springs: int) -> int:
    """Bytes of one row of the pool: 4 floats + an int64 + the owner (int32) + 3 floats per
    spring (44 + 24 springs)."""
    return 44 + 24 * int(springs)


#: arrays of the pool at least this large (bytes) are mapped from the operating system directly
_MAP_BYTES = 1 << 22


def _mapped(shape: tuple, dtype: np.dtype) -> np.ndarray:
    """An array for pool rows (contents undefined, as ``np.empty``): beyond :data:`_MAP_BYTES`
    an anonymous memory map of its own, in the operating system's base pages. numpy asks Linux
    for transparent huge pages for large arrays (``madvise``); where the kernel then compacts
    memory to find them, the first write into fresh rows stalls: measured on a 2-core VM, the
    first changing-load step of 10^6 contacts, all switching (428 MB of fresh rows), took
    1.24-1.36 s CPU with huge pages (0.93-1.02 s of it in the kernel) and 0.55-0.58 s in base
    pages; the later steps the same (180-219 ms against 199-217 ms, load 6). The map is
    released with the last array that views it."""
    dtype = np.dtype(dtype)
    nbytes = int(np.prod(shape)) * dtype.itemsize
    if nbytes < _MAP_BYTES:
        return np.empty(shape, dtype)
    buf = mmap.mmap(-1, nbytes)
    return np.frombuffer(buf, dtype).reshape(shape)


class SpringPool:
    """The spring rows of the contacts of a law that are on springs (module docstring).

    Parameters
    ----------
    size : int
        Contacts of the law.
    springs : int
        Springs per contact (> 0).
    """

    def __init__(self, size: int, springs: int) -> None:
        self.size = int(size)
        self.springs = int(springs)
        self.slot = np.full(self.size, -1, np.int32)
        self.used = 0
        self.owner = np.zeros(0, np.int32)
        self.rows = {k: np.zeros((0, self.springs) if per else 0, dt)
                     for k, (dt, per) in SPRING_FIELDS.items()}

    @property
    def capacity(self) -> int:
        """Rows allocated."""
        return int(self.owner.size)

    def on(self) -> np.ndarray:
        """Per contact: on its springs (a new bool array)."""
        return self.slot >= 0

    def reserve(self, more: int) -> None:
        """Room for ``more`` further rows: grow (doubling, rows in use copied) when needed; the
        new arrays are checked against the memory budget before they are allocated."""
        need = self.used + int(more)
        if need <= self.capacity:
            return
        cap = min(max(need, 2 * self.capacity, _MIN_ROWS), self.size)
        check_memory("ContactLaw.step()", float(cap) * pool_row_bytes(self.springs),
                     f"spring state of {cap} contacts on {self.springs} springs each")
        u = self.used
        owner = _mapped((cap,), np.dtype(np.int32))
        owner[:u] = self.owner[:u]
        self.owner = owner
        for k, v in self.rows.items():
            new = _mapped((cap, *v.shape[1:]), v.dtype)
            new[:u] = v[:u]
            self.rows[k] = new

    def assign(self, idx: np.ndarray) -> np.ndarray:
        """Rows for the contacts ``idx`` (not on springs), in their order after the rows in use;
        returns them (the rows' contents are the caller's to write)."""
        self.reserve(idx.size)
        s = np.arange(self.used, self.used + idx.size, dtype=np.int32)
        self.slot[idx] = s
        self.owner[s] = idx
        self.used += int(idx.size)
        return s

    def release(self, idx: np.ndarray) -> None:
        """The contacts ``idx`` leave their springs (those on them give their rows back)."""
        s = self.slot[idx]
        s = np.unique(s[s >= 0])
        if s.size == 0:
            return
        self.slot[self.owner[s]] = -1
        new_used = self.used - s.size
        holes = s[s < new_used]
        tail = np.arange(new_used, self.used, dtype=np.int32)
        movers = tail[~np.isin(tail, s)]            # rows in use beyond the new end
        if holes.size:
            self.owner[holes] = self.owner[movers]
            for v in self.rows.values():
                v[holes] = v[movers]
            self.slot[self.owner[holes]] = holes
        self.used = new_used

    def clear(self) -> None:
        """Every contact leaves its springs (the arrays are kept for reuse)."""
        self.slot[...] = -1
        self.used = 0

    def of(self, key: str, idx: np.ndarray) -> np.ndarray:
        """Field ``key`` of the contacts ``idx`` (all on springs), a copy."""
        return self.rows[key][self.slot[idx]]

    def full(self, key: str) -> np.ndarray:
        """Field ``key`` per contact (zeros for contacts not on springs): the law's state."""
        v = self.rows[key]
        out = np.zeros((self.size, *v.shape[1:]), v.dtype)
        u = self.used
        out[self.owner[:u]] = v[:u]
        return out

    def like(self, key: str) -> np.ndarray:
        """A zero-cost array of the shape and dtype of :meth:`full` (for checks)."""
        dt, per = SPRING_FIELDS[key]
        return np.broadcast_to(np.zeros((), dt), (self.size, self.springs) if per
                               else (self.size,))

    def load(self, on: np.ndarray, fields: dict) -> None:
        """Replace the pool by the per-contact arrays ``fields`` of the contacts ``on``."""
        self.clear()
        idx = np.flatnonzero(on)
        s = self.assign(idx)
        for k in SPRING_FIELDS:
            self.rows[k][s] = fields[k][idx]
