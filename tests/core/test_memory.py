import json
import os
import subprocess
import sys
import textwrap

import numpy as np
import pytest

from roadsigns.core import drivewindows, memory

#: A fresh interpreter: glibc keeps 100 MB of freed arrays inside its heap (the mmap
#: threshold raised by the first freed 4 MB array), then release_freed_memory gives them back.
FRAGMENTED_HEAP = textwrap.dedent("""
    import json
    import numpy as np
    from roadsigns.core.memory import release_freed_memory

    def rss_mb():
        with open("/proc/self/status") as f:
            return next(int(line.split()[1]) for line in f if line.startswith("VmRSS")) / 1024

    big = np.ones((4 << 20) // 8)
    del big                                    # glibc now serves 1 MB arrays from its heap
    arrays = [np.ones((1 << 20) // 8) for _ in range(200)]
    before = rss_mb()
    del arrays[::2]                            # 100 MB free, between live arrays
    freed = rss_mb()
    released = release_freed_memory()
    print(json.dumps({"before": before, "freed": freed, "after": rss_mb(), "released": released}))
""")


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="glibc's heap")
def test_freed_arrays_held_by_the_heap_are_given_back():
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(p for p in sys.path if p))
    out = subprocess.run([sys.executable, "-c", FRAGMENTED_HEAP], capture_output=True, text=True,
                         env=env, check=True)
    mb = json.loads(out.stdout.strip().splitlines()[-1])
    assert mb["before"] - mb["freed"] < 20          # free() kept the pages (the case at hand)
    assert mb["released"] is True
    assert mb["freed"] - mb["after"] > 80           # 100 MB were free, given back


@pytest.mark.parametrize("threads", [1, 2])
def test_memory_is_given_back_after_each_block(monkeypatch, threads):
    calls = []
    monkeypatch.setattr(drivewindows, "release_freed_memory", lambda: calls.append(1) or True)
    out = list(drivewindows.map_in_order(lambda k: k * k, range(5), threads, lambda: None))
    assert out == [0, 1, 4, 9, 16] and len(calls) == 5


def test_release_is_a_no_op_without_glibc(monkeypatch):
    monkeypatch.setattr(memory, "_malloc_trim", lambda: None)
    assert memory.release_freed_memory() is False


def test_a_spool_gives_the_writing_pass_memory_back_at_its_first_read(monkeypatch, tmp_path):
    calls = []
    monkeypatch.setattr(drivewindows, "release_freed_memory", lambda: calls.append(1) or True)
    with drivewindows.Spool({"v": "f8"}, folder=str(tmp_path)) as spool:
        for k in range(3):
            spool.append("v", k, np.arange(4.0))
        assert calls == []                      # not while it is written
        assert list(spool.read("v", 0)) == [0.0, 1.0, 2.0, 3.0]
        assert len(calls) == 1
        spool.read("v", 1), spool.read("v", 2)
        assert len(calls) == 1                  # once, when reading begins
