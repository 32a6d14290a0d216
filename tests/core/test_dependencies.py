"""The dependency check names what is missing and the command that installs it."""
from roadsigns import dependencies


def test_present_packages_give_no_message():
    assert dependencies.missing(["numpy", "scipy"]) == []
    assert dependencies.missing_message(["numpy"]) == ""


def test_missing_package_is_named_with_its_install_command():
    dependencies.PACKAGES["roadsigns_no_such_module"] = "no-such-package"
    try:
        message = dependencies.missing_message(["numpy", "roadsigns_no_such_module"])
    finally:
        del dependencies.PACKAGES["roadsigns_no_such_module"]
    assert "no-such-package" in message and "numpy" not in message.split("Install with")[0]
    assert "pip install --user --break-system-packages --upgrade no-such-package" in message


def test_install_commands_per_platform():
    windows = dependencies.install_command(["laspy", "lazrs", "shapely"], platform="win32")
    assert windows.startswith('python -m pip install --upgrade "laspy[lazrs]" "shapely>=2"')
    assert "OSGeo4W Shell" in windows
    mac = dependencies.install_command(["cv2"], platform="darwin")
    assert mac.endswith("-m pip install --upgrade opencv-python-headless")


def test_shapely_wheel_with_its_own_geos_is_flagged_on_linux(tmp_path, monkeypatch):
    (tmp_path / "shapely").mkdir()
    (tmp_path / "shapely" / "__init__.py").write_text("")
    monkeypatch.syspath_prepend(str(tmp_path))
    import importlib
    importlib.invalidate_caches()
    monkeypatch.delitem(__import__("sys").modules, "shapely", raising=False)
    assert dependencies.shapely_geos_conflict("3.11.1", platform="linux") == ""  # built from source
    (tmp_path / "shapely.libs").mkdir()
    message = dependencies.shapely_geos_conflict("3.11.1", platform="linux")
    assert "GEOS 3.11.1" in message and "--no-binary shapely" in message
    assert dependencies.shapely_geos_conflict("3.11.1", platform="win32") == ""
