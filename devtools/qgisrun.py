"""Run ``qgis_process`` with the plugin from this checkout in a throw-away QGIS profile.

Shared by the tests, the demo and the benchmarks. The checkout is exposed as the package
``roadsigns`` through a symlink in a temporary plugin folder (``QGIS_PLUGINPATH``); the
venv's site-packages go on ``PYTHONPATH`` so QGIS's Python finds the dependencies.
"""
from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import tempfile
from dataclasses import dataclass

from . import plugin_path as default_plugin_path
from . import temp_folder


@dataclass
class Run:
    returncode: int
    stdout: str
    stderr: str
    wall_s: float = 0.0
    peak_rss_mb: float = 0.0

    @property
    def json(self):
        return json.loads(self.stdout)

    @property
    def text(self):
        return self.stdout + self.stderr


def _vm_hwm_kb(pid: int) -> int:
    """Peak resident memory (KiB) of a running process, 0 when it cannot be read."""
    try:
        with open("/proc/{}/status".format(pid)) as f:
            for line in f:
                if line.startswith("VmHWM:"):
                    return int(line.split()[1])
    except OSError:
        pass
    return 0


class QgisProcess:
    """``qgis_process`` bound to one plugin folder and one throw-away profile."""

    def __init__(self, plugin_path: str = None, profile: str = None):
        self.executable = shutil.which("qgis_process")
        if self.executable is None:
            raise RuntimeError("qgis_process is not installed: run `make setup` (scripts/setup.sh)")
        self.profile = profile or temp_folder("roadsigns-qgis-profile-")
        env = dict(os.environ)
        site = [p for p in sys.path if p.endswith("site-packages") and os.path.isdir(p)]
        env.update({
            "QGIS_PLUGINPATH": plugin_path or default_plugin_path(),
            "QGIS_CUSTOM_CONFIG_PATH": self.profile,
            "QT_QPA_PLATFORM": "offscreen",
            "PYTHONPATH": os.pathsep.join(site + [env.get("PYTHONPATH", "")]).strip(os.pathsep),
            "PROJ_DATA": env.get("PROJ_DATA", "/usr/share/proj"),
            "XDG_RUNTIME_DIR": env.get("XDG_RUNTIME_DIR") or temp_folder("roadsigns-xdg-"),
        })
        self.env = env
        enabled = self("plugins", "enable", "roadsigns")
        if enabled.returncode != 0:
            raise RuntimeError("qgis_process could not enable the plugin:\n" + enabled.text)

    def __call__(self, *args, timeout=3600) -> Run:
        """Run ``qgis_process ARGS``; wall time and this run's own peak RSS are measured."""
        import time
        with tempfile.TemporaryFile("w+") as out, tempfile.TemporaryFile("w+") as err:
            start = time.perf_counter()
            p = subprocess.Popen([self.executable, *args], env=self.env, stdout=out, stderr=err,
                                 stdin=subprocess.DEVNULL, text=True)
            peak_kb = 0
            while True:
                # VmHWM of the running process is its own peak: ru_maxrss from wait4 would
                # also count this (parent) process's memory at fork time
                peak_kb = max(peak_kb, _vm_hwm_kb(p.pid))
                pid, status, usage = os.wait4(p.pid, os.WNOHANG)
                if pid:
                    break
                if time.perf_counter() - start > timeout:
                    p.kill()
                    os.wait4(p.pid, 0)
                    raise subprocess.TimeoutExpired(args, timeout)
                time.sleep(0.02)
            p.returncode = os.waitstatus_to_exitcode(status)
            wall_s = time.perf_counter() - start
            out.seek(0)
            err.seek(0)
            return Run(p.returncode, out.read(), err.read(), wall_s, peak_kb / 1024.0)

    def run(self, algorithm: str, timeout=3600, **parameters) -> Run:
        """``qgis_process --json run algorithm -- NAME=value ...``."""
        args = ["--json", "run", algorithm, "--"]
        args += ["{}={}".format(k, v) for k, v in parameters.items()]
        return self(*args, timeout=timeout)
