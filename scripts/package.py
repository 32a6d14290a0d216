"""Build the installable plugin zip: ``dist/roadsigns.zip`` holding the folder ``roadsigns/``
with the runtime files only (no tests, benchmarks, dev tools, training code or data).

    python scripts/package.py [--out dist/roadsigns.zip]
"""
import argparse
import os
import subprocess
import sys
import zipfile

REPO_ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
#: what the plugin needs at run time, relative to the checkout
RUNTIME = ("metadata.txt", "__init__.py", "plugin.py", "dependencies.py", "requirements.txt",
           "README.md", "docs", "provider", "gui", "algorithms", "core", "models", "i18n", "icons")
#: never shipped, even inside the folders above
EXCLUDED_SUFFIXES = (".pyc", ".ts", ".pt", ".ckpt")
EXCLUDED_NAMES = ("__pycache__",)


def tracked_files():
    """Files git tracks (so nothing generated or ignored slips in)."""
    out = subprocess.run(["git", "ls-files", "-z"], cwd=REPO_ROOT, capture_output=True, check=True)
    return [p for p in out.stdout.decode().split("\0") if p]


def runtime_files():
    keep = []
    for path in tracked_files():
        top = path.split("/")[0]
        if top not in RUNTIME:
            continue
        parts = path.split("/")
        if any(p in EXCLUDED_NAMES for p in parts) or path.endswith(EXCLUDED_SUFFIXES):
            continue
        keep.append(path)
    return sorted(keep)


def build(out_path):
    os.makedirs(os.path.dirname(os.path.abspath(out_path)), exist_ok=True)
    temp = out_path + ".part"
    with zipfile.ZipFile(temp, "w", zipfile.ZIP_DEFLATED) as archive:
        for path in runtime_files():
            archive.write(os.path.join(REPO_ROOT, path), "roadsigns/" + path)
    os.replace(temp, out_path)
    return out_path


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default=os.path.join(REPO_ROOT, "dist", "roadsigns.zip"))
    args = parser.parse_args(argv)
    path = build(args.out)
    with zipfile.ZipFile(path) as archive:
        names = archive.namelist()
    print("{} ({} files, {:.1f} MB)".format(path, len(names), os.path.getsize(path) / 2**20))


if __name__ == "__main__":
    sys.exit(main())
