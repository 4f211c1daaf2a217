"""Spring state of a :class:`contactlab.effects.law.ContactLaw`, allocated per contact that needs
it: :class:`SpringPool`; and the law's memory count (:func:`law_memory`), checked against the
memory budget before its arrays are allocated.

A contact runs on its MDR springs only once its normal load changes; in a granular packing most
contacts never do. The pool holds the spring rows of those contacts only: ``slot[c]`` is the row
of contact ``c`` (``-1``: not on springs), ``owner[s]`` the contact of row ``s``. Rows
``[0, used)`` are in use; the arrays grow geometrically (doubling) when a step switches more
contacts than they hold, and a contact that leaves its springs (separation, ``reset``) gives its
row back by moving the last row into the hole, so the rows in use stay dense. Results never
depend on which row a contact holds (contacts are independent), and the law's ``state`` gives
the spring state per contact (:meth:`SpringPool.full`), independent of the rows. Arrays of 4 MB
and more are anonymous private memory maps in base pages, the rows about to be written faulted
in by one call (:func:`_mapped`: a switch of many contacts writes them for the first time, and
huge pages made that write stall; ``tracemalloc`` does not count these maps).
"""
from __future__ import annotations

import ctypes
import mmap
import sys
import threading
from collections.abc import Mapping
from typing import Any

import numpy as np

from ..params import check_memory

__all__ = ["SpringPool", "SPRING_FIELDS", "OLD_SPRING_FIELDS", "pool_row_bytes", "upgraded_state",
           "law_memory", "law_spring_memory"]

#: the spring state per contact: name -> (dtype, per spring?). The cells' normal integrals of
#: the last step are not stored: they follow from its depth ``spr_depth``, radius ``spr_a`` and
#: the cover (recomputed by the same expressions, the same bits), 16 springs x 8 B less per row
SPRING_FIELDS = {"spr_cover": (np.float64, False), "spr_depth": (np.float64, False),
                 "spr_a": (np.float64, False), "spr_k": (np.int64, False),
                 "spr_tan": (np.float64, True), "spr_tor": (np.float64, True),
                 "spr_x_tan": (np.float64, False), "spr_x_tor": (np.float64, False)}
#: the per-spring cell integrals a state saved before ``spr_a`` replaced them holds
OLD_SPRING_FIELDS = ("spr_S",)
#: smallest number of rows allocated at the first switch
_MIN_ROWS = 64


def pool_row_bytes(springs: int) -> int:
    """Bytes of one row of the pool: 5 floats + an int64 + the owner (int32) + 2 floats per
    spring (52 + 16 springs: 308 B at 16 springs)."""
    return 52 + 16 * int(springs)


#: bytes per contact held by a law (counted from its arrays, equal to tracemalloc's count):
#: 7 parameters, the force factor of the normal contact and mu E*, the reference depth, per channel
#: 3 floats + an int64 depth + 2 flag bytes; per turning point of memory 2 channels x (X, Y);
#: with springs the row index (int32) of the spring pool; plus a step's 8 float and 2 flag
#: bytes of results (the arrays a step returns, or ``out``) and 3 scalar inputs broadcast per
#: contact. The spring rows themselves (52 + 16 springs bytes,
#: :func:`~contactlab.effects.law_pool.pool_row_bytes`) are allocated only for contacts that
#: switch onto their springs (:class:`~contactlab.effects.law_pool.SpringPool`)
_PER_CONTACT, _PER_LEVEL, _PER_SPRINGS, _PER_STEP = 148, 32, 4, 90
#: float64 values per contact on springs in a step of the numpy path (temporaries; measured
#: 20-21 per spring): the compiled step has none
_NUMPY_CONTACT, _NUMPY_SPRING_STEP = 32, 24


def law_memory(size: int, memory: int, springs: int, on_springs: int = 0) -> float:
    """Memory of a :class:`~contactlab.effects.law.ContactLaw`'s state and of one step's
    results, bytes (checked against the memory budget, :func:`contactlab.set_memory_budget`,
    before it is allocated):
    ``size × (148 + 32 memory + 4 [springs > 0] + 90)``, 498 B per contact at the defaults,
    plus ``on_springs × (52 + 16 springs)`` for the contacts on their springs (308 B each at
    the default 16 springs; allocated when they switch, checked then)."""
    per = _PER_CONTACT + _PER_LEVEL * memory + _PER_STEP
    if springs:
        per += _PER_SPRINGS
    return float(size) * per + (float(on_springs) * pool_row_bytes(springs) if springs else 0.0)


def law_spring_memory(n_contacts: int, springs: int) -> float:
    """Estimated peak temporaries of a numpy step with ``n_contacts`` contacts on springs,
    bytes (the compiled step allocates none)."""
    return 8.0 * float(n_contacts) * (_NUMPY_CONTACT + _NUMPY_SPRING_STEP * springs)


#: arrays of the pool at least this large (bytes) are mapped from the operating system directly
_MAP_BYTES = 1 << 22


#: ``madvise`` advice that faults a range in at once, writeable (Linux >= 5.14, value 23;
#: Python's ``mmap`` names it from 3.13 on); None elsewhere
_MADV_POPULATE_WRITE = getattr(mmap, "MADV_POPULATE_WRITE",
                               23 if sys.platform.startswith("linux") else None)


_LIBC: list = []


def _libc_madvise():
    """The C library's ``madvise`` through ctypes (which lets go of the GIL during the call;
    Python's ``mmap.madvise`` holds it), or None where it is not found."""
    if not _LIBC:
        try:
            f = ctypes.CDLL(None, use_errno=True).madvise
            f.argtypes = [ctypes.c_void_p, ctypes.c_size_t, ctypes.c_int]
            f.restype = ctypes.c_int
        except (OSError, AttributeError, TypeError):    # pragma: no cover - not POSIX
            f = None
        _LIBC.append(f)
    return _LIBC[0]


def _populate(buf: mmap.mmap, arr: np.ndarray, used: int, threads: bool, advice: int) -> None:
    """Fault in the first ``used`` bytes of the map ``buf`` (viewed by ``arr``) by one
    ``madvise`` (``advice``: ``MADV_POPULATE_WRITE``); ``threads``: its two halves at once,
    the second on a thread of its own (measured on a 2-core VM, 428 MB: 79-97 ms wall against
    149-152 ms in one call, the same CPU time). Where the advice fails the pages fault in on
    the first write."""
    f = _libc_madvise() if threads else None
    if f is None:
        try:
            buf.madvise(advice, 0, used)
        except OSError:                 # not supported here: faulted in on the first write
            pass
        return
    half = used // 2 // mmap.PAGESIZE * mmap.PAGESIZE
    base = arr.ctypes.data              # the map's start: page-aligned
    t = threading.Thread(target=f, args=(base + half, used - half, advice))
    t.start()
    f(base, half, advice)
    t.join()


def _mapped(shape: tuple, dtype: np.dtype, fill: int = -1, threads: bool = False) -> np.ndarray:
    """An array for pool rows, zeros (+0; a fresh map is zero-filled): beyond :data:`_MAP_BYTES`
    an anonymous private memory map of its own in the operating system's base pages, its first
    ``fill`` entries (along the first axis; all for -1) faulted in by one ``madvise`` call. A
    switch of many contacts writes fresh rows; measured on a 2-core VM, 428 MB of fresh rows
    (10^6 contacts at 16 springs) cost, CPU: a shared map (Python's default) written page by
    page 246-257 ms, a private one 178-183 ms, a private one populated by
    ``MADV_POPULATE_WRITE`` (no fault per page) 138-163 ms plus 17-23 ms for the write;
    transparent huge pages (numpy's request for large arrays, or ``MADV_HUGEPAGE``) 44-68 ms
    when the kernel's free huge pages are memory the VM's host has backed already, but
    0.7-1.4 s when they are not (no compaction counted: the host backs a VM's memory on its
    first touch, and the kernel hands out huge pages from memory never touched more often
    than base pages, which it recycles), unpredictably from one process to the next, so they
    are not asked for. Where the advice is not known (older kernels, other systems) the pages
    fault in on the first write. The map is released with the last array that views it."""
    dtype = np.dtype(dtype)
    nbytes = int(np.prod(shape)) * dtype.itemsize
    if nbytes < _MAP_BYTES:
        return np.zeros(shape, dtype)
    flags = getattr(mmap, "MAP_PRIVATE", None)
    buf = (mmap.mmap(-1, nbytes) if flags is None
           else mmap.mmap(-1, nbytes, flags=flags | mmap.MAP_ANONYMOUS))
    used = nbytes if fill < 0 else nbytes // shape[0] * min(int(fill), shape[0])
    arr = np.frombuffer(buf, dtype).reshape(shape)
    if used and _MADV_POPULATE_WRITE is not None and hasattr(buf, "madvise"):
        _populate(buf, arr, used, threads, _MADV_POPULATE_WRITE)
    return arr


class SpringPool:
    """The spring rows of the contacts of a law that are on springs (module docstring).

    Parameters
    ----------
    size : int
        Contacts of the law.
    springs : int
        Springs per contact (> 0).
    reserve : int
        Rows allocated (and their pages faulted in) right away: switches of up to that many
        contacts allocate nothing.
    threads : bool
        Fault the reserved rows in on two threads.
    """

    def __init__(self, size: int, springs: int, reserve: int = 0, threads: bool = False) -> None:
        self.size = int(size)
        self.springs = int(springs)
        self.slot = np.full(self.size, -1, np.int32)
        self.used = 0
        #: per channel ("tan", "tor"): the elements of the cells beyond a row's edge cell may
        #: not all be +0 (a spring step did not drive the channel, or the rows were loaded
        #: from a state), so the channel's next driven step writes +0 to all of them; else
        #: only to those up to the last step's edge cell (the others are +0 already)
        self.stale = {"tan": False, "tor": False}
        #: rows from ``clean`` on hold +0 in every element (zeros since their arrays were
        #: allocated: never written): a switch onto such a row need not write +0 beyond its
        #: edge cell (the compiled first step then leaves the cache lines of those cells alone)
        self.clean = 0
        self.owner = np.zeros(0, np.int32)
        self.rows = {k: np.zeros((0, self.springs) if per else 0, dt)
                     for k, (dt, per) in SPRING_FIELDS.items()}
        if reserve > 0:
            self.reserve(reserve, threads)

    @property
    def capacity(self) -> int:
        """Rows allocated."""
        return int(self.owner.size)

    def on(self) -> np.ndarray:
        """Per contact: on its springs (a new bool array)."""
        return self.slot >= 0

    def reserve(self, more: int, threads: bool = False) -> None:
        """Room for ``more`` further rows: grow (doubling, rows in use copied) when needed; the
        new arrays are checked against the memory budget before they are allocated
        (``threads``: their rows about to be written faulted in by two threads)."""
        need = self.used + int(more)
        if need <= self.capacity:
            return
        cap = min(max(need, 2 * self.capacity, _MIN_ROWS), self.size)
        check_memory("ContactLaw.step()", float(cap) * pool_row_bytes(self.springs),
                     f"spring state of {cap} contacts on {self.springs} springs each")
        u = self.used
        owner = _mapped((cap,), np.dtype(np.int32), need, threads)
        owner[:u] = self.owner[:u]
        self.owner = owner
        for k, v in self.rows.items():
            new = _mapped((cap, *v.shape[1:]), v.dtype, need, threads)
            new[:u] = v[:u]
            self.rows[k] = new
        self.clean = u                  # the rows beyond those copied are zeros

    def assign(self, idx: np.ndarray) -> np.ndarray:
        """Rows for the contacts ``idx`` (not on springs), in their order after the rows in use;
        returns them (the rows' contents are the caller's to write)."""
        self.reserve(idx.size)
        s = np.arange(self.used, self.used + idx.size, dtype=np.int32)
        self.slot[idx] = s
        self.owner[s] = idx
        self.take(idx.size)
        return s

    def take(self, count: int) -> None:
        """The ``count`` rows after those in use are in use now, written (or about to be) by
        the caller: :attr:`used` and :attr:`clean` past them."""
        self.used += int(count)
        self.clean = max(self.clean, self.used)

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
        """Replace the pool by the per-contact arrays ``fields`` of the contacts ``on``
        (both channels :attr:`stale`: the rows come from outside)."""
        self.clear()
        self.stale = {"tan": True, "tor": True}
        idx = np.flatnonzero(on)
        s = self.assign(idx)
        for k in SPRING_FIELDS:
            self.rows[k][s] = fields[k][idx]


def upgraded_state(value: Any, law: Any) -> Any:
    """A law's state as saved before the spring rows dropped their per-spring cell integrals
    (``spr_S``, replaced by the radius ``spr_a`` of the row's last step) in the current form:
    ``spr_a`` is the contact radius at the stored ``spr_depth`` (``law._radius``), ``spr_S``
    dropped; anything else (a current state, no springs, a dict the setter refuses) as given.
    From such a state the law continues at the same cells, edge cells and elements; the
    radius a force-controlled step found may differ from the one recomputed from its depth by
    rounding, so the first step's contact weights of the cells between the old and new edge
    may move by rounding too (a depth-controlled Paraboloid run: the same bits)."""
    if (law._pool is None or not isinstance(value, Mapping) or "spr_a" in value
            or not all(k in value for k in (*OLD_SPRING_FIELDS, "spr_on", "spr_depth"))):
        return value
    try:
        on = np.asarray(value["spr_on"]).astype(bool)
        depth = np.asarray(value["spr_depth"], dtype=float)
        with np.errstate(all="ignore"):
            a = np.where(on, law._radius(np.where(on, np.abs(depth), 0.0), slice(None)), 0.0)
    except (TypeError, ValueError, IndexError):     # shapes and the like: the setter names them
        return value
    new = {k: v for k, v in value.items() if k not in OLD_SPRING_FIELDS}
    new["spr_a"] = a
    return new
