"""The current step of long work (``Progress.step``) and how often it is shown
(``StepThrottle``); the stages' steps are tested beside each stage."""
from roadsigns.core.errors import SILENT, Message, Progress, StepThrottle


def test_a_step_goes_to_the_children_but_not_to_work_in_other_threads():
    steps = []
    progress = Progress(on_step=steps.append)
    child = progress.sub(0.2, 0.6).sub(0.5, 1.0)
    message = child.step("Panorama {n} of {count}", n=3, count=7)
    assert steps == ["Panorama 3 of 7"]
    assert isinstance(steps[0], Message) and steps[0].template == "Panorama {n} of {count}"
    assert steps[0].fields == {"n": 3, "count": 7} and message is steps[0]
    worker, kept = progress.recorder()
    worker.step("Block {n}", n=1)
    assert steps == ["Panorama 3 of 7"] and kept == []
    assert SILENT.step("Nothing {n}", n=1) == "Nothing 1"


def test_the_throttle_shows_a_new_kind_of_step_at_once_and_the_same_kind_every_interval():
    shown, now = [], [0.0]
    throttle = StepThrottle(shown.append, interval_s=5.0, clock=lambda: now[0])
    progress = Progress(on_step=throttle)
    for k in range(1, 101):                       # 100 panoramas, 0.25 s each
        now[0] = 0.25 * (k - 1)
        progress.step("Panorama {n} of {count}", n=k, count=100)
    assert shown == ["Panorama {} of 100".format(k) for k in (1, 21, 41, 61, 81)]
    now[0] = 25.0                                 # another kind of step: shown at once
    progress.step("Block {n} of {count}", n=1, count=3)
    now[0] = 25.25
    progress.step("Block {n} of {count}", n=2, count=3)
    assert shown[-1] == "Block 1 of 3" and len(shown) == 6
    now[0] = 25.5                                 # back to the first kind: a change too
    progress.step("Panorama {n} of {count}", n=100, count=100)
    assert shown[-1] == "Panorama 100 of 100"
