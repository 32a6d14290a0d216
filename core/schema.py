"""Layer schemas: the fields of every layer the plugin reads or writes, declared once.

A :class:`Field` has a name and a Python kind (``int``, ``float`` or ``str``); a schema is
a tuple of fields in the layer's order. Each schema is declared in the core module beside
the dataclass that holds its values (``trajectory.STATION_FIELDS``,
``projection.DETECTION_FIELDS`` and ``CANDIDATE_FIELDS``, ``refine.SIGN_FIELDS``...); the
Processing adapters map the kinds to QGIS field types. Records are plain dicts keyed by
field name, ``None`` for NULL.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Dict, Iterable, Optional, Sequence, Tuple

#: The Python kinds a field may have.
KINDS = (int, float, str)


@dataclass(frozen=True)
class Field:
    """One attribute of a layer: ``name`` as written, ``kind`` one of :data:`KINDS`."""

    name: str
    kind: type

    def __post_init__(self) -> None:
        if self.kind not in KINDS:
            raise TypeError("field {}: kind must be int, float or str, not {!r}".format(
                self.name, self.kind))

    def value(self, raw: Any) -> Any:
        """``raw`` as this field's kind; ``None`` for NULL (and for a float NaN)."""
        if raw is None:
            return None
        if self.kind is float:
            number = float(raw)
            return None if math.isnan(number) else number
        if self.kind is int:
            return int(raw)
        return str(raw)


Schema = Tuple[Field, ...]


def fields(*spec: Tuple[str, type]) -> Schema:
    """A schema from ``(name, kind)`` pairs."""
    return tuple(Field(name, kind) for name, kind in spec)


def names(schema: Iterable[Field]) -> Tuple[str, ...]:
    """The field names of ``schema``, in order."""
    return tuple(f.name for f in schema)


def select(schema: Schema, wanted: Sequence[str]) -> Schema:
    """The fields of ``schema`` named in ``wanted``, in ``wanted``'s order."""
    by_name = {f.name: f for f in schema}
    return tuple(by_name[name] for name in wanted)


def typed_record(schema: Schema, record: Dict[str, Any],
                 default: Optional[Any] = None) -> Dict[str, Any]:
    """``record`` reduced to ``schema``'s fields, each value of its field's kind."""
    return {f.name: f.value(record.get(f.name, default)) for f in schema}
