"""The review panel in the real QGIS desktop (see conftest.py and drive_panel.py): the plugin
loads with its panel, the panel follows the map's selection, verdicts given with keys and
buttons reach the layer through its edit buffer, undo takes one back, the map follows the
current sign, saving writes the fields to the file, a layer without the sign fields is
named for what it lacks, and unloading removes the panel."""
import re

import pytest
from helpers.reviewdata import SIGNS, X0, Y0

ISO = re.compile(r"^\d{4}-\d\d-\d\dT\d\d:\d\d:\d\d\+00:00$")
EMPTY = {"review_status": None, "reviewed_class": None, "reviewed_code": None, "reviewed_at": None}


def review(step, sign_id):
    values = dict(step["review"][str(sign_id)])
    values["reviewed_at"] = bool(values.get("reviewed_at")) and bool(ISO.match(values["reviewed_at"]))
    return values


def at_sign(step, sign_id):
    """The map is centred on the sign."""
    _, dx, dy = SIGNS[sign_id][:3]
    return step["canvas_center"] == [pytest.approx(X0 + dx, abs=0.01), pytest.approx(Y0 + dy, abs=0.01)]


def test_no_error_in_qgis(gui_run):
    assert gui_run["errors"] == []


def test_the_plugin_adds_the_panel_and_its_action(gui_run):
    assert gui_run["plugin_loaded"]
    assert gui_run["action_text"] == "Sign review panel"
    assert gui_run["panel_hidden_at_start"] and gui_run["panel_visible"]


def test_the_panel_shows_the_first_unreviewed_sign_with_its_chips(gui_run):
    start = gui_run["steps"]["start"]
    assert start["current"] == 1 and start["selected"] == [1]
    assert start["message"].startswith("<b>Sign 1</b> (1 of 5)") and "0 of 5 reviewed" in start["message"]
    assert (start["class_text"], start["code_text"], start["score_text"], start["condition_text"]) == \
        ("prohibitory", "206", "0.83", "good")
    assert "seen in 3 panorama(s): p00.jpg, p01.jpg, p02.jpg" in start["sources_text"]
    # the layer's chip (from the best panorama), then one cut from every other panorama that saw it
    assert start["chips"] == ["best · p02.jpg (review chip)", "p01.jpg · 11 m", "p00.jpg · 16 m"]
    # a sign without a chip in the layer: one cut from every panorama, best first
    assert gui_run["steps"]["accept_key"]["chips"] == ["best · p08.jpg · 7 m", "p07.jpg · 11 m", "p06.jpg · 16 m",
                                                       "p05.jpg · 21 m"]
    assert start["buttons_enabled"] == [True] * 4 and not start["editable"]


def test_a_click_on_the_map_selects_the_sign_in_the_panel(gui_run):
    step = gui_run["steps"]["select_on_map"]
    assert step["selected"] == [3] and step["current"] == 3
    assert step["class_text"] == "mandatory" and step["code_text"] == "(none)"
    assert at_sign(step, 3)
    assert step["review"]["3"] == {}  # no review fields yet


def test_accept_with_the_key_writes_through_the_edit_buffer_and_steps_on(gui_run):
    step = gui_run["steps"]["accept_key"]
    assert review(step, 3) == dict(EMPTY, review_status="accepted", reviewed_at=True)
    assert all(review(step, k) == dict(EMPTY, reviewed_at=False) for k in (1, 2, 4, 5))
    assert step["editable"] and step["undo_index"] == 1
    assert step["current"] == 4 and step["selected"] == [4] and at_sign(step, 4)
    assert "1 of 5 reviewed" in step["message"]


def test_reject_with_the_button(gui_run):
    step = gui_run["steps"]["reject_button"]
    assert review(step, 4) == dict(EMPTY, review_status="rejected", reviewed_at=True)
    assert step["current"] == 5 and step["undo_index"] == 2


def test_change_the_code_then_undo(gui_run):
    changed = gui_run["steps"]["change_code"]
    assert review(changed, 5) == dict(EMPTY, review_status="corrected", reviewed_code="206-1", reviewed_at=True)
    assert changed["current"] == 1                 # the next unreviewed sign, round the end
    undone = gui_run["steps"]["undo"]
    assert review(undone, 5) == dict(EMPTY, reviewed_at=False)
    assert review(undone, 3)["review_status"] == "accepted" and review(undone, 4)["review_status"] == "rejected"
    assert undone["undo_index"] == 2 and undone["current"] == 5 and at_sign(undone, 5)


def test_change_the_class_look_again_and_step_back(gui_run):
    step = gui_run["steps"]["change_class"]
    assert review(step, 5) == dict(EMPTY, review_status="corrected", reviewed_class="stop", reviewed_at=True)
    assert step["current"] == 1
    unsure = gui_run["steps"]["unsure_key"]
    assert review(unsure, 1) == dict(EMPTY, review_status="unsure", reviewed_at=True)
    assert unsure["current"] == 2
    assert gui_run["steps"]["previous_key"]["current"] == 1


def test_the_panorama_view_frames_the_sign(gui_run):
    view = gui_run["panorama_view"]
    assert view["shown"] and (view["width"], view["height"]) == (960, 540)
    assert view["title"] == "Panorama view: sign 1" and view["caption"].startswith("p02.jpg")
    red, green, blue = view["centre"]
    assert red > 200 and green < 60 and blue < 60     # the red disc of sign 1 at the centre
    assert view["corner"] == [pytest.approx(90, abs=12)] * 3  # the grey panorama around it


def test_saved_edits_reach_the_file(gui_run):
    saved = gui_run["saved"]
    assert saved["fields"][-4:] == ["review_status", "reviewed_class", "reviewed_code", "reviewed_at"]
    assert {k: v["review_status"] for k, v in saved["review"].items()} == \
        {"1": "unsure", "2": None, "3": "accepted", "4": "rejected", "5": "corrected"}
    assert saved["review"]["5"]["reviewed_class"] == "stop" and saved["review"]["5"]["reviewed_code"] is None
    assert saved["still_editable"] and not saved["modified"]


def test_a_layer_without_the_sign_fields_is_named_for_them(gui_run):
    step = gui_run["steps"]["bare_layer"]
    assert "The layer bare lacks the field(s) sign_id, score, source_images." in step["message"]
    assert step["buttons_enabled"] == [False] * 4


def test_unloading_removes_the_panel(gui_run):
    assert gui_run["after_unload"] == {"docks": [], "plugin_panel": None}


def test_screenshots(gui_run):
    import os

    from PIL import Image

    for name, least in (("review_panel.png", (300, 500)), ("review_window.png", (1000, 700)),
                        ("panorama_view.png", (900, 500))):
        path = os.path.join(gui_run["out"], name)
        with Image.open(path) as image:
            assert image.size[0] >= least[0] and image.size[1] >= least[1], name
            assert len(image.convert("RGB").getcolors(1 << 20) or range(1000)) > 50, name  # not blank
