"""Review of a sign layer: the verdicts, the fields they are written to, the order the signs
are stepped through and the fields a layer needs (the review panel, ``gui/reviewpanel.py``;
the handover export, :mod:`.handover`).

A sign's review state is its ``review_status`` field: NULL (or empty) until someone looks at
it, then one of the verdicts:

* ``accepted``: a real sign, class and code right;
* ``corrected``: a real sign whose class or code was changed (``reviewed_class``,
  ``reviewed_code``: the detector's ``class`` and the layer's ``code`` stay as they were);
* ``rejected``: not a sign (a false detection, a duplicate);
* ``unsure``: needs another look.

``reviewed_at`` is the time of the verdict, ISO 8601 in UTC.
"""
from __future__ import annotations

from datetime import datetime, timezone
from typing import Dict, Iterable, List, Optional, Sequence

from .schema import Field, Schema, names

ACCEPTED, CORRECTED, REJECTED, UNSURE = "accepted", "corrected", "rejected", "unsure"
#: the state of a sign without a verdict (``review_status`` NULL or empty)
UNREVIEWED = "unreviewed"
#: the verdicts, as written to ``review_status``
VERDICTS = (ACCEPTED, CORRECTED, REJECTED, UNSURE)
#: every state a sign can be in, in the order the export lists them
STATES = VERDICTS + (UNREVIEWED,)
#: the signs handed over when nobody says otherwise: the real ones
DEFAULT_HANDOVER_STATES = (ACCEPTED, CORRECTED)

REVIEW_STATUS = Field("review_status", str)
REVIEWED_CLASS = Field("reviewed_class", str)
REVIEWED_CODE = Field("reviewed_code", str)
REVIEWED_AT = Field("reviewed_at", str)
#: the fields verdicts are written to (added to a layer that lacks them)
REVIEW_FIELDS: Schema = (REVIEW_STATUS, REVIEWED_CLASS, REVIEWED_CODE, REVIEWED_AT)
#: the fields the review panel needs in a sign layer; others (``code``, ``condition``,
#: ``height``...) are shown when present
PANEL_REQUIRED = ("sign_id", "class", "score", "source_images")
#: optional fields of a sign layer the panel and the export read when present
CODE_FIELD, CONDITION_FIELD, NAME_FIELD = "code", "condition", "name"
POLE_FIELDS = ("pole_id", "pole")
SOURCE_FIELD = "source"


def state_of(value) -> str:
    """The review state of a ``review_status`` value: a verdict, :data:`UNREVIEWED` for NULL
    or blank; other text as written, lowercase (never one of the selectable states)."""
    if value is None:
        return UNREVIEWED
    text = str(value).strip().lower()
    return text or UNREVIEWED


def image_names(value) -> List[str]:
    """The panorama names of a ``source_images`` value (``;``-separated), each once."""
    out: List[str] = []
    for name in str(value or "").split(";"):
        name = name.strip()
        if name and name not in out:
            out.append(name)
    return out


def image_names_of(record: Dict) -> List[str]:
    """The panoramas a sign was seen in (its ``source_images``)."""
    return image_names(record.get("source_images"))


def is_reviewed(value) -> bool:
    return state_of(value) != UNREVIEWED


def missing_fields(found: Iterable[str], required: Sequence[str] = PANEL_REQUIRED) -> List[str]:
    """The names of ``required`` that are not among the field names ``found``, in order."""
    have = set(found)
    return [name for name in required if name not in have]


def missing_review_fields(found: Iterable[str]) -> List[str]:
    """The review fields (:data:`REVIEW_FIELDS`) a layer with the fields ``found`` lacks."""
    return missing_fields(found, names(REVIEW_FIELDS))


def now_iso(now: Optional[datetime] = None) -> str:
    """``now`` (default: the current time) as ISO 8601 in UTC to the second."""
    moment = now or datetime.now(timezone.utc)
    if moment.tzinfo is None:
        moment = moment.replace(tzinfo=timezone.utc)
    return moment.astimezone(timezone.utc).isoformat(timespec="seconds")


def verdict_values(verdict: str, record: Dict, new_class: Optional[str] = None,
                   new_code: Optional[str] = None, now: Optional[datetime] = None) -> Dict[str, object]:
    """The values of the review fields for ``verdict`` on the sign ``record`` (its current
    field values). ``corrected`` takes ``new_class`` and ``new_code``; when neither differs
    from the sign's class and code it is an ``accepted``. Other verdicts keep an earlier
    correction (a rejected sign keeps what it was corrected to). ValueError for an unknown
    verdict."""
    if verdict not in VERDICTS:
        raise ValueError("unknown verdict {!r}".format(verdict))
    values: Dict[str, object] = {REVIEW_STATUS.name: verdict, REVIEWED_AT.name: now_iso(now)}
    if verdict == CORRECTED:
        klass = (new_class or "").strip() or None
        code = (new_code or "").strip() or None
        if klass == record.get("class"):
            klass = None
        if code is not None and code == _text(record.get(CODE_FIELD)):
            code = None
        if klass is None and code is None:
            values[REVIEW_STATUS.name] = ACCEPTED
        values[REVIEWED_CLASS.name] = klass
        values[REVIEWED_CODE.name] = code
    return values


def _text(value) -> Optional[str]:
    return None if value is None or str(value).strip() == "" else str(value).strip()


def effective_class(record: Dict) -> Optional[str]:
    """The sign's class after review: ``reviewed_class`` when set, else ``class``."""
    return _text(record.get(REVIEWED_CLASS.name)) or _text(record.get("class"))


def effective_code(record: Dict) -> Optional[str]:
    """The sign's code after review: ``reviewed_code`` when set, else the ``code`` field's
    value (None when the layer has neither)."""
    return _text(record.get(REVIEWED_CODE.name)) or _text(record.get(CODE_FIELD))


def review_order(signs: Sequence[Dict], key: str = "sign_id", fid: str = "fid") -> List:
    """The feature ids (``record[fid]``) of ``signs`` in review order: by ``key`` (signs
    without one last), then by feature id."""
    def sort_key(record):
        value = record.get(key)
        try:
            number = float(value)
        except (TypeError, ValueError):
            return (1, 0.0, record[fid])
        return (0, number, record[fid])

    return [record[fid] for record in sorted(signs, key=sort_key)]


def step(order: Sequence, current, direction: int = 1):
    """The feature after (``direction`` 1) or before (-1) ``current`` in ``order``, wrapping
    round; the first (last) one when ``current`` is not in ``order``; None for no signs."""
    if not order:
        return None
    if current not in order:
        return order[0] if direction > 0 else order[-1]
    return order[(list(order).index(current) + direction) % len(order)]


def next_unreviewed(order: Sequence, states: Dict, current=None, direction: int = 1):
    """The next feature of ``order`` after ``current`` (wrapping round, ``current`` itself
    last) whose state in ``states`` (feature -> ``review_status`` value) is unreviewed;
    None when every sign has a verdict."""
    if not order:
        return None
    order = list(order)
    start = order.index(current) if current in order else (-1 if direction > 0 else len(order))
    for k in range(1, len(order) + 1):
        fid = order[(start + direction * k) % len(order)]
        if not is_reviewed(states.get(fid)):
            return fid
    return None


def tally(states: Iterable) -> Dict[str, int]:
    """How many signs are in each state of :data:`STATES` (``review_status`` values)."""
    counts = {state: 0 for state in STATES}
    for value in states:
        state = state_of(value)
        counts[state] = counts.get(state, 0) + 1
    return counts
