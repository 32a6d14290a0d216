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


#: Algorithms whose help is also read as JSON, to check the text's parameters against: the
#: one with the most parameters and the model (whose names hold colons).
JSON_CHECKED = ("roadsigns:detectsigns", "roadsigns:signinventory")


def argument_help(help_text):
    """{parameter name: its help text} from ``qgis_process help``'s Arguments section: each
    parameter's header line ``NAME: label``, then tab-indented lines: a default value, the
    help, then its argument type and acceptable values."""
    arguments = help_text.split("\nArguments\n")[1].split("\nOutputs\n")[0]
    helps, name, past_help = {}, None, False
    for line in arguments.splitlines():
        if not line.strip() or line.startswith("---"):
            continue
        if not line.startswith("\t"):
            name, past_help = line.split(": ", 1)[0], False
            helps[name] = []
        elif line.startswith("\tArgument type:"):
            past_help = True
        elif not past_help and not line.startswith("\tDefault value:"):
            helps[name].append(line.strip())
    return {name: " ".join(lines) for name, lines in helps.items()}


def test_every_algorithm_and_parameter_has_help(qgis_process, listing):
    """Every algorithm's ``qgis_process help`` (what a user reads): a description, and help
    text on every parameter; the parameters read from the text are those of the JSON form
    for :data:`JSON_CHECKED`. Asked four at a time (each call is mostly QGIS starting)."""
    from concurrent.futures import ThreadPoolExecutor

    algorithm_ids = sorted(listing["roadsigns"]["algorithms"])
    assert set(JSON_CHECKED) <= set(algorithm_ids)
    with ThreadPoolExecutor(max_workers=4) as pool:
        as_text = dict(zip(algorithm_ids, pool.map(lambda a: qgis_process("help", a), algorithm_ids)))
        as_json = dict(zip(JSON_CHECKED, pool.map(lambda a: qgis_process("--json", "help", a), JSON_CHECKED)))
    for algorithm_id, run in as_text.items():
        assert run.returncode == 0, run.text
        description = run.stdout.split("Description")[1].split("Arguments")[0]
        assert len(description.strip("-\n ")) > 80, algorithm_id
        helps = argument_help(run.stdout)
        assert helps, algorithm_id
        for name, text in helps.items():
            assert text, "{}: parameter {} has no help text".format(algorithm_id, name)
    for algorithm_id, run in as_json.items():
        assert run.returncode == 0, run.text
        info = run.json
        assert info["algorithm_details"]["short_description"], algorithm_id
        assert set(argument_help(as_text[algorithm_id].stdout)) == set(info["parameters"]), algorithm_id
        for name, parameter in info["parameters"].items():
            assert parameter.get("help"), "{}: parameter {} has no help text".format(algorithm_id, name)


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
