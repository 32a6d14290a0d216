"""Exceptions and the progress/cancel protocol shared by the engine.

Core code never imports qgis; the Processing adapters turn :class:`InputError` into a
``QgsProcessingException`` (translating ``template`` with ``tr``) and pass a
:class:`Progress` that forwards to ``QgsProcessingFeedback``. Log messages are
:class:`Message` s: English text that keeps its template and fields, which the adapters
translate the same way.
"""
from __future__ import annotations

import time
from typing import Any, Callable, List, Optional, Tuple


class InputError(ValueError):
    """Bad user input. ``template`` is an English message with ``{named}`` fields.

    Messages name the file, line and field and say what was expected.
    """

    def __init__(self, template: str, **fields):
        self.template = template
        self.fields = fields
        super().__init__(template.format(**fields))


class Message(str):
    """An English log message (``template.format(**fields)``) that keeps its ``template``
    and ``fields``, so that an adapter can show it in the user's language; a plain ``str``
    everywhere else."""

    template: str
    fields: dict

    def __new__(cls, template: str, **fields):
        if isinstance(template, Message) and not fields:
            return template
        message = super().__new__(cls, template.format(**fields) if fields else template)
        message.template, message.fields = str(template), fields
        return message


class Cancelled(RuntimeError):
    """The user cancelled; nothing must be written."""


class Progress:
    """Progress in percent, a log and a cancel flag, for long loops in ``core``.

    ``report(fraction)`` takes 0..1 of the current step; ``check()`` raises
    :class:`Cancelled` when cancel was asked for; ``step(template, ...)`` says what the work
    is doing now (the Processing dialog's progress text: the adapters show it through a
    :class:`StepThrottle`). All callbacks are optional.
    """

    def __init__(self,
                 on_progress: Optional[Callable[[float], None]] = None,
                 is_cancelled: Optional[Callable[[], bool]] = None,
                 on_info: Optional[Callable[[str], None]] = None,
                 on_warning: Optional[Callable[[str], None]] = None,
                 start: float = 0.0, span: float = 100.0, *,
                 on_step: Optional[Callable[[str], None]] = None):
        self._on_progress = on_progress
        self._is_cancelled = is_cancelled
        self._on_info = on_info
        self._on_warning = on_warning
        self._on_step = on_step
        self._start, self._span = start, span

    def sub(self, start_fraction: float, end_fraction: float) -> "Progress":
        """A child reporting into ``[start, end]`` of this one's range."""
        return Progress(self._on_progress, self._is_cancelled, self._on_info, self._on_warning,
                        self._start + self._span * start_fraction,
                        self._span * (end_fraction - start_fraction), on_step=self._on_step)

    def report(self, fraction: float) -> None:
        self.check()
        if self._on_progress is not None:
            self._on_progress(self._start + self._span * min(max(fraction, 0.0), 1.0))

    def check(self) -> None:
        if self._is_cancelled is not None and self._is_cancelled():
            raise Cancelled("cancelled")

    def info(self, template: str, **fields) -> Message:
        """Log ``template`` (English, ``{named}`` fields) as a :class:`Message`; returns it."""
        message = Message(template, **fields)
        if self._on_info is not None:
            self._on_info(message)
        return message

    def warning(self, template: str, **fields) -> Message:
        """Warn with ``template`` (English, ``{named}`` fields) as a :class:`Message`."""
        message = Message(template, **fields)
        if self._on_warning is not None:
            self._on_warning(message)
        return message

    def step(self, template: str, **fields) -> Message:
        """Say what the work is doing now (English ``template`` with ``{named}`` fields, such
        as "Panorama {n} of {count}"): the current step, not a log line. Long loops call it
        once an item; the adapter decides how often it is shown (:class:`StepThrottle`)."""
        message = Message(template, **fields)
        if self._on_step is not None:
            self._on_step(message)
        return message

    def recorder(self) -> Tuple["Progress", List[Tuple[str, Message]]]:
        """A Progress for work in another thread and the list its log goes to: it reports no
        progress and no steps, keeps its messages as ``(kind, message)`` (``info`` or ``warning``) for
        :meth:`replay` in this thread, and checks this one's cancel."""
        kept: List[Tuple[str, Message]] = []

        def keep(kind: str) -> Callable[[Any], None]:
            return lambda message: kept.append((kind, message))
        return Progress(None, self._is_cancelled, keep("info"), keep("warning")), kept

    def replay(self, kept: List[Tuple[str, Message]]) -> None:
        """Log the messages a :meth:`recorder` kept, in their order."""
        for kind, message in kept:
            callback = self._on_info if kind == "info" else self._on_warning
            if callback is not None:
                callback(message)


#: Seconds between two steps of the same kind shown by a :class:`StepThrottle`.
STEP_INTERVAL_S = 10.0


class StepThrottle:
    """Shows :meth:`Progress.step` messages through ``show`` (an adapter's progress text,
    which the Processing dialog also writes to its log): a step of another kind (another
    template) at once, one of the same kind at most every ``interval_s`` seconds, so that a
    loop over 7,000 panoramas says where it is without filling the log. ``clock``: seconds
    (``time.monotonic``; tests give their own)."""

    def __init__(self, show: Callable[[Message], None], interval_s: float = STEP_INTERVAL_S,
                 clock: Callable[[], float] = time.monotonic):
        self.show, self.interval_s, self.clock = show, float(interval_s), clock
        self._template: Optional[str] = None
        self._shown_at = float("-inf")

    def __call__(self, message: Message) -> None:
        now = self.clock()
        template = getattr(message, "template", str(message))
        if template != self._template or now - self._shown_at >= self.interval_s:
            self._template, self._shown_at = template, now
            self.show(message)


#: A Progress that reports nothing and never cancels.
SILENT = Progress()
