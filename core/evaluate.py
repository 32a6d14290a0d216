"""Evaluation of a sign layer against reference (ground-truth) sign panels.

Conventions (``docs/formats.md``, "Reference (ground truth) signs CSV" and
"Evaluation"):

* Both sets come in one projected CRS (East, North, Up, metres); the adapter reprojects.
* Signs and reference panels are matched one-to-one by optimal assignment on the 3D
  distance between panel centres, pairs farther apart than ``match_radius_m`` forbidden,
  class ignored. The matching has the largest possible number of pairs and, among those,
  the smallest total distance.
* ``PRECISION`` = matches / signs, ``RECALL`` = matches / reference panels,
  ``F1`` = 2 TP / (2 TP + FP + FN) (the harmonic mean of the two where both exist).
  A ratio whose denominator is zero is NaN (no signs: precision NaN; no matches: class
  accuracy and the error statistics NaN).
* Errors of a match are "sign minus reference": ``dz`` and the height error keep their
  sign in the per-row records; the summary statistics take absolute values.
  Azimuth error = circular absolute difference in degrees, in [0, 180]. Height and azimuth
  may be NaN (unknown) on either side; such pairs are left out of those two statistics.
* ``P95_ERROR`` is the 95th percentile with linear interpolation between order
  statistics (``numpy.percentile``'s default).
* Sign codes (OpenStreetMap ``traffic_sign`` values such as ``DE:274[50]``) are scored only
  when both sets have them (``SignSet.codes`` not None: the reference's ``code`` column, the
  sign layer's ``code`` field). Among the matches whose reference code is not empty, code
  accuracy = share whose sign code equals it (compared as text, surrounding blanks
  removed); a sign without a code counts as wrong and is counted as "no code" too. The
  confusions are the (reference code, sign code) pairs that differ, most frequent first.
  Otherwise the result says, in :attr:`EvaluationResult.code_note`, why codes were not scored.
"""
from __future__ import annotations

import html
import math
from collections import Counter
from dataclasses import dataclass, field
from typing import Dict, List, Optional, Sequence, Tuple

import numpy as np
from scipy.optimize import linear_sum_assignment
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components
from scipy.spatial import cKDTree

from .errors import InputError, Message
from .outputs import write_text_atomically
from .tables import read_table

#: Reference CSV columns (docs/formats.md order), all required; header names are case-insensitive.
REFERENCE_COLUMNS = ("sign_id", "class", "x", "y", "z", "height", "width",
                     "panel_height", "azimuth")
REFERENCE_NUMERIC = ("x", "y", "z", "height", "width", "panel_height", "azimuth")

#: Optional reference CSV column: the sign's OpenStreetMap ``traffic_sign`` code ("" unknown).
REFERENCE_CODE = "code"

#: Numeric output names of ``roadsigns:evaluate``, in order.
OUTPUT_NAMES = ("TP", "FP", "FN", "PRECISION", "RECALL", "F1", "CLASS_ACCURACY",
                "MEDIAN_ERROR", "P95_ERROR", "MEDIAN_HEIGHT_ERROR", "MEDIAN_AZIMUTH_ERROR",
                "MEDIAN_SIZE_ERROR", "P95_SIZE_ERROR",
                "CODE_ACCURACY", "CODE_COMPARED", "NO_CODE")
#: Text output of ``roadsigns:evaluate``: the code confusions (:func:`confusions_text`).
CODE_CONFUSIONS = "CODE_CONFUSIONS"
#: How a missing (empty) sign code is written in the confusions.
NO_CODE_TEXT = "(none)"

MATCHED, MISSED, FALSE = "matched", "missed", "false"


# --------------------------------------------------------------------------- sign sets

def _float_column(values, n: int, name: str) -> np.ndarray:
    """``values`` as a float array of length ``n``; None means all NaN (unknown)."""
    if values is None:
        return np.full(n, np.nan)
    array = np.asarray(values, dtype=float).reshape(-1)
    if array.shape != (n,):
        raise ValueError(f"SignSet.{name} has {array.size} values for {n} signs")
    return array


def _code_text(value) -> str:
    """A sign code as text, surrounding blanks removed; "" for None and NaN (unknown)."""
    if value is None or (isinstance(value, float) and math.isnan(value)):
        return ""
    return str(value).strip()


@dataclass
class SignSet:
    """Sign panels in one CRS: ``xyz`` (N, 3) panel centres in world metres (E, N, Up).

    ``height`` (panel centre above the ground below, m), ``azimuth_deg`` (direction the
    face looks towards, clockwise from grid north), ``width_m`` / ``panel_height_m`` may
    hold NaN where unknown; None means all unknown. ``images`` are image names shown in
    the report (e.g. a sign's ``best_image``), "" where none. ``codes`` are the signs'
    ``traffic_sign`` codes, "" (or None, NaN) where unknown; ``codes`` None means the set
    has no codes at all (no ``code`` column or field), and codes are then not scored.
    """
    ids: Sequence[str]
    classes: Sequence[str]
    xyz: np.ndarray
    height: Optional[np.ndarray] = None
    azimuth_deg: Optional[np.ndarray] = None
    width_m: Optional[np.ndarray] = None
    panel_height_m: Optional[np.ndarray] = None
    images: Optional[Sequence[str]] = None
    codes: Optional[Sequence[str]] = None

    def __post_init__(self):
        self.ids = [str(value) for value in self.ids]
        n = len(self.ids)
        self.classes = [str(value) for value in self.classes]
        if len(self.classes) != n:
            raise ValueError(f"SignSet has {len(self.classes)} classes for {n} ids")
        self.xyz = np.asarray(self.xyz, dtype=float).reshape(n, 3)
        self.height = _float_column(self.height, n, "height")
        self.azimuth_deg = _float_column(self.azimuth_deg, n, "azimuth_deg")
        self.width_m = _float_column(self.width_m, n, "width_m")
        self.panel_height_m = _float_column(self.panel_height_m, n, "panel_height_m")
        self.images = [""] * n if self.images is None else [str(v) for v in self.images]
        if len(self.images) != n:
            raise ValueError(f"SignSet has {len(self.images)} images for {n} ids")
        if self.codes is not None:
            self.codes = [_code_text(value) for value in self.codes]
            if len(self.codes) != n:
                raise ValueError(f"SignSet has {len(self.codes)} codes for {n} ids")

    def __len__(self) -> int:
        return len(self.ids)


# --------------------------------------------------------------------------- reference CSV

def read_reference_csv(path: str) -> SignSet:
    """Read a reference signs CSV (the columns of docs/formats.md, comma/semicolon/tab separated).

    The optional column ``code`` gives the set its ``codes`` (an empty cell: no code);
    without it ``codes`` is None.

    Raises :class:`InputError` naming the file (and line and field) for missing columns,
    values that are not finite numbers, empty ids or classes, duplicate ``sign_id`` and a
    file without data rows.
    """
    columns = read_table(path, required=REFERENCE_COLUMNS, numeric=REFERENCE_NUMERIC,
                         optional=(REFERENCE_CODE,), what="reference signs")
    first_line: Dict[str, int] = {}
    for name in ("sign_id", "class"):
        for value, line in zip(columns[name], columns["_line"]):
            if not value:
                raise InputError("reference signs file {path}, line {line}, field '{field}': "
                                 "empty value", path=path, line=int(line), field=name)
    for sign_id, line in zip(columns["sign_id"], columns["_line"]):
        if sign_id in first_line:
            raise InputError("reference signs file {path}, line {line}: sign_id '{sign_id}' "
                             "already used on line {first}", path=path, line=int(line),
                             sign_id=sign_id, first=first_line[sign_id])
        first_line[sign_id] = int(line)
    return SignSet(ids=list(columns["sign_id"]), classes=list(columns["class"]),
                   xyz=np.column_stack([columns["x"], columns["y"], columns["z"]]),
                   height=columns["height"], azimuth_deg=columns["azimuth"],
                   width_m=columns["width"], panel_height_m=columns["panel_height"],
                   codes=list(columns[REFERENCE_CODE]) if REFERENCE_CODE in columns else None)


def check_overlap(signs: SignSet, reference: SignSet, match_radius_m: float, sign_label: str,
                  reference_label: str, gap_m: float = 1000.0) -> None:
    """:class:`InputError` when the two sets lie apart: their boxes separated by more than
    ``gap_m`` (and the match radius). Then the scores would be 0, not because the signs are
    wrong but because the two are not in the same CRS or area."""
    a, b = signs.xyz[np.isfinite(signs.xyz).all(axis=1)], reference.xyz[np.isfinite(reference.xyz).all(axis=1)]
    if not len(a) or not len(b):
        return
    gap = np.maximum(np.maximum(a[:, :2].min(axis=0) - b[:, :2].max(axis=0),
                                b[:, :2].min(axis=0) - a[:, :2].max(axis=0)), 0.0)
    if float(np.hypot(*gap)) <= gap_m + float(match_radius_m):
        return
    raise InputError("The signs ({signs}: x {sx0} to {sx1}, y {sy0} to {sy1}) and the reference "
                     "{reference} (x {rx0} to {rx1}, y {ry0} to {ry1}) do not overlap: are both in the "
                     "same CRS and the same area?", signs=sign_label, reference=reference_label,
                     sx0=round(float(a[:, 0].min()), 1), sx1=round(float(a[:, 0].max()), 1),
                     sy0=round(float(a[:, 1].min()), 1), sy1=round(float(a[:, 1].max()), 1),
                     rx0=round(float(b[:, 0].min()), 1), rx1=round(float(b[:, 0].max()), 1),
                     ry0=round(float(b[:, 1].min()), 1), ry1=round(float(b[:, 1].max()), 1))


# --------------------------------------------------------------------------- matching

@dataclass
class Matching:
    """One-to-one pairs ``sign_index[k] <-> reference_index[k]`` (sorted by reference),
    their 3D distances, and the indices left unmatched on each side (ascending)."""
    sign_index: np.ndarray
    reference_index: np.ndarray
    distance_m: np.ndarray
    unmatched_signs: np.ndarray
    unmatched_reference: np.ndarray


def _check_radius(match_radius_m) -> float:
    radius = float(match_radius_m)
    if not (math.isfinite(radius) and radius > 0.0):
        raise InputError("match radius {radius} m: expected a positive number of metres",
                         radius=match_radius_m)
    return radius


def _check_finite_positions(signs: SignSet, label: str) -> None:
    bad = np.flatnonzero(~np.isfinite(signs.xyz).all(axis=1))
    if bad.size:
        raise InputError("{label}: sign '{sign_id}' has no valid x, y, z position",
                         label=label, sign_id=signs.ids[bad[0]])


def match_signs(signs: SignSet, reference: SignSet, match_radius_m: float) -> Matching:
    """Optimal one-to-one matching of sign and reference panel centres (class ignored).

    Pairs at 3D distance <= ``match_radius_m`` are allowed. The result has the largest
    number of pairs and, among such matchings, the smallest total distance.

    The bipartite graph of allowed pairs is split into connected components (a pair never
    crosses components) and each is solved by ``linear_sum_assignment`` on a dense matrix
    holding the distance for allowed pairs and ``BIG = (k + 1) * radius + 1`` for forbidden
    ones, k = min(rows, columns). Every assignment of the square-ish problem fills k
    pairs, so its cost is (sum of allowed distances) + BIG * (k - matches); the sum is at
    most k * radius < BIG, so one more match always outweighs any distance saving: the
    minimum cost maximises matches first, then minimises their total distance. Forbidden
    pairs the solver had to fill are dropped afterwards.
    """
    radius = _check_radius(match_radius_m)
    _check_finite_positions(signs, "signs")
    _check_finite_positions(reference, "reference")
    n_signs, n_reference = len(signs), len(reference)
    empty = np.zeros(0, dtype=int)
    if n_signs == 0 or n_reference == 0:
        return Matching(empty, empty, np.zeros(0), np.arange(n_signs), np.arange(n_reference))

    # Candidate pairs from k-d trees (a slightly larger radius), exact distances after.
    origin = reference.xyz.mean(axis=0)
    sign_xyz, reference_xyz = signs.xyz - origin, reference.xyz - origin
    candidates = cKDTree(sign_xyz).query_ball_tree(cKDTree(reference_xyz),
                                                   radius * (1.0 + 1e-9) + 1e-12)
    rows = np.repeat(np.arange(n_signs), [len(c) for c in candidates])
    cols = np.fromiter((j for c in candidates for j in c), dtype=int, count=rows.size)
    distance = np.linalg.norm(sign_xyz[rows] - reference_xyz[cols], axis=1)
    keep = distance <= radius
    rows, cols, distance = rows[keep], cols[keep], distance[keep]

    # Components of the bipartite graph: nodes 0..n_signs-1 signs, then reference panels.
    n_nodes = n_signs + n_reference
    graph = coo_matrix((np.ones(rows.size), (rows, cols + n_signs)), shape=(n_nodes, n_nodes))
    _, label = connected_components(graph, directed=False)
    pair_component = label[rows]
    matched_signs, matched_reference, matched_distance = [], [], []
    for component in np.unique(pair_component):
        in_component = pair_component == component
        comp_rows, comp_cols = rows[in_component], cols[in_component]
        comp_dist = distance[in_component]
        sign_ids = np.unique(comp_rows)
        reference_ids = np.unique(comp_cols)
        r = np.searchsorted(sign_ids, comp_rows)
        c = np.searchsorted(reference_ids, comp_cols)
        big = (min(sign_ids.size, reference_ids.size) + 1) * radius + 1.0
        cost = np.full((sign_ids.size, reference_ids.size), big)
        allowed = np.zeros(cost.shape, dtype=bool)
        cost[r, c] = comp_dist
        allowed[r, c] = True
        assigned_r, assigned_c = linear_sum_assignment(cost)
        ok = allowed[assigned_r, assigned_c]
        matched_signs.append(sign_ids[assigned_r[ok]])
        matched_reference.append(reference_ids[assigned_c[ok]])
        matched_distance.append(cost[assigned_r[ok], assigned_c[ok]])

    sign_index = np.concatenate(matched_signs) if matched_signs else empty
    reference_index = np.concatenate(matched_reference) if matched_reference else empty
    distance_m = np.concatenate(matched_distance) if matched_distance else np.zeros(0)
    order = np.argsort(reference_index, kind="stable")
    sign_index, reference_index, distance_m = (sign_index[order], reference_index[order],
                                               distance_m[order])
    return Matching(sign_index=sign_index, reference_index=reference_index,
                    distance_m=distance_m,
                    unmatched_signs=np.setdiff1d(np.arange(n_signs), sign_index),
                    unmatched_reference=np.setdiff1d(np.arange(n_reference), reference_index))


# --------------------------------------------------------------------------- evaluation

def azimuth_difference_deg(a_deg, b_deg):
    """Circular absolute difference of azimuths in degrees, in [0, 180] (NaN stays NaN)."""
    difference = np.asarray(a_deg, dtype=float) - np.asarray(b_deg, dtype=float)
    return np.abs((difference + 180.0) % 360.0 - 180.0)


@dataclass
class ReportRow:
    """One line of the report: a match, a missed reference panel or a false sign.

    Errors are sign minus reference (``dz_m``, ``height_error_m``, ``width_error_m``,
    ``panel_height_error_m`` signed), NaN where they do not apply or are unknown;
    ``horizontal_m`` and ``azimuth_error_deg`` are >= 0.
    """
    status: str
    sign_id: str = ""
    sign_class: str = ""
    reference_id: str = ""
    reference_class: str = ""
    image: str = ""
    sign_code: str = ""
    reference_code: str = ""
    distance_m: float = math.nan
    horizontal_m: float = math.nan
    dz_m: float = math.nan
    height_error_m: float = math.nan
    azimuth_error_deg: float = math.nan
    width_error_m: float = math.nan
    panel_height_error_m: float = math.nan

    #: this match is one of the code comparisons (codes scored, reference code not empty)
    code_compared: bool = False

    @property
    def class_agrees(self) -> Optional[bool]:
        return self.sign_class == self.reference_class if self.status == MATCHED else None

    @property
    def code_agrees(self) -> Optional[bool]:
        """Whether the sign's code is the reference's; None where codes are not compared."""
        return self.sign_code == self.reference_code if self.code_compared else None


def _ratio(numerator: float, denominator: float) -> float:
    return numerator / denominator if denominator else math.nan


def _median(values: np.ndarray) -> float:
    values = values[~np.isnan(values)]
    return float(np.median(values)) if values.size else math.nan


def _p95(values: np.ndarray) -> float:
    values = values[~np.isnan(values)]
    return float(np.percentile(values, 95)) if values.size else math.nan


def size_error_m(width_error_m: np.ndarray, panel_height_error_m: np.ndarray) -> np.ndarray:
    """Per match, the larger of the absolute width and panel-height errors (m); the known one
    where the other is NaN, NaN where both are."""
    both = np.abs(np.column_stack([width_error_m, panel_height_error_m]))
    known = ~np.isnan(both)
    return np.where(known.any(axis=1), np.max(np.where(known, both, -np.inf), axis=1), np.nan)


@dataclass
class EvaluationResult:
    """Counts, rates, error statistics (absolute values; NaN where undefined) and rows."""
    match_radius_m: float
    n_signs: int
    n_reference: int
    tp: int
    fp: int
    fn: int
    precision: float
    recall: float
    f1: float
    class_accuracy: float
    median_error_m: float
    p95_error_m: float
    median_horizontal_error_m: float
    median_vertical_error_m: float
    median_height_error_m: float
    median_azimuth_error_deg: float
    #: a match's size error: the larger of |width| and |panel_height| sign minus reference
    #: (the one known where the other is not; NaN where neither is), median and 95th percentile
    median_size_error_m: float
    p95_size_error_m: float
    matching: Matching
    rows: List[ReportRow] = field(default_factory=list)
    #: whether codes were scored (both sets have codes); else ``code_note`` says why not
    codes_scored: bool = False
    #: matches whose reference code is not empty, and the share of them with the same sign code
    code_compared: int = 0
    code_accuracy: float = math.nan
    #: of those, the signs without a code (counted wrong)
    no_code: int = 0
    #: (reference code, sign code ("" none), count) of the compared matches whose codes differ,
    #: most frequent first, then by reference code and sign code
    code_confusions: List[Tuple[str, str, int]] = field(default_factory=list)
    #: why codes were not scored (a :class:`Message`); None when they were
    code_note: Optional[Message] = None

    def as_outputs(self) -> Dict[str, float]:
        """The numeric outputs of ``roadsigns:evaluate`` (counts as int; the code figures
        NaN when codes were not scored)."""
        values = (self.tp, self.fp, self.fn, self.precision, self.recall, self.f1,
                  self.class_accuracy, self.median_error_m, self.p95_error_m,
                  self.median_height_error_m, self.median_azimuth_error_deg,
                  self.median_size_error_m, self.p95_size_error_m,
                  self.code_accuracy,
                  self.code_compared if self.codes_scored else math.nan,
                  self.no_code if self.codes_scored else math.nan)
        return dict(zip(OUTPUT_NAMES, values))


def confusions_text(confusions: Sequence[Tuple[str, str, int]]) -> str:
    """The confusions as one line, ``DE:274[50] -> DE:274[30]: 2; DE:206 -> (none): 1``
    (a missing sign code written :data:`NO_CODE_TEXT`); "" when there are none."""
    return "; ".join(f"{reference} -> {predicted or NO_CODE_TEXT}: {count}"
                     for reference, predicted, count in confusions)


def _code_note(signs: SignSet, reference: SignSet) -> Optional[Message]:
    """Why codes cannot be scored, or None when both sets have codes."""
    if signs.codes is None and reference.codes is None:
        return Message("Code accuracy not computed: neither the signs nor the reference have "
                       "a 'code' field or column.")
    if reference.codes is None:
        return Message("Code accuracy not computed: the reference has no 'code' column or field.")
    if signs.codes is None:
        return Message("Code accuracy not computed: the signs have no 'code' field.")
    return None


def score_codes(sign_codes: Sequence[str], reference_codes: Sequence[str]
                ) -> Tuple[int, float, int, List[Tuple[str, str, int]]]:
    """(compared, accuracy, no code, confusions) of matched code pairs ``sign_codes[k]`` /
    ``reference_codes[k]`` ("" unknown): the pairs whose reference code is not empty are
    compared; accuracy NaN when none is. Confusions: see :attr:`EvaluationResult.code_confusions`."""
    compared = [(_code_text(s), _code_text(r)) for s, r in zip(sign_codes, reference_codes)
                if _code_text(r)]
    right = sum(s == r for s, r in compared)
    no_code = sum(s == "" for s, _ in compared)
    counts = Counter((r, s) for s, r in compared if s != r)
    confusions = sorted(((r, s, n) for (r, s), n in counts.items()),
                        key=lambda item: (-item[2], item[0], item[1]))
    return len(compared), _ratio(right, len(compared)), no_code, confusions


def evaluate(signs: SignSet, reference: SignSet, match_radius_m: float) -> EvaluationResult:
    """Match ``signs`` to ``reference`` (see :func:`match_signs`) and score the result.

    Empty inputs do not fail here (the adapter refuses empty layers): with no signs
    precision is NaN, with no reference recall is NaN, with neither F1 is NaN too.
    Rows: reference panels in their order (matched or missed), then false signs.
    """
    matching = match_signs(signs, reference, match_radius_m)
    s, r = matching.sign_index, matching.reference_index
    delta = signs.xyz[s] - reference.xyz[r]
    horizontal = np.hypot(delta[:, 0], delta[:, 1])
    height_error = np.asarray(signs.height)[s] - np.asarray(reference.height)[r]
    azimuth_error = azimuth_difference_deg(np.asarray(signs.azimuth_deg)[s], np.asarray(reference.azimuth_deg)[r])
    width_error = np.asarray(signs.width_m)[s] - np.asarray(reference.width_m)[r]
    panel_height_error = np.asarray(signs.panel_height_m)[s] - np.asarray(reference.panel_height_m)[r]
    size_error = size_error_m(width_error, panel_height_error)
    class_agrees = np.array([signs.classes[i] == reference.classes[j] for i, j in zip(s, r)],
                            dtype=bool)

    tp, fp, fn = int(s.size), len(signs) - int(s.size), len(reference) - int(s.size)
    distance = matching.distance_m
    sign_images = list(signs.images or [""] * len(signs))
    result = EvaluationResult(
        match_radius_m=float(match_radius_m), n_signs=len(signs), n_reference=len(reference),
        tp=tp, fp=fp, fn=fn,
        precision=_ratio(tp, len(signs)), recall=_ratio(tp, len(reference)),
        f1=_ratio(2 * tp, 2 * tp + fp + fn),
        class_accuracy=float(class_agrees.mean()) if tp else math.nan,
        median_error_m=_median(distance),
        p95_error_m=_p95(distance),
        median_horizontal_error_m=_median(horizontal),
        median_vertical_error_m=_median(np.abs(delta[:, 2])),
        median_height_error_m=_median(np.abs(height_error)),
        median_azimuth_error_deg=_median(azimuth_error),
        median_size_error_m=_median(size_error), p95_size_error_m=_p95(size_error),
        matching=matching)

    result.code_note = _code_note(signs, reference)
    result.codes_scored = result.code_note is None
    sign_codes = list(signs.codes) if signs.codes is not None else [""] * len(signs)
    reference_codes = list(reference.codes) if reference.codes is not None else [""] * len(reference)
    if result.codes_scored:
        (result.code_compared, result.code_accuracy, result.no_code,
         result.code_confusions) = score_codes([sign_codes[i] for i in s],
                                               [reference_codes[j] for j in r])

    match_of_reference = {int(j): k for k, j in enumerate(r)}
    for j in range(len(reference)):
        k = match_of_reference.get(j)
        if k is None:
            result.rows.append(ReportRow(MISSED, reference_id=reference.ids[j],
                                         reference_class=reference.classes[j],
                                         reference_code=reference_codes[j]))
            continue
        i = int(s[k])
        result.rows.append(ReportRow(
            MATCHED, sign_id=signs.ids[i], sign_class=signs.classes[i],
            reference_id=reference.ids[j], reference_class=reference.classes[j],
            image=sign_images[i], sign_code=sign_codes[i], reference_code=reference_codes[j],
            code_compared=result.codes_scored and bool(reference_codes[j]),
            distance_m=float(distance[k]),
            horizontal_m=float(horizontal[k]), dz_m=float(delta[k, 2]),
            height_error_m=float(height_error[k]),
            azimuth_error_deg=float(azimuth_error[k]),
            width_error_m=float(width_error[k]), panel_height_error_m=float(panel_height_error[k])))
    for i in matching.unmatched_signs:
        result.rows.append(ReportRow(FALSE, sign_id=signs.ids[i], sign_class=signs.classes[i],
                                     image=sign_images[i], sign_code=sign_codes[i]))
    return result


# --------------------------------------------------------------------------- HTML report

_CSS = """
body { font-family: sans-serif; margin: 1.5em; color: #222; }
h1 { font-size: 1.4em; } h2 { font-size: 1.15em; margin-top: 1.5em; }
table { border-collapse: collapse; margin: 0.5em 0; }
th, td { border: 1px solid #bbb; padding: 0.25em 0.6em; }
th { background: #eee; text-align: left; }
td.num { text-align: right; font-variant-numeric: tabular-nums; }
tr.matched td.status { color: #176117; }
tr.missed td.status { color: #a05a00; }
tr.false td.status { color: #b01c1c; }
td.wrongclass, td.wrongcode { background: #fde4e4; }
p.note { color: #555; font-size: 0.9em; }
"""


def _number(value: float, unit: str = "", digits: int = 3, signed: bool = False) -> str:
    """A number with its unit; an em dash where it is undefined (NaN)."""
    if value is None or (isinstance(value, float) and math.isnan(value)):
        return "\u2014"
    text = f"{value:+.{digits}f}" if signed else f"{value:.{digits}f}"
    return f"{text}\u00a0{unit}" if unit else text


def _cell(text: str, css_class: str = "") -> str:
    attribute = f' class="{css_class}"' if css_class else ""
    return f"<td{attribute}>{html.escape(text)}</td>"


def _summary_html(result: EvaluationResult) -> str:
    rows = [
        ("Signs evaluated", str(result.n_signs)),
        ("Reference panels", str(result.n_reference)),
        ("Match radius", _number(result.match_radius_m, "m", 2)),
        ("Matched (TP)", str(result.tp)),
        ("False signs (FP)", str(result.fp)),
        ("Missed panels (FN)", str(result.fn)),
        ("Precision (TP / signs)", _number(result.precision)),
        ("Recall (TP / reference)", _number(result.recall)),
        ("F1", _number(result.f1)),
        ("Class accuracy (of matches)", _number(result.class_accuracy)),
        ("Median 3D position error", _number(result.median_error_m, "m")),
        ("95th percentile 3D position error", _number(result.p95_error_m, "m")),
        ("Median horizontal error", _number(result.median_horizontal_error_m, "m")),
        ("Median vertical error (|dz|)", _number(result.median_vertical_error_m, "m")),
        ("Median height error (|dh above ground|)", _number(result.median_height_error_m, "m")),
        ("Median azimuth error", _number(result.median_azimuth_error_deg, "\u00b0", 1)),
        ("Median size error (larger of |dw|, |dh| of the panel)", _number(result.median_size_error_m, "m")),
        ("95th percentile size error", _number(result.p95_size_error_m, "m")),
    ]
    if result.codes_scored:
        rows += [
            ("Code accuracy (of matches with a reference code)", _number(result.code_accuracy)),
            ("Codes compared", str(result.code_compared)),
            ("Compared signs without a code", str(result.no_code)),
        ]
    body = "\n".join(f"<tr><th>{html.escape(name)}</th>{_cell(value, 'num')}</tr>"
                     for name, value in rows)
    return f'<table class="summary">\n{body}\n</table>'


_ROW_HEADERS = ("Status", "Sign id", "Sign class", "Reference id", "Reference class",
                "3D distance", "Horizontal", "dz (sign \u2212 ref.)",
                "Height error (sign \u2212 ref.)", "Azimuth error",
                "Width error (sign \u2212 ref.)", "Panel height error (sign \u2212 ref.)", "Image")
#: the columns added after the classes when codes are scored
_CODE_HEADERS = ("Sign code", "Reference code")


def _code_cells(row: ReportRow) -> List[str]:
    code_css = "wrongcode" if row.code_agrees is False else ""
    sign_code = row.sign_code or (NO_CODE_TEXT if row.code_compared else "")
    return [_cell(sign_code, code_css), _cell(row.reference_code, code_css)]


def _row_html(row: ReportRow, codes: bool = False) -> str:
    class_css = "wrongclass" if row.class_agrees is False else ""
    cells = [_cell(row.status, "status"), _cell(row.sign_id), _cell(row.sign_class, class_css),
             _cell(row.reference_id), _cell(row.reference_class, class_css),
             *(_code_cells(row) if codes else []),
             _cell(_number(row.distance_m, "m"), "num"),
             _cell(_number(row.horizontal_m, "m"), "num"),
             _cell(_number(row.dz_m, "m", signed=True), "num"),
             _cell(_number(row.height_error_m, "m", signed=True), "num"),
             _cell(_number(row.azimuth_error_deg, "\u00b0", 1), "num"),
             _cell(_number(row.width_error_m, "m", signed=True), "num"),
             _cell(_number(row.panel_height_error_m, "m", signed=True), "num"),
             _cell(row.image)]
    return f'<tr class="{row.status}">{"".join(cells)}</tr>'


def _codes_html(result: EvaluationResult) -> List[str]:
    """The code confusions section, or the one line saying why codes were not scored."""
    if not result.codes_scored:
        return [f'<p class="note">{html.escape(str(result.code_note))}</p>']
    if not result.code_confusions:
        return ["<h2>Code confusions</h2>",
                "<p>None: every compared sign has its reference code.</p>" if result.code_compared
                else "<p>No match has a reference code.</p>"]
    header = "".join(f"<th>{html.escape(name)}</th>" for name in ("Reference code", "Sign code", "Count"))
    body = "\n".join(f"<tr>{_cell(reference)}{_cell(predicted or NO_CODE_TEXT)}{_cell(str(count), 'num')}</tr>"
                     for reference, predicted, count in result.code_confusions)
    return ["<h2>Code confusions</h2>",
            f'<table class="confusions">\n<thead><tr>{header}</tr></thead>\n<tbody>\n{body}\n'
            "</tbody>\n</table>"]


def render_html_report(result: EvaluationResult, title: str = "Road sign evaluation",
                       sign_label: str = "", reference_label: str = "") -> str:
    """The report as one self-contained HTML document (inline CSS, every text escaped)."""
    sources = []
    if sign_label:
        sources.append(f"<p>Signs: {html.escape(sign_label)}</p>")
    if reference_label:
        sources.append(f"<p>Reference: {html.escape(reference_label)}</p>")
    codes = result.codes_scored
    names = (_ROW_HEADERS[:5] + _CODE_HEADERS + _ROW_HEADERS[5:]) if codes else _ROW_HEADERS
    header = "".join(f"<th>{html.escape(name)}</th>" for name in names)
    rows = "\n".join(_row_html(row, codes) for row in result.rows)
    note = ("Signs and reference panels are matched one-to-one by optimal assignment on the "
            "3D distance between panel centres within the match radius, ignoring class. "
            "Errors are sign minus reference; summary errors are absolute values; the azimuth "
            "error is the circular difference. \u2014 means undefined or unknown.")
    return "\n".join([
        "<!DOCTYPE html>",
        '<html lang="en">',
        "<head>",
        '<meta charset="utf-8">',
        f"<title>{html.escape(title)}</title>",
        f"<style>{_CSS}</style>",
        "</head>",
        "<body>",
        f"<h1>{html.escape(title)}</h1>",
        *sources,
        "<h2>Summary</h2>",
        _summary_html(result),
        *_codes_html(result),
        "<h2>Signs and reference panels</h2>",
        f"<table class=\"signs\">\n<thead><tr>{header}</tr></thead>\n<tbody>\n{rows}\n"
        "</tbody>\n</table>",
        f'<p class="note">{html.escape(note)}</p>',
        "</body>",
        "</html>",
        "",
    ])


def write_html_report(result: EvaluationResult, path: str,
                      title: str = "Road sign evaluation", sign_label: str = "",
                      reference_label: str = "") -> None:
    """Write :func:`render_html_report` to ``path`` atomically (UTF-8).

    The document goes to a temporary file in the same folder which then replaces
    ``path`` with the user's normal permissions (0666 less the umask), so a failure never
    leaves a partial report (nor the temporary file).
    """
    document = render_html_report(result, title=title, sign_label=sign_label,
                                  reference_label=reference_label)
    write_text_atomically(path, document)
