"""Layer schemas: the fields of every layer the plugin reads or writes, declared once.

A :class:`Field` has a name and a Python kind (``int``, ``float`` or ``str``); a schema is
a tuple of fields in the layer's order. Each schema is declared in the core module beside
the dataclass that holds its values (``trajectory.STATION_FIELDS``,
``projection.DETECTION_FIELDS`` and ``CANDIDATE_FIELDS``, ``refine.SIGN_FIELDS``...); the
Processing adapters map the kinds to QGIS field types. Records are plain dicts keyed by
field name, ``None`` for NULL; a layer of a whole drive is read into :class:`Columns`, a
sequence of rows that stores its values column by column.
"""
from __future__ import annotations

import math
from array import array
from dataclasses import dataclass
from typing import Any, Dict, Iterable, Iterator, List, Mapping, Optional, Sequence, Tuple, overload

import numpy as np

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


class Columns(Sequence[Mapping[str, Any]]):
    """Records of ``schema``'s fields stored column by column: a float64 array per number
    field (NaN for NULL), a list per text field. A drive's layer of thousands of features
    then takes 8 bytes a number, not a dict a feature (whose freed memory the C heap keeps
    through the blocks that follow).

    It reads as the list of records it stands for: ``columns[k]`` is a :class:`Row`, a
    read-only mapping with the values :meth:`Field.value` gives (``None`` for NULL), so the
    ``from_records`` readers of core take it as they take a list of dicts. Fill it with
    :meth:`append` (a record: a mapping, missing fields NULL); numbers are stored as
    floats, so a value that is not a number raises ``TypeError`` or ``ValueError``.
    """

    def __init__(self, schema: Iterable[Field]) -> None:
        self.schema: Schema = tuple(schema)
        self._numbers: Dict[str, array] = {f.name: array("d") for f in self.schema if f.kind is not str}
        self._texts: Dict[str, List[Optional[str]]] = {f.name: [] for f in self.schema if f.kind is str}
        self._kinds = {f.name: f.kind for f in self.schema}
        self._count = 0

    def append(self, record: Mapping[str, Any]) -> None:
        values = [(name, math.nan if record.get(name) is None else float(record[name]))
                  for name in self._numbers]   # all converted before any is stored
        for name, value in values:
            self._numbers[name].append(value)
        for name, texts in self._texts.items():
            raw = record.get(name)
            texts.append(None if raw is None else str(raw))
        self._count += 1

    def __len__(self) -> int:
        return self._count

    @overload
    def __getitem__(self, k: int) -> "Row": ...

    @overload
    def __getitem__(self, k: slice) -> List["Row"]: ...

    def __getitem__(self, k):
        if isinstance(k, slice):
            return [Row(self, i) for i in range(*k.indices(self._count))]
        if not -self._count <= k < self._count:
            raise IndexError(k)
        return Row(self, k % self._count)

    def column(self, name: str) -> np.ndarray:
        """The values of the number field ``name`` (NaN for NULL), a float64 array."""
        return np.array(self._numbers[name], dtype=np.float64)

    def value(self, name: str, k: int) -> Any:
        """The value of field ``name`` in row ``k``, as :meth:`Field.value` gives it."""
        if name in self._texts:
            return self._texts[name][k]
        number = self._numbers[name][k]
        if math.isnan(number):
            return None
        return int(number) if self._kinds[name] is int and number.is_integer() else number


class Row(Mapping[str, Any]):
    """Row ``k`` of a :class:`Columns`: a read-only mapping of its fields' values."""

    __slots__ = ("_columns", "_k")

    def __init__(self, columns: Columns, k: int) -> None:
        self._columns, self._k = columns, k

    def __getitem__(self, name: str) -> Any:
        if name not in self._columns._kinds:
            raise KeyError(name)
        return self._columns.value(name, self._k)

    def __iter__(self) -> Iterator[str]:
        return iter(self._columns._kinds)

    def __len__(self) -> int:
        return len(self._columns._kinds)
