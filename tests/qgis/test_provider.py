"""The provider loads in qgis_process, lists its algorithms, and every algorithm and
parameter carries help text."""
import pytest

EXPECTED_ALGORITHMS = {"roadsigns:" + a for a in (
    "importtrajectory", "detectsigns", "groundfilter", "projectdetections", "refinesigns", "findsignsincloud",
    "fusesigns", "evaluate", "exporthandover", "signinventory")}


@pytest.fixture(scope="module")
def listing(qgis_process):
    run = qgis_process("--json", "list")
    assert run.returncode == 0, run.text
    return run.json["providers"]


def test_provider_is_listed_with_its_algorithms(listing):
    provider = listing["roadsigns"]
    assert provider["name"] == "Road sign inventory"
    assert provider["is_active"]
    assert EXPECTED_ALGORITHMS <= set(provider["algorithms"])


def test_every_algorithm_and_parameter_has_help(qgis_process, listing):
    """Both help forms of every algorithm, asked of qgis_process four at a time (each call is
    mostly QGIS starting)."""
    from concurrent.futures import ThreadPoolExecutor

    algorithm_ids = sorted(listing["roadsigns"]["algorithms"])
    with ThreadPoolExecutor(max_workers=4) as pool:
        as_json = list(pool.map(lambda a: qgis_process("--json", "help", a), algorithm_ids))
        as_text = list(pool.map(lambda a: qgis_process("help", a), algorithm_ids))
    for algorithm_id, run, text_run in zip(algorithm_ids, as_json, as_text):
        assert run.returncode == 0, run.text
        info = run.json
        assert info["algorithm_details"]["short_description"], algorithm_id
        for name, parameter in info["parameters"].items():
            assert parameter.get("help"), "{}: parameter {} has no help text".format(algorithm_id, name)
        assert text_run.returncode == 0, text_run.text
        description = text_run.stdout.split("Description")[1].split("Arguments")[0]
        assert len(description.strip("-\n ")) > 80, algorithm_id


def test_provider_loads_without_the_optional_packages(qgis_process):
    """Without the venv (onnxruntime, cv2, laspy, shapely missing) the provider still loads
    and qgis_process says what is missing and how to install it."""
    import subprocess
    env = dict(qgis_process.env)
    env["PYTHONPATH"] = ""
    p = subprocess.run([qgis_process.executable, "list"], env=env, capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    assert "roadsigns:importtrajectory" in p.stdout
    assert "needs the Python package(s)" in p.stderr
    for package in ("onnxruntime", "opencv-python-headless", "laspy[lazrs]"):
        assert package in p.stderr
    assert "pip install" in p.stderr
