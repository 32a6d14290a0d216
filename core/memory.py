"""Memory the process has freed, given back to the system.

The cloud stages allocate and free arrays of tens of megabytes block after block. glibc's
``malloc`` serves an allocation above its mmap threshold (128 kB at start) from a fresh
mapping, but after the first such block is freed it raises the threshold to that size (up
to 32 MB), so later arrays come from its heaps and arenas, and ``free`` keeps their pages
unless they lie at the top of a heap. A stage's resident memory then grows with the number
of blocks it has worked through, not with a block's size: ``projectdetections`` peaked at
837 MB on the 9.2 km drive against 657 MB on 1 km (671 MB on 9.2 km with a fixed
threshold). ``malloc_trim(0)`` returns the free pages of every arena (glibc 2.8 and later).

:func:`release_freed_memory` is called after each block (:func:`.drivewindows.map_in_order`)
and when an algorithm ends. Where the C library is not glibc it does nothing.
"""
from __future__ import annotations

import ctypes
import ctypes.util
import functools
import sys
from typing import Callable, Optional


@functools.lru_cache(maxsize=None)
def _malloc_trim() -> Optional[Callable[[int], int]]:
    """glibc's ``malloc_trim``, or None (another C library, or not Linux); looked up once."""
    if not sys.platform.startswith("linux"):
        return None
    try:
        trim = ctypes.CDLL(ctypes.util.find_library("c") or "libc.so.6").malloc_trim
    except (OSError, AttributeError):   # musl and others have no malloc_trim
        return None
    trim.argtypes, trim.restype = [ctypes.c_size_t], ctypes.c_int
    return trim


def release_freed_memory() -> bool:
    """Give the free pages of the C heap back to the system; True when glibc did so (some
    memory was released), False when nothing was freed or it cannot be done here."""
    trim = _malloc_trim()
    return bool(trim(0)) if trim is not None else False
