#!/usr/bin/env bash
# Set up everything the plugin, its tests and its demo need on a fresh Debian 12 machine:
# QGIS 3.40 LTR from bookworm-backports and a venv on Debian's Python 3.11 with numpy
# pinned to the system's. Idempotent: a second run only checks and returns in seconds.
set -euo pipefail
export PROJ_DATA="${PROJ_DATA:-/usr/share/proj}"
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
VENV="${ROADSIGNS_VENV:-$here/.venv}"
SUDO=""
if [ "$(id -u)" != 0 ]; then SUDO="sudo"; fi

log() { printf '[setup] %s\n' "$*"; }

# --- 1. QGIS 3.40 LTR and Debian's scientific Python --------------------------------
# libgeos-dev: shapely is built against the system GEOS (the one QGIS links): a shapely wheel
# bundles another GEOS whose C++ symbols clash with QGIS's inside qgis_process and crash it.
# qttools5-dev-tools (lrelease) and pyqt5-dev-tools (pylupdate5): translations, make i18n.
# xvfb and xauth (xvfb-run): the review panel's tests run the QGIS desktop on a virtual display.
apt_pkgs=(qgis python3-qgis qgis-providers python3-venv python3-pip python3-dev python3-scipy python3-pyproj
          python3-numpy libgeos-dev qttools5-dev-tools pyqt5-dev-tools xvfb xauth)
need_apt=0
if ! command -v qgis_process >/dev/null 2>&1; then need_apt=1; fi
for p in "${apt_pkgs[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || need_apt=1
done
if [ "$need_apt" = 1 ]; then
  src=/etc/apt/sources.list.d/bookworm-backports.sources
  if [ ! -f "$src" ]; then
    log "adding the bookworm-backports apt source (that suite only)"
    $SUDO tee "$src" >/dev/null <<'SRC'
Types: deb
URIs: http://deb.debian.org/debian
Suites: bookworm-backports
Components: main
Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg
SRC
  fi
  log "installing QGIS 3.40 LTR (about a minute)"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq -t bookworm-backports \
    --no-install-recommends "${apt_pkgs[@]}" >/dev/null
fi
log "$(QT_QPA_PLATFORM=offscreen qgis_process --version 2>/dev/null | grep -m1 QGIS || echo 'qgis_process: not found')"

# --- 2. venv on Debian's Python with the system numpy pinned -------------------------
if [ ! -x "$VENV/bin/python" ]; then
  log "creating venv $VENV"
  /usr/bin/python3 -m venv --system-site-packages "$VENV"
fi
stamp="$VENV/.roadsigns-requirements"
want="$(cat "$here/requirements.txt" "$here/requirements-dev.txt" | sha1sum | cut -c1-40)"
if [ "$(cat "$stamp" 2>/dev/null)" != "$want" ]; then
  sys_numpy="$(/usr/bin/python3 -c 'import numpy; print(numpy.__version__)')"
  constraints="$VENV/constraints.txt"
  echo "numpy==$sys_numpy" > "$constraints"
  log "installing Python dependencies (numpy pinned to $sys_numpy)"
  "$VENV/bin/python" -m pip install -q --disable-pip-version-check --no-binary shapely \
    -c "$constraints" -r "$here/requirements.txt" -r "$here/requirements-dev.txt"
  echo "$want" > "$stamp"
fi
sys_geos="$(geos-config --version)"
venv_geos="$("$VENV/bin/python" -c 'import shapely; print(".".join(map(str, shapely.geos_version)))')"
if [ "$sys_geos" != "$venv_geos" ]; then
  log "rebuilding shapely against the system GEOS $sys_geos (it had GEOS $venv_geos)"
  "$VENV/bin/python" -m pip install -q --disable-pip-version-check --no-binary shapely \
    --force-reinstall --no-deps -c "$VENV/constraints.txt" "shapely>=2.0"
fi
log "python deps ok: $("$VENV/bin/python" -c 'import numpy, scipy, pyproj, shapely; print("numpy", numpy.__version__, "scipy", scipy.__version__, "pyproj", pyproj.__version__, "shapely", shapely.__version__, "GEOS", shapely.geos_version_string)')"

# --- 3. PDAL's Python bindings for the tests (only where ../shared/tools/pdal-2.9.2 exists) ---
# The real PDAL 2.9.2 build beside the checkout (its README): the tests run the plugin's PDAL
# engine with its `pdal` application and with these bindings. Test-only: the plugin never
# ships them; --no-deps keeps the venv's numpy (pinned to Debian's).
pdal_dir="$(cd "$here/.." && pwd)/shared/tools/pdal-2.9.2"
if [ -d "$pdal_dir" ]; then
  pdal_whl="$(ls "$pdal_dir"/python/pdal-*.whl 2>/dev/null | head -n1 || true)"
  pdal_want="$(basename "${pdal_whl:-none-none}" | cut -d- -f2)"
  pdal_have="$("$VENV/bin/python" -c 'import importlib.metadata as m; print(m.version("pdal"))' 2>/dev/null || true)"
  if [ -n "$pdal_whl" ] && [ "$pdal_have" != "$pdal_want" ]; then
    log "installing PDAL's Python bindings $pdal_want (tests only) from $pdal_whl"
    "$VENV/bin/python" -m pip install -q --disable-pip-version-check --no-deps --force-reinstall "$pdal_whl"
  fi
  pdal_app="$("$pdal_dir/bin/pdal" --version 2>/dev/null || true)"
  pdal_py="$("$VENV/bin/python" -c 'import pdal; print(pdal.__version__, "on PDAL", pdal.info.version)' 2>/dev/null || true)"
  log "PDAL for the tests: $(echo "$pdal_app" | grep -o 'pdal [0-9][0-9.]*' | head -n1 || true), bindings ${pdal_py:-that do not import}"
fi
