"""Writing behind the work: one background thread that runs writes in order, one at a time.

A cloud stage alternates work that holds Python's GIL (decompressing, numpy on a chunk) with
writes that release it (``ndarray.tofile``, lazrs' compression). :class:`WriteBehind` runs
each write on its own thread while the caller goes on with the next chunk. Conventions:

* **Order**: writes run in the order given; :meth:`WriteBehind.submit` first waits for the
  previous write, so at most one runs while the caller prepares the next (memory: one
  chunk more than writing in line).
* **Errors**: an exception of a write is raised in the caller's thread by the next
  :meth:`~WriteBehind.submit` or :meth:`~WriteBehind.wait`, never lost.
* The data handed to a write must not change until :meth:`~WriteBehind.wait` returns.
"""
from __future__ import annotations

from concurrent.futures import Future, ThreadPoolExecutor
from typing import Any, Callable, Optional


class WriteBehind:
    """Runs ``fn(*args)`` calls in order on one thread, one at a time (module docstring).

    Use as a context manager, or call :meth:`close`: it waits for the last write (raising
    its error) and ends the thread. :meth:`abandon` ends it without raising, for cleanup
    after an error.
    """

    def __init__(self, name: str = "roadsigns-write"):
        self._pool: Optional[ThreadPoolExecutor] = ThreadPoolExecutor(max_workers=1, thread_name_prefix=name)
        self._last: Optional[Future] = None

    def submit(self, fn: Callable[..., Any], *args: Any) -> None:
        """Wait for the previous write (raising its error), then start ``fn(*args)``."""
        self.wait()
        if self._pool is None:
            raise RuntimeError("WriteBehind is closed")
        self._last = self._pool.submit(fn, *args)

    def wait(self) -> None:
        """Wait for the write under way, if any; raise its error."""
        last, self._last = self._last, None
        if last is not None:
            last.result()

    def close(self) -> None:
        """Wait for the last write (raising its error) and end the thread."""
        try:
            self.wait()
        finally:
            self._shutdown()

    def abandon(self) -> None:
        """Wait for the write under way, ignore its outcome, and end the thread."""
        last, self._last = self._last, None
        if last is not None:
            last.exception()
        self._shutdown()

    def _shutdown(self) -> None:
        if self._pool is not None:
            self._pool.shutdown(wait=True)
            self._pool = None

    def __enter__(self) -> "WriteBehind":
        return self

    def __exit__(self, exc_type, exc, tb) -> None:
        if exc_type is None:
            self.close()
        else:
            self.abandon()
