"""Tests of ``core.evaluate``: matching, scores, the reference CSV and the HTML report.

Expected values are worked out by hand in the comments next to each case.
"""
import itertools
import math
import os
from html.parser import HTMLParser

import numpy as np
import pytest

from roadsigns.core.errors import InputError, Message
from roadsigns.core.evaluate import (
    FALSE,
    MATCHED,
    MISSED,
    OUTPUT_NAMES,
    SignSet,
    azimuth_difference_deg,
    confusions_text,
    evaluate,
    match_signs,
    read_reference_csv,
    render_html_report,
    write_html_report,
)

# A realistic UTM origin: coordinates are offsets from it.
E0, N0, H0 = 500000.0, 5300000.0, 200.0


def make_set(prefix, offsets, classes=None, height=None, azimuth=None, images=None, codes=None):
    offsets = np.asarray(offsets, dtype=float).reshape(-1, 3)
    n = len(offsets)
    return SignSet(ids=[f"{prefix}{k + 1}" for k in range(n)],
                   classes=classes if classes is not None else ["warning"] * n,
                   xyz=offsets + [E0, N0, H0],
                   height=height if height is not None else np.full(n, 2.0),
                   azimuth_deg=azimuth if azimuth is not None else np.zeros(n),
                   images=images, codes=codes)


def pairs(matching, signs, reference):
    return sorted((signs.ids[i], reference.ids[j])
                  for i, j in zip(matching.sign_index, matching.reference_index))


# --------------------------------------------------------------------------- scores

def test_exact_match():
    reference = make_set("R", [[0, 0, 0], [10, 0, 0], [0, 20, 1]],
                         classes=["stop", "yield", "warning"])
    signs = make_set("S", [[0, 0, 0], [10, 0, 0], [0, 20, 1]],
                     classes=["stop", "yield", "warning"])
    result = evaluate(signs, reference, 1.0)
    assert (result.tp, result.fp, result.fn) == (3, 0, 0)
    assert result.precision == result.recall == result.f1 == 1.0
    assert result.class_accuracy == 1.0
    assert result.median_error_m == 0.0 and result.p95_error_m == 0.0
    assert result.median_height_error_m == 0.0 and result.median_azimuth_error_deg == 0.0
    assert pairs(result.matching, signs, reference) == [("S1", "R1"), ("S2", "R2"), ("S3", "R3")]
    assert [row.status for row in result.rows] == [MATCHED] * 3


def test_one_missed():
    reference = make_set("R", [[0, 0, 0], [10, 0, 0], [20, 0, 0]])
    signs = make_set("S", [[0.3, 0.4, 0], [20, 0, 0]])  # R2 has no sign
    result = evaluate(signs, reference, 1.0)
    assert (result.tp, result.fp, result.fn) == (2, 0, 1)
    assert result.precision == 1.0
    assert result.recall == pytest.approx(2 / 3)
    assert result.f1 == pytest.approx(0.8)  # 2 * 1 * 2/3 / (1 + 2/3)
    # distances 0.5 and 0 -> median 0.25, p95 = 0 + 0.95 * 0.5
    assert result.median_error_m == pytest.approx(0.25)
    assert result.p95_error_m == pytest.approx(0.475)
    statuses = [(row.status, row.reference_id, row.sign_id) for row in result.rows]
    assert statuses == [(MATCHED, "R1", "S1"), (MISSED, "R2", ""), (MATCHED, "R3", "S2")]


def test_one_false():
    reference = make_set("R", [[0, 0, 0], [10, 0, 0]])
    signs = make_set("S", [[0, 0, 0], [5, 5, 0], [10, 0, 0]])  # S2 is false
    result = evaluate(signs, reference, 1.0)
    assert (result.tp, result.fp, result.fn) == (2, 1, 0)
    assert result.precision == pytest.approx(2 / 3)
    assert result.recall == 1.0
    assert result.f1 == pytest.approx(0.8)
    assert [(row.status, row.sign_id) for row in result.rows][-1] == (FALSE, "S2")
    assert sorted(result.matching.unmatched_signs) == [1]


def test_wrong_class_counts_as_match_but_lowers_class_accuracy():
    reference = make_set("R", [[0, 0, 0], [10, 0, 0], [20, 0, 0]],
                         classes=["stop", "yield", "warning"])
    signs = make_set("S", [[0, 0, 0], [10, 0, 0], [20, 0, 0]],
                     classes=["stop", "warning", "warning"])
    result = evaluate(signs, reference, 1.0)
    assert result.tp == 3 and result.precision == 1.0 and result.recall == 1.0
    assert result.class_accuracy == pytest.approx(2 / 3)
    assert [row.class_agrees for row in result.rows] == [True, False, True]


def test_error_statistics_by_hand():
    reference = make_set("R", [[0, 0, 0], [10, 0, 0], [20, 0, 0], [30, 0, 0]],
                         height=[2.0, 2.5, 3.0, 2.2], azimuth=[1.0, 80.0, 0.0, 350.0])
    # offsets (dx, dy, dz): 3D distance / horizontal / |dz|
    #   (0.3, 0.4, 0)   0.5 / 0.5 / 0
    #   (0, 0, -0.2)    0.2 / 0   / 0.2
    #   (0.6, 0.8, 0)   1.0 / 1.0 / 0
    #   (0, 0.3, 0.4)   0.5 / 0.3 / 0.4
    signs = make_set("S", [[0.3, 0.4, 0], [10, 0, -0.2], [20.6, 0.8, 0], [30, 0.3, 0.4]],
                     height=[2.1, 2.2, 3.0, 2.4],       # errors +0.1 -0.3 0 +0.2
                     azimuth=[359.0, 90.0, 180.0, 10.0])  # errors 2, 10, 180, 20
    result = evaluate(signs, reference, 1.5)
    assert result.tp == 4
    # distances sorted 0.2 0.5 0.5 1.0: median 0.5; p95 at rank 0.95 * 3 = 2.85
    assert result.median_error_m == pytest.approx(0.5)
    assert result.p95_error_m == pytest.approx(0.5 + 0.85 * 0.5)
    assert result.median_horizontal_error_m == pytest.approx(0.4)  # 0 0.3 | 0.5 1.0
    assert result.median_vertical_error_m == pytest.approx(0.1)    # 0 0 | 0.2 0.4
    assert result.median_height_error_m == pytest.approx(0.15)     # 0 0.1 | 0.2 0.3
    assert result.median_azimuth_error_deg == pytest.approx(15.0)  # 2 10 | 20 180
    row = result.rows[1]
    assert row.dz_m == pytest.approx(-0.2) and row.height_error_m == pytest.approx(-0.3)
    assert row.horizontal_m == pytest.approx(0.0, abs=1e-9)
    outputs = result.as_outputs()
    assert tuple(outputs) == OUTPUT_NAMES
    assert outputs["TP"] == 4 and outputs["MEDIAN_AZIMUTH_ERROR"] == pytest.approx(15.0)
    assert outputs["P95_ERROR"] == pytest.approx(0.925)


def test_size_error_is_the_larger_of_the_width_and_panel_height_errors():
    reference = make_set("R", [[0, 0, 0], [10, 0, 0], [20, 0, 0], [30, 0, 0], [40, 0, 0]])
    reference.width_m = np.array([0.9, 0.6, 0.6, 0.6, 0.6])
    reference.panel_height_m = np.array([0.78, 0.6, 0.6, 0.6, 0.6])
    signs = make_set("S", [[0, 0, 0], [10, 0, 0], [20, 0, 0], [30, 0, 0], [40, 0, 0]])
    # width / panel height errors -> size error:
    #   a strip of a yield sign: -0.82 / +0.03 -> 0.82
    #   +0.01 / -0.02 -> 0.02;  +0.05 / NaN -> 0.05 (the known one);  NaN / NaN -> left out
    #   -0.1 / +0.2 -> 0.2
    signs.width_m = np.array([0.08, 0.61, 0.65, np.nan, 0.5])
    signs.panel_height_m = np.array([0.81, 0.58, np.nan, np.nan, 0.8])
    result = evaluate(signs, reference, 1.0)
    # sizes sorted 0.02 0.05 0.2 0.82: median 0.125; p95 at rank 0.95 * 3 = 2.85 -> 0.2 + 0.85 * 0.62
    assert result.median_size_error_m == pytest.approx(0.125)
    assert result.p95_size_error_m == pytest.approx(0.2 + 0.85 * 0.62)
    assert result.rows[0].width_error_m == pytest.approx(-0.82)
    assert result.rows[0].panel_height_error_m == pytest.approx(0.03)
    assert math.isnan(result.rows[3].width_error_m)
    outputs = result.as_outputs()
    assert outputs["MEDIAN_SIZE_ERROR"] == pytest.approx(0.125)
    assert outputs["P95_SIZE_ERROR"] == pytest.approx(0.727)
    assert "Width error" in render_html_report(result) and "\u2212" in render_html_report(result)
    # no sizes known at all: undefined, not zero
    signs.width_m[:] = np.nan
    signs.panel_height_m[:] = np.nan
    unknown = evaluate(signs, reference, 1.0)
    assert math.isnan(unknown.median_size_error_m) and math.isnan(unknown.p95_size_error_m)


def test_unknown_azimuth_and_height_are_left_out_of_their_statistics():
    reference = make_set("R", [[0, 0, 0], [10, 0, 0], [20, 0, 0]],
                         azimuth=[0.0, 0.0, 0.0], height=[2.0, 2.0, 2.0])
    signs = make_set("S", [[0, 0, 0], [10, 0, 0], [20, 0, 0]],
                     azimuth=[10.0, np.nan, 30.0], height=[2.5, 2.1, np.nan])
    result = evaluate(signs, reference, 1.0)
    assert result.median_azimuth_error_deg == pytest.approx(20.0)  # of 10 and 30
    assert result.median_height_error_m == pytest.approx(0.3)      # of 0.5 and 0.1
    assert math.isnan(result.rows[1].azimuth_error_deg)


@pytest.mark.parametrize("a, b, expected", [(359, 1, 2), (1, 359, 2), (0, 180, 180),
                                            (90, 270, 180), (-10, 10, 20), (720, 5, 5),
                                            (45, 44, 1)])
def test_azimuth_difference_wraps(a, b, expected):
    assert azimuth_difference_deg(a, b) == pytest.approx(expected)


def test_azimuth_wrap_in_evaluation():
    reference = make_set("R", [[0, 0, 0]], azimuth=[1.0])
    signs = make_set("S", [[0, 0, 0]], azimuth=[359.0])
    assert evaluate(signs, reference, 1.0).median_azimuth_error_deg == pytest.approx(2.0)


def test_radius_boundary_is_inclusive():
    reference = make_set("R", [[0, 0, 0]])
    assert evaluate(make_set("S", [[0, 2.0, 0]]), reference, 2.0).tp == 1
    assert evaluate(make_set("S", [[0, 2.001, 0]]), reference, 2.0).tp == 0
    assert evaluate(make_set("S", [[1.2, 1.6, 0]]), reference, 2.0).tp == 1  # 3-4-5 scaled
    assert evaluate(make_set("S", [[0, 0, 2.0]]), reference, 2.0).tp == 1   # 3D, not 2D
    assert evaluate(make_set("S", [[0, 0, 2.01]]), reference, 2.0).tp == 0


@pytest.mark.parametrize("radius", [0.0, -1.0, float("nan"), float("inf")])
def test_bad_radius(radius):
    with pytest.raises(InputError, match="match radius"):
        evaluate(make_set("S", [[0, 0, 0]]), make_set("R", [[0, 0, 0]]), radius)


def test_non_finite_position_is_an_input_error():
    signs = make_set("S", [[0, 0, 0], [np.nan, 0, 0]])
    with pytest.raises(InputError, match="S2"):
        evaluate(signs, make_set("R", [[0, 0, 0]]), 1.0)


def test_empty_sets_do_not_crash():
    reference = make_set("R", [[0, 0, 0], [5, 0, 0]])
    no_signs = make_set("S", np.zeros((0, 3)))
    result = evaluate(no_signs, reference, 1.0)
    assert (result.tp, result.fp, result.fn) == (0, 0, 2)
    assert math.isnan(result.precision) and result.recall == 0.0 and result.f1 == 0.0
    assert math.isnan(result.class_accuracy) and math.isnan(result.median_error_m)
    assert math.isnan(result.p95_error_m)
    assert [row.status for row in result.rows] == [MISSED, MISSED]
    both_empty = evaluate(no_signs, make_set("R", np.zeros((0, 3))), 1.0)
    assert all(math.isnan(both_empty.as_outputs()[name])
               for name in ("PRECISION", "RECALL", "F1"))
    no_matches = evaluate(make_set("S", [[50, 0, 0]]), reference, 1.0)
    assert (no_matches.tp, no_matches.fp, no_matches.fn) == (0, 1, 2)
    assert no_matches.precision == 0.0 and no_matches.f1 == 0.0


# --------------------------------------------------------------------------- optimality

def greedy_nearest_pairs(signs, reference, radius):
    """Greedy matching for contrast: repeatedly take the globally closest free pair."""
    d = np.linalg.norm(signs.xyz[:, None, :] - reference.xyz[None, :, :], axis=2)
    result, used_s, used_r = [], set(), set()
    for flat in np.argsort(d, axis=None, kind="stable"):
        i, j = np.unravel_index(flat, d.shape)
        if d[i, j] <= radius and i not in used_s and j not in used_r:
            result.append((signs.ids[i], reference.ids[j]))
            used_s.add(i)
            used_r.add(j)
    return sorted(result)


def test_greedy_pairs_wrongly_optimal_assignment_does_not():
    # On a line: S1 at 0, R1 at 1.1, S2 at 2.0, R2 at 3.15; radius 1.2.
    # Allowed pairs: S1-R1 1.1, S2-R1 0.9, S2-R2 1.15 (S1-R2 = 3.15 is too far).
    # Greedy takes the closest pair S2-R1 first and leaves S1 and R2 unmatched.
    # The optimum is S1-R1 + S2-R2 (2 matches, total 2.25). A naive cost with
    # "forbidden = radius" would prefer S2-R1 + forbidden (0.9 + 1.2 = 2.1 < 2.25).
    reference = make_set("R", [[1.1, 0, 0], [3.15, 0, 0]])
    signs = make_set("S", [[0, 0, 0], [2.0, 0, 0]])
    radius = 1.2
    assert greedy_nearest_pairs(signs, reference, radius) == [("S2", "R1")]
    matching = match_signs(signs, reference, radius)
    assert pairs(matching, signs, reference) == [("S1", "R1"), ("S2", "R2")]
    assert matching.distance_m.sum() == pytest.approx(2.25)
    result = evaluate(signs, reference, radius)
    assert (result.tp, result.fp, result.fn) == (2, 0, 0)


def test_same_number_of_matches_minimal_total_distance():
    # Distances S1-R1 0.5, S1-R2 0.6, S2-R1 0.6, S2-R2 1.0 (all within radius 2):
    # greedy takes S1-R1 then S2-R2 (total 1.5); the optimum crosses (total 1.2).
    s1, r1, r2 = np.array([0.0, 0, 0]), np.array([0.5, 0, 0]), np.array([-0.6, 0, 0])
    x = (0.64 / 1.1 - 0.1) / 2          # |S2 - R1| = 0.6 and |S2 - R2| = 1.0
    s2 = np.array([x, math.sqrt(0.36 - (x - 0.5) ** 2), 0])
    signs = make_set("S", [s1, s2])
    reference = make_set("R", [r1, r2])
    assert greedy_nearest_pairs(signs, reference, 2.0) == [("S1", "R1"), ("S2", "R2")]
    matching = match_signs(signs, reference, 2.0)
    assert pairs(matching, signs, reference) == [("S1", "R2"), ("S2", "R1")]
    assert matching.distance_m.sum() == pytest.approx(1.2)


def brute_force_best(d, radius):
    """(most matches, least total distance) over all partial one-to-one matchings."""
    n, m = d.shape
    best = (0, 0.0)
    for target in itertools.product(range(-1, m), repeat=n):
        chosen = [(i, j) for i, j in enumerate(target) if j >= 0]
        if len({j for _, j in chosen}) < len(chosen):
            continue
        if any(d[i, j] > radius for i, j in chosen):
            continue
        total = sum(d[i, j] for i, j in chosen)
        if (len(chosen), -total) > (best[0], -best[1]):
            best = (len(chosen), total)
    return best


def test_matching_agrees_with_brute_force_on_random_layouts():
    rng = np.random.default_rng(7)
    for _ in range(150):
        n, m = rng.integers(0, 5, size=2)
        signs = make_set("S", rng.uniform(0, 4, size=(n, 3)))
        reference = make_set("R", rng.uniform(0, 4, size=(m, 3)))
        radius = float(rng.uniform(0.5, 3.0))
        d = np.linalg.norm(signs.xyz[:, None, :] - reference.xyz[None, :, :], axis=2)
        count, total = brute_force_best(d.reshape(n, m), radius)
        matching = match_signs(signs, reference, radius)
        assert matching.sign_index.size == count
        assert matching.distance_m.sum() == pytest.approx(total, abs=1e-9)
        assert len(set(matching.sign_index)) == count == len(set(matching.reference_index))
        assert np.all(matching.distance_m <= radius)
        assert (matching.unmatched_signs.size, matching.unmatched_reference.size) == \
            (n - count, m - count)


def test_separate_clusters_are_solved_independently():
    # Two copies of the greedy-trap layout 1 km apart plus an isolated exact match.
    base_s, base_r = [[0, 0, 0], [2.0, 0, 0]], [[1.1, 0, 0], [3.15, 0, 0]]
    far = np.array([1000.0, 0, 0])
    signs = make_set("S", base_s + [list(np.add(p, far)) for p in base_s] + [[0, 500, 0]])
    reference = make_set("R", base_r + [list(np.add(p, far)) for p in base_r] + [[0, 500, 0]])
    matching = match_signs(signs, reference, 1.2)
    assert pairs(matching, signs, reference) == [("S1", "R1"), ("S2", "R2"), ("S3", "R3"),
                                                 ("S4", "R4"), ("S5", "R5")]
    assert list(matching.reference_index) == [0, 1, 2, 3, 4]  # sorted by reference


# --------------------------------------------------------------------------- HTML report

class _Checker(HTMLParser):
    VOID = {"meta", "br", "img", "hr", "link", "input"}

    def __init__(self):
        super().__init__(convert_charrefs=True)
        self.stack, self.tags, self.text, self.errors = [], [], [], []

    def handle_starttag(self, tag, attrs):
        self.tags.append((tag, dict(attrs)))
        if tag not in self.VOID:
            self.stack.append(tag)

    def handle_endtag(self, tag):
        if not self.stack or self.stack[-1] != tag:
            self.errors.append(f"unexpected </{tag}> with open {self.stack}")
        else:
            self.stack.pop()

    def handle_data(self, data):
        self.text.append(data)


def _parse(document):
    checker = _Checker()
    checker.feed(document)
    checker.close()
    assert checker.errors == [] and checker.stack == []
    return checker


def test_html_report_lists_every_sign_and_escapes_text(tmp_path):
    reference = make_set("R", [[0, 0, 0], [10, 0, 0], [20, 0, 0]],
                         classes=["stop", "<b>", "warning"])
    signs = make_set("S", [[0.3, 0.4, 0], [10, 0, 0], [40, 0, 0]],
                     classes=["stop", "x & y", "yield"], images=["a.jpg", "b.jpg", "c<d>.jpg"])
    result = evaluate(signs, reference, 1.0)
    path = tmp_path / "report.html"
    write_html_report(result, str(path), title="Eval <test>", sign_label="signs & co",
                      reference_label="truth.csv")
    document = path.read_text(encoding="utf-8")
    checker = _parse(document)
    tags = [tag for tag, _ in checker.tags]
    assert "b" not in tags and "test" not in tags and "d" not in tags
    assert not any(tag in ("script", "link", "img") for tag in tags)  # self-contained
    assert "style" in tags
    text = "".join(checker.text)
    for needle in ("R1", "R2", "R3", "S1", "S2", "S3", "<b>", "x & y", "c<d>.jpg",
                   "Eval <test>", "signs & co", "truth.csv"):
        assert needle in text
    rows = [attrs.get("class") for tag, attrs in checker.tags if tag == "tr" and attrs]
    assert rows == [MATCHED, MATCHED, MISSED, FALSE]
    assert "0.500\u00a0m" in text                      # S1-R1 distance with its unit
    assert "0.667" in text and "0.800" not in text     # precision 2/3, recall 2/3, F1 2/3
    assert list(tmp_path.iterdir()) == [path]          # no temporary file left


def test_html_report_of_empty_result_is_valid():
    result = evaluate(make_set("S", np.zeros((0, 3))), make_set("R", [[0, 0, 0]]), 1.0)
    text = "".join(_parse(render_html_report(result)).text)
    assert "R1" in text and "\u2014" in text  # undefined precision shown as a dash


def test_html_report_failure_leaves_no_partial_file(tmp_path, monkeypatch):
    result = evaluate(make_set("S", [[0, 0, 0]]), make_set("R", [[0, 0, 0]]), 1.0)
    path = tmp_path / "report.html"
    path.write_text("previous report", encoding="utf-8")

    def failing_replace(source, target):
        raise OSError("disk full")

    monkeypatch.setattr(os, "replace", failing_replace)
    with pytest.raises(OSError, match="disk full"):
        write_html_report(result, str(path))
    assert path.read_text(encoding="utf-8") == "previous report"
    assert list(tmp_path.iterdir()) == [path]


# --------------------------------------------------------------------------- reference CSV

HEADER = "sign_id,class,x,y,z,height,width,panel_height,azimuth"


def write(tmp_path, text, name="reference.csv"):
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return str(path)


def test_read_reference_csv(tmp_path):
    path = write(tmp_path, HEADER + "\n"
                 "r1,stop,500000.5,5300000.25,201.5,2.1,0.6,0.6,90\n"
                 "\n"
                 "r2,warning,500010,5300000,202,2.4,0.9,0.8,359.5\n")
    reference = read_reference_csv(path)
    assert reference.ids == ["r1", "r2"] and reference.classes == ["stop", "warning"]
    np.testing.assert_allclose(reference.xyz, [[500000.5, 5300000.25, 201.5],
                                               [500010, 5300000, 202]])
    np.testing.assert_allclose(reference.height, [2.1, 2.4])
    np.testing.assert_allclose(reference.azimuth_deg, [90, 359.5])
    np.testing.assert_allclose(reference.width_m, [0.6, 0.9])
    np.testing.assert_allclose(reference.panel_height_m, [0.6, 0.8])


@pytest.mark.parametrize("delimiter", [";", "\t"])
def test_read_reference_csv_other_delimiters_and_header_case(tmp_path, delimiter):
    header = delimiter.join(name.upper() if k % 2 else name
                            for k, name in enumerate(HEADER.split(",") + ["note"]))
    row = delimiter.join(["r1", "yield", "1", "2", "3", "2", "0.9", "0.8", "45", "extra"])
    reference = read_reference_csv(write(tmp_path, header + "\n" + row + "\n"))
    assert reference.ids == ["r1"] and reference.classes == ["yield"]
    np.testing.assert_allclose(reference.xyz, [[1, 2, 3]])
    assert reference.azimuth_deg[0] == 45.0


def test_reference_missing_columns_are_named(tmp_path):
    path = write(tmp_path, "sign_id,class,x,y,z,width\nr1,stop,1,2,3,0.6\n")
    with pytest.raises(InputError) as info:
        read_reference_csv(path)
    message = str(info.value)
    assert path in message
    assert "missing column(s) height, panel_height, azimuth" in message
    assert "found sign_id, class, x, y, z, width" in message
    assert HEADER.replace(",", ", ") in message  # the expected columns


@pytest.mark.parametrize("value, found", [("abc", "abc"), ("nan", "nan"), ("", "")])
def test_reference_bad_number_names_line_and_field(tmp_path, value, found):
    path = write(tmp_path, HEADER + "\n"
                 "r1,stop,1,2,3,2,0.6,0.6,90\n"
                 f"r2,stop,1,2,{value},2,0.6,0.6,90\n")
    with pytest.raises(InputError) as info:
        read_reference_csv(path)
    message = str(info.value)
    assert path in message and "line 3" in message and "'z'" in message
    assert f"'{found}'" in message


def test_reference_duplicate_id_and_empty_class(tmp_path):
    path = write(tmp_path, HEADER + "\nr1,stop,1,2,3,2,0.6,0.6,90\nr1,stop,5,2,3,2,0.6,0.6,90\n")
    with pytest.raises(InputError, match=r"line 3: sign_id 'r1' already used on line 2"):
        read_reference_csv(path)
    path = write(tmp_path, HEADER + "\nr1,,1,2,3,2,0.6,0.6,90\n", name="b.csv")
    with pytest.raises(InputError, match=r"line 2, field 'class': empty value"):
        read_reference_csv(path)


def test_reference_empty_file_and_header_only(tmp_path):
    with pytest.raises(InputError, match="empty"):
        read_reference_csv(write(tmp_path, ""))
    with pytest.raises(InputError, match="no data rows"):
        read_reference_csv(write(tmp_path, HEADER + "\n", name="h.csv"))


# --------------------------------------------------------------------------- sign codes

LINE = [[10.0 * k, 0, 0] for k in range(8)]


def test_code_accuracy_no_code_and_confusions_by_hand():
    # R1..R8 on a line, one sign on each; reference codes and sign codes:
    #   R1 DE:206       S1 DE:206       right
    #   R2 DE:274[50]   S2 DE:274[30]   wrong
    #   R3 DE:274[50]   S3 DE:274[30]   wrong (same confusion: count 2)
    #   R4 DE:274[50]   S4 ""           wrong, no code
    #   R5 DE:205       S5 None         wrong, no code (None is no code)
    #   R6 ""           S6 DE:206       not compared: no reference code
    #   R7 " DE:123 "   S7 DE:123       right (blanks removed)
    #   R8 DE:101       S8 DE:102       wrong
    # compared 7, right 2 -> 2/7; no code 2
    reference = make_set("R", LINE, codes=["DE:206", "DE:274[50]", "DE:274[50]", "DE:274[50]",
                                          "DE:205", "", " DE:123 ", "DE:101"])
    signs = make_set("S", LINE, codes=["DE:206", "DE:274[30]", "DE:274[30]", "", None,
                                       "DE:206", "DE:123", "DE:102"])
    result = evaluate(signs, reference, 1.0)
    assert result.codes_scored and result.code_note is None
    assert result.code_compared == 7
    assert result.code_accuracy == pytest.approx(2 / 7)
    assert result.no_code == 2
    # most frequent first; ties by reference code, then sign code ("" before any code)
    assert result.code_confusions == [("DE:274[50]", "DE:274[30]", 2), ("DE:101", "DE:102", 1),
                                      ("DE:205", "", 1), ("DE:274[50]", "", 1)]
    assert confusions_text(result.code_confusions) == (
        "DE:274[50] -> DE:274[30]: 2; DE:101 -> DE:102: 1; DE:205 -> (none): 1; "
        "DE:274[50] -> (none): 1")
    outputs = result.as_outputs()
    assert tuple(outputs) == OUTPUT_NAMES
    assert outputs["CODE_ACCURACY"] == pytest.approx(2 / 7)
    assert (outputs["CODE_COMPARED"], outputs["NO_CODE"]) == (7, 2)
    assert [row.code_agrees for row in result.rows] == [True, False, False, False, False, None,
                                                        True, False]
    assert (result.rows[3].sign_code, result.rows[3].reference_code) == ("", "DE:274[50]")


def test_codes_only_of_matches_count():
    # S2 is false (no reference near it), R2 is missed: neither is compared, whatever its code.
    reference = make_set("R", [[0, 0, 0], [10, 0, 0]], codes=["DE:206", "DE:205"])
    signs = make_set("S", [[0, 0, 0], [50, 0, 0]], codes=["DE:206", "DE:999"])
    result = evaluate(signs, reference, 1.0)
    assert (result.tp, result.code_compared, result.code_accuracy) == (1, 1, 1.0)
    assert result.code_confusions == [] and confusions_text(result.code_confusions) == ""
    assert [row.code_agrees for row in result.rows] == [True, None, None]


def test_code_accuracy_is_undefined_without_reference_codes():
    result = evaluate(make_set("S", [[0, 0, 0]], codes=["DE:206"]),
                      make_set("R", [[0, 0, 0]], codes=[""]), 1.0)
    assert result.codes_scored and result.code_compared == 0 and result.no_code == 0
    assert math.isnan(result.code_accuracy)
    assert result.as_outputs()["CODE_COMPARED"] == 0


@pytest.mark.parametrize("sign_codes, reference_codes, why", [
    (["DE:206"], None, "the reference has no 'code' column"),
    (None, ["DE:206"], "the signs have no 'code' field"),
    (None, None, "neither the signs nor the reference"),
])
def test_codes_missing_on_either_side_are_not_scored(sign_codes, reference_codes, why):
    reference = make_set("R", [[0, 0, 0], [10, 0, 0]], classes=["stop", "yield"],
                         codes=None if reference_codes is None else reference_codes * 2)
    signs = make_set("S", [[0, 0, 0], [10, 0, 0]], classes=["stop", "stop"],
                     codes=None if sign_codes is None else ["DE:101"] * 2)
    result = evaluate(signs, reference, 1.0)
    assert (result.tp, result.class_accuracy) == (2, 0.5)  # the rest as before
    assert not result.codes_scored
    assert isinstance(result.code_note, Message) and why in result.code_note
    assert result.code_note.startswith("Code accuracy not computed")
    outputs = result.as_outputs()
    assert all(math.isnan(outputs[name]) for name in ("CODE_ACCURACY", "CODE_COMPARED", "NO_CODE"))
    assert result.code_confusions == [] and all(row.code_agrees is None for row in result.rows)
    checker = _parse(render_html_report(result))
    text = "".join(checker.text)
    assert str(result.code_note) in text
    assert "Code accuracy (of" not in text and "Code confusions" not in text
    assert "Sign code" not in text and "Reference code" not in text


def test_html_report_shows_codes_and_confusions():
    reference = make_set("R", [[0, 0, 0], [10, 0, 0], [20, 0, 0], [30, 0, 0]],
                         codes=["DE:206", "DE:274[50]", "DE:205", "DE:<1>"])
    signs = make_set("S", [[0, 0, 0], [10, 0, 0], [20, 0, 0], [30, 0, 0]],
                     codes=["DE:206", "DE:274[30]", "", "DE:<1>"])
    result = evaluate(signs, reference, 1.0)
    document = render_html_report(result)
    checker = _parse(document)
    text = "".join(checker.text)
    assert "Code accuracy (of matches with a reference code)0.500" in text
    assert "Codes compared4" in text and "Compared signs without a code1" in text
    # the confusions table: reference code, sign code, count
    assert "Code confusions" in text
    assert "DE:205(none)1" in text and "DE:274[50]DE:274[30]1" in text
    assert "DE:<1>" in text and "DE:<1>" not in document  # escaped
    # the per-sign table has the code columns after the classes, wrong codes marked
    assert "Sign classReference idReference classSign codeReference code3D distance" in text
    wrong = [attrs for tag, attrs in checker.tags if tag == "td" and attrs.get("class") == "wrongcode"]
    assert len(wrong) == 4  # two rows, two cells each


def test_read_reference_csv_code_column(tmp_path):
    path = write(tmp_path, HEADER + ",faded,code\n"
                 "r1,stop,1,2,3,2,0.6,0.6,90,0,DE:206\n"
                 "r2,information,5,2,3,2,0.6,0.6,90,0,\n"
                 "r3,prohibitory,9,2,3,2,0.6,0.6,90,1,DE:274[50]\n")
    assert read_reference_csv(path).codes == ["DE:206", "", "DE:274[50]"]
    without = write(tmp_path, HEADER + "\nr1,stop,1,2,3,2,0.6,0.6,90\n", name="old.csv")
    assert read_reference_csv(without).codes is None
