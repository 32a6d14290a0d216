"""Delimited text tables (CSV and friends) read with errors that name file, line and field.

A table has a header row; the delimiter is comma, semicolon, tab or runs of whitespace
(detected from the header). Column names are matched case-insensitively after stripping
blanks; extra columns are ignored. A row with more fields than the header is an error
(decimal commas in a comma-separated file split every number in two; empty trailing
fields, from a delimiter at the end of the line, are allowed). Line numbers in messages
are 1-based, the header being line 1. Every problem is an :class:`InputError` naming the
file, line and field.
"""
from __future__ import annotations

import csv
import math
import os
from typing import Dict, List, Optional, Sequence, Tuple

import numpy as np

from .errors import InputError


def _detect_delimiter(header_line: str) -> Optional[str]:
    for delimiter in (",", ";", "\t"):
        if delimiter in header_line:
            return delimiter
    return None  # whitespace


def _split_rows(lines: Sequence[Tuple[int, str]], delimiter: Optional[str], path: str,
                what: str) -> List[List[str]]:
    """The fields of each ``(line number, text)``; a line the csv module cannot split (a NUL
    character, an unclosed quote running past the field size limit) is an error naming it."""
    if delimiter is None:
        return [text.split() for _, text in lines]
    rows: List[List[str]] = []
    for line_no, text in lines:
        try:
            rows.extend(csv.reader([text], delimiter=delimiter))
        except csv.Error as e:
            raise InputError("{what} file {path}, line {line}: cannot split the line into fields "
                             "({error})", what=what, path=path, line=line_no, error=str(e))
    return rows


def read_table(path: str,
               required: Sequence[str],
               numeric: Sequence[str] = (),
               optional: Sequence[str] = (),
               what: str = "table") -> Dict[str, np.ndarray]:
    """Read ``path`` into ``{column: array}`` for the ``required`` and present ``optional`` columns.

    Columns in ``numeric`` become float64 arrays and must hold finite numbers (an
    optional numeric column may be empty in every row, which yields no entry); the
    others stay str arrays. ``what`` names the kind of file in messages
    ("trajectory", "image times", ...). Raises :class:`InputError` on an unreadable or
    empty file, missing columns (listing those found), wrong field counts and
    non-numeric, NaN or infinite values (file, line and field).
    Returns also ``"_line"``: the 1-based line number of each data row.
    """
    try:
        with open(path, "r", encoding="utf-8-sig", newline="") as f:
            text = f.read()
    except FileNotFoundError:
        raise InputError("{what} file not found: {path}", what=what, path=path)
    except UnicodeDecodeError as e:
        raise InputError("Cannot read {what} file {path}: it is not UTF-8 text (byte {position}); "
                         "save it as CSV in UTF-8", what=what, path=path, position=e.start + 1)
    except OSError as e:
        raise InputError("Cannot read {what} file {path}: {error}", what=what, path=path,
                         error=e.strerror or str(e))

    lines = text.replace("\r\n", "\n").replace("\r", "\n").split("\n")  # line numbers as editors count
    # Keep track of original line numbers while skipping blank lines.
    numbered = [(i + 1, line) for i, line in enumerate(lines) if line.strip()]
    if not numbered:
        raise InputError("{what} file {path} is empty: expected a header row with the columns {expected}",
                         what=what, path=path, expected=", ".join(required))
    header_line_no, header_line = numbered[0]
    delimiter = _detect_delimiter(header_line)
    rows = _split_rows(numbered, delimiter, path, what)
    header = [h.strip().lower() for h in rows[0]]
    missing = [c for c in required if c.lower() not in header]
    if missing:
        raise InputError("{what} file {path}: missing column(s) {missing}; found {found}; "
                         "expected {expected}",
                         what=what, path=path, missing=", ".join(missing),
                         found=_shorten(", ".join(h for h in header if h), 200) or "(none)",
                         expected=", ".join(required))
    data_rows = rows[1:]
    line_numbers = [n for n, _ in numbered[1:]]
    if not data_rows:
        raise InputError("{what} file {path} has a header but no data rows", what=what, path=path)
    _check_field_counts(data_rows, line_numbers, len(header), path, what)

    wanted = list(required) + [c for c in optional if c.lower() in header]
    index = {c: header.index(c.lower()) for c in wanted}
    out: Dict[str, np.ndarray] = {}
    numeric_set = {c.lower() for c in numeric}
    for column in wanted:
        col = index[column]
        values: List[str] = []
        for row, line_no in zip(data_rows, line_numbers):
            if col >= len(row):
                raise InputError("{what} file {path}, line {line}: field '{field}' is missing "
                                 "(the row has {count} fields, the header {header_count})",
                                 what=what, path=path, line=line_no, field=column,
                                 count=len(row), header_count=len(header))
            values.append(row[col].strip())
        if column.lower() in numeric_set:
            if column not in required and all(v == "" for v in values):
                continue
            out[column] = _parse_numbers(values, line_numbers, column, path, what)
        else:
            out[column] = np.array(values, dtype=object)
    out["_line"] = np.array(line_numbers, dtype=np.int64)
    return out


def _check_field_counts(rows: List[List[str]], line_numbers: List[int], header_count: int,
                        path: str, what: str) -> None:
    """A row with more (non-empty) fields than the header is an error: read as it is, every
    value after the first extra delimiter would be shifted into the wrong column."""
    for row, line_no in zip(rows, line_numbers):
        if len(row) > header_count and any(field.strip() for field in row[header_count:]):
            raise InputError("{what} file {path}, line {line}: {count} fields, but the header has "
                             "{header_count}: decimal commas, or the delimiter inside a value? Write "
                             "numbers with a decimal point (1.5, not 1,5)", what=what, path=path,
                             line=line_no, count=len(row), header_count=header_count)


def _parse_numbers(values: List[str], line_numbers: List[int], column: str, path: str, what: str):
    try:  # fast path; the loop below finds the line of the first bad value
        result = np.array(values, dtype=float)
        if np.isfinite(result).all():
            return result
    except ValueError:
        pass
    result = np.empty(len(values))
    for k, (text, line_no) in enumerate(zip(values, line_numbers)):
        try:
            number = float(text)
        except ValueError:
            if _is_decimal_comma(text):
                raise InputError("{what} file {path}, line {line}, field '{field}': expected a "
                                 "number, found '{value}': a decimal comma? Write numbers with a "
                                 "decimal point (1.5, not 1,5)", what=what, path=path,
                                 line=line_no, field=column, value=text)
            raise InputError("{what} file {path}, line {line}, field '{field}': expected a number, "
                             "found '{value}'", what=what, path=path, line=line_no, field=column,
                             value=_shorten(text))
        if not math.isfinite(number):
            raise InputError("{what} file {path}, line {line}, field '{field}': expected a finite "
                             "number, found '{value}'", what=what, path=path, line=line_no,
                             field=column, value=_shorten(text))
        result[k] = number
    return result


def _is_decimal_comma(text: str) -> bool:
    if text.count(",") != 1:
        return False
    try:
        float(text.replace(",", "."))
    except ValueError:
        return False
    return True


def _shorten(text: str, limit: int = 60) -> str:
    """A value as shown in a message: at most ``limit`` characters."""
    return text if len(text) <= limit else text[:limit] + "…"


def display_name(path: str) -> str:
    """The file name for messages that list many files."""
    return os.path.basename(path) or path
