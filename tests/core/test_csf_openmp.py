"""The built-in CSF runs on one OpenMP thread whichever OpenMP runtime its library binds to
(core/ground/csf.py, ``_one_openmp_thread``): the library's parallel loops race, and its
OpenMP calls bind to the first runtime the process loaded with global symbols, which after
torch (or in a QGIS where another plugin imported it) is not the one its wheel bundles.

Each case runs in a fresh Python, where the other runtime is loaded before CSF, as it is
when torch is imported first.
"""
import glob
import json
import os
import shutil
import subprocess
import sys

import pytest

csf_wheel = pytest.importorskip("CSF", reason="the built-in CSF's package (cloth-simulation-filter)")

#: Run in the child: the other OpenMP runtime (a copy of the wheel's own, under another name,
#: so it is a second runtime) loaded with global symbols, then the plugin's CSF run on a
#: slope, recording, while the library simulates, every loaded OpenMP runtime's threads.
CHILD = r"""
import ctypes, json, sys
other = sys.argv[1]
ctypes.CDLL(other, mode=ctypes.RTLD_GLOBAL)
import numpy as np
import CSF
from threadpoolctl import threadpool_info
from roadsigns.core.ground import csf

def openmp_threads():
    return {i["filepath"]: i["num_threads"] for i in threadpool_info() if i["user_api"] == "openmp"}

seen = []
simulate = CSF.CSF.do_cloth_export
def recorded(self, *args):
    seen.append(openmp_threads())
    return simulate(self, *args)
CSF.CSF.do_cloth_export = recorded

rng = np.random.default_rng(0)
xy = rng.uniform(0.0, 40.0, (20_000, 2))
xyz = np.column_stack([xy, 0.03 * xy[:, 0] + rng.normal(0.0, 0.05, len(xy))])
before = openmp_threads()
cloths = [csf.run_csf_cloth(xyz, csf.CsfParams(resolution=0.5)) for _ in range(2)]
print(json.dumps({"before": before, "during": seen, "after": openmp_threads(),
                  "same_cloth": bool(np.array_equal(cloths[0], cloths[1]))}))
"""


def _wheel_openmp():
    here = os.path.dirname(os.path.abspath(csf_wheel.__file__))
    found = glob.glob(os.path.join(here, "cloth_simulation_filter.libs", "libgomp*"))
    if not found:
        pytest.skip("this cloth-simulation-filter wheel bundles no libgomp")
    return found[0]


def test_csf_runs_on_one_thread_of_whichever_openmp_it_binds_to(tmp_path):
    other = str(tmp_path / "libgomp-loaded-first.so.1")
    shutil.copyfile(_wheel_openmp(), other)
    env = dict(os.environ, OMP_NUM_THREADS="4")    # more than one thread by default, on any machine
    env["PYTHONPATH"] = os.pathsep.join(p for p in sys.path if p)
    run = subprocess.run([sys.executable, "-c", CHILD, other], env=env, capture_output=True, text=True,
                         timeout=120, check=False)
    assert run.returncode == 0, run.stderr[-3000:]
    out = json.loads(run.stdout.strip().splitlines()[-1])
    assert out["before"].get(other) == 4      # loaded first, globally: CSF binds to it (LD_DEBUG=bindings)
    assert len(out["during"]) == 2
    for during in out["during"]:
        assert other in during
        assert set(during.values()) == {1}, during                    # every runtime on one thread
    assert out["after"] == out["before"]                              # and given back its setting
    assert out["same_cloth"]
