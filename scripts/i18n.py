"""Translations of Road Sign Inventory (i18n/README.md): Qt's ``pylupdate5`` extracts the
plugin's ``tr`` literals, this script adds the core's texts and keeps ``i18n/`` up to date.

    python3 scripts/i18n.py update              pylupdate5 + context RoadSigns -> i18n/roadsigns_<lang>.ts
    python3 scripts/i18n.py compile             lrelease -> i18n/roadsigns_<lang>.qm
    python3 scripts/i18n.py check [--json]      untranslated, unfinished or broken entries, stale .qm
    python3 scripts/i18n.py import FILE.json    set translations from {"lang": {"source": "translation"}}
    python3 scripts/i18n.py extract             every (context, source) and where it is
    python3 scripts/i18n.py audit               English text shown to users outside tr

``make i18n`` runs update, compile and check. ``pylupdate5 -noobsolete`` reads
:data:`PLUGIN_SOURCES` (``self.tr("...")`` in a class: the class's context; a bare
``tr("...")``: ``@default``); :func:`core_strings` adds context RoadSigns (``tr_core``).
"""
from __future__ import annotations

import argparse
import ast
import difflib
import glob
import json
import os
import re
import shutil
import string
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ET
from collections import OrderedDict, namedtuple
from pathlib import Path
from typing import Dict, List, Optional, Tuple

REPO_ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
I18N_DIR = os.path.join(REPO_ROOT, "i18n")
#: file suffix (roadsigns_<suffix>.ts/.qm) -> TS language code
LANGUAGES = OrderedDict([("zh_Hans", "zh_CN"), ("es", "es")])
CORE_CONTEXT = "RoadSigns"
#: what pylupdate5 reads: the shipped Python code but core (scripts/package.py ships it)
PLUGIN_SOURCES = ("__init__.py", "plugin.py", "dependencies.py", "provider", "gui", "algorithms")
#: where the core's texts are
CORE_SOURCES = ("core", "dependencies.py")
#: the code that shows text to users (audit)
ADAPTERS = ("__init__.py", "plugin.py", "provider", "gui", "algorithms")
#: core message fields whose values are words, translated too (algorithms/base.py localise)
TRANSLATED_FIELDS = ("what", "role", "kind")
TEMPLATE = "template"
#: adapter calls whose text reaches users, as does that of QgsProcessingParameter*/Output* and add_*
USER_CALLS = {"QgsProcessingException", "pushInfo", "pushWarning", "reportError", "pushFormattedMessage",
              "setProgressText", "logMessage", "pushMessage", "pushCommandInfo", "setHelp", "Setting",
              "QgsRendererCategory"}
COMMENTS = {"template": "Message: keep every {field} exactly as written; they are filled in afterwards.",
            "field": "A word filled into {what}, {role} or {kind} of messages (a kind of file or CRS, or "
                     "'is duplicated'): write it to fit those messages' translations, lowercase.",
            "model": "Help of the shipped Processing model (models/*.model3)."}

Entry = namedtuple("Entry", "translation finished locations")


def py_files(entries) -> List[str]:
    out = []
    for entry in entries:
        path = os.path.join(REPO_ROOT, entry)
        out += sorted(glob.glob(os.path.join(path, "**", "*.py"), recursive=True)) if os.path.isdir(path) \
            else [path] if os.path.isfile(path) else []
    return out


def rel(path: str) -> str:
    return os.path.relpath(path, REPO_ROOT).replace(os.sep, "/")


def _parse(paths) -> List[Tuple[str, ast.AST]]:
    return [(path, ast.parse(Path(path).read_text(encoding="utf-8"), filename=path)) for path in paths]


# --- TS files ------------------------------------------------------------------------------

def ts_path(language: str) -> str:
    return os.path.join(I18N_DIR, "roadsigns_{}.ts".format(language))


def qm_path(language: str) -> str:
    return os.path.join(I18N_DIR, "roadsigns_{}.qm".format(language))


def messages(root):
    """(context name, <message> element) of a TS tree."""
    for context in root.findall("context"):
        for message in context.findall("message"):
            yield context.findtext("name") or "", message


def read_ts(path: str) -> "OrderedDict[Tuple[str, str], Entry]":
    """{(context, source): Entry(translation, finished, [(location file, line)])}."""
    out: "OrderedDict[Tuple[str, str], Entry]" = OrderedDict()
    for context, message in messages(ET.parse(path).getroot()) if os.path.exists(path) else ():
        text = message.findtext("translation") or ""
        out[(context, message.findtext("source") or "")] = Entry(
            text, bool(text) and message.find("translation").get("type") not in ("unfinished", "vanished"),
            [(loc.get("filename", ""), int(loc.get("line") or 0)) for loc in message.findall("location")])
    return out


def set_translation(message, text: str, finished: bool):
    node = message.find("translation")
    node.text, node.attrib = text, {} if finished else {"type": "unfinished"}


def write_ts(path: str, root):
    root.text = "\n"
    for context in root:  # laid out as pylupdate5 does
        ET.indent(context, "    ")
        context.tail = "\n"
    with open(path + ".part", "w", encoding="utf-8", newline="\n") as f:
        f.write('<?xml version="1.0" encoding="utf-8"?>\n<!DOCTYPE TS>\n' + ET.tostring(root, encoding="unicode"))
    os.replace(path + ".part", path)


def pylupdate(ts_files: List[str]):
    """``pylupdate5 -noobsolete`` of :data:`PLUGIN_SOURCES` into ``ts_files``."""
    exe = shutil.which("pylupdate5")
    if exe is None:
        raise SystemExit("pylupdate5 not found: install the Debian package pyqt5-dev-tools")
    p = subprocess.run([exe, "-noobsolete", *[rel(f) for f in py_files(PLUGIN_SOURCES)], "-ts", *ts_files],
                       cwd=REPO_ROOT, capture_output=True, text=True, env=dict(os.environ, PYTHONWARNINGS="ignore"))
    if p.returncode != 0 or "error" in p.stderr.lower():
        raise RuntimeError("pylupdate5 failed:\n" + p.stdout + p.stderr)


# --- the core's texts (context RoadSigns) ------------------------------------------------------

def _name(call: ast.Call) -> Optional[str]:
    return getattr(call.func, "id", None) or getattr(call.func, "attr", None)


def _literals(node, constants) -> List[str]:
    """The strings ``node`` is: a literal, a module constant, either branch of ``a if c else b``."""
    if isinstance(node, ast.Constant) and isinstance(node.value, str):
        return [node.value]
    if isinstance(node, ast.Name) and node.id in constants:
        return [constants[node.id]]
    if isinstance(node, ast.IfExp):
        return _literals(node.body, constants) + _literals(node.orelse, constants)
    return []


def passed_on(function) -> set:
    """The :data:`TRANSLATED_FIELDS` that ``function`` passes on as ``what=what``."""
    return {k.arg for n in ast.walk(function) if isinstance(n, ast.Call) for k in n.keywords
            if k.arg in TRANSLATED_FIELDS and isinstance(k.value, ast.Name) and k.value.id == k.arg}


def signatures(trees) -> Dict[str, Dict[str, Optional[int]]]:
    """Name -> {parameter: position, None if keyword only} of the calls that take a template:
    InputError, Message, info, warning (core/errors.py) and the functions of ``trees`` with a
    ``template`` parameter (their ``**fields`` take :data:`TRANSLATED_FIELDS`); and of the
    functions that pass a :data:`TRANSLATED_FIELDS` parameter on."""
    fields = {f: None for f in TRANSLATED_FIELDS}
    out = {name: {TEMPLATE: 0, **fields} for name in ("InputError", "Message", "info", "warning")}
    for function in (n for tree in trees for n in ast.walk(tree) if isinstance(n, ast.FunctionDef)):
        wanted, args = {TEMPLATE} | passed_on(function), function.args
        positional = [a.arg for a in args.posonlyargs + args.args]
        positional = positional[1:] if positional[:1] in (["self"], ["cls"]) else positional
        params = {p: k for k, p in enumerate(positional) if p in wanted}
        params.update({a.arg: None for a in args.kwonlyargs if a.arg in wanted})
        params.update(fields if TEMPLATE in params and args.kwarg else {})
        if params and not function.name.startswith("__"):
            out.setdefault(function.name, {}).update(params)
    return out


def bound(call: ast.Call, params: Dict[str, Optional[int]]):
    """(parameter, argument node) that ``call`` passes for ``params``."""
    for param, position in params.items():
        arg = next((k.value for k in call.keywords if k.arg == param), None)
        if arg is None and position is not None and position < len(call.args) and \
                not any(isinstance(a, ast.Starred) for a in call.args[:position + 1]):
            arg = call.args[position]
        if arg is not None:
            yield param, arg


def core_strings(files: Optional[List[str]] = None) -> "OrderedDict[str, Tuple[str, List[Tuple[str, int]]]]":
    """{text: (kind, [(file, line)])}, context RoadSigns: what is no literal at a tr call, in
    ``files`` (default :data:`CORE_SOURCES`, then the shipped models' help): the literal (or
    module constant) given as ``template`` to InputError, Message, progress.info/warning or
    any function with a ``template`` parameter, the literals given to a
    :data:`TRANSLATED_FIELDS` parameter that a function passes on (``what=what``), assigned to
    it or its default."""
    parsed = _parse(files or py_files(CORE_SOURCES))
    calls = signatures([t for _, t in parsed])
    found: "OrderedDict[str, Tuple[str, List[Tuple[str, int]]]]" = OrderedDict()

    def add(texts, kind, path, node):
        for text in (t for t in texts if t.strip()):
            found.setdefault(text, (kind, []))[1].append((rel(path), node.lineno))

    for path, tree in parsed:
        constants = {t.id: n.value.value for n in tree.body if isinstance(n, ast.Assign)
                     and isinstance(n.value, ast.Constant) and isinstance(n.value.value, str)
                     for t in n.targets if isinstance(t, ast.Name)}
        for node in ast.walk(tree):
            if isinstance(node, ast.Call):
                for param, arg in bound(node, calls.get(_name(node), {})):
                    add(_literals(arg, constants), "template" if param == TEMPLATE else "field", path, node)
            elif isinstance(node, ast.FunctionDef):  # what = "..." / def f(what="...") and what=what
                fields, args = passed_on(node), node.args
                for n in ast.walk(node):
                    if isinstance(n, ast.Assign) and any(getattr(x, "id", None) in fields for x in n.targets):
                        add(_literals(n.value, constants), "field", path, n)
                positional = args.posonlyargs + args.args
                for arg, default in list(zip(positional[len(positional) - len(args.defaults):], args.defaults)) + \
                        list(zip(args.kwonlyargs, args.kw_defaults)):
                    if arg.arg in fields and default is not None:
                        add(_literals(default, constants), "field", path, default)
    for text, path, line in model_help() if files is None else ():
        found.setdefault(text, ("model", []))[1].append((path, line))
    return found


def model_help() -> List[Tuple[str, str, int]]:
    """(text, file, line) of the description (ALG_DESC) and the parameters' help of every
    shipped model: what ``ShippedModel`` reads with ``helpContent()`` (provider/provider.py)."""
    out = []
    for path in sorted(glob.glob(os.path.join(REPO_ROOT, "models", "*.model3"))):
        text = Path(path).read_text(encoding="utf-8")
        maps = {o.get("name"): o for o in ET.fromstring(text).findall("Option")}
        parameters = {o.get("name") for o in maps.get("parameterDefinitions", ())}
        lines = text.splitlines()
        start = next((k for k, line in enumerate(lines) if 'type="Map" name="help"' in line), 0)
        for option in maps["help"].findall("Option") if "help" in maps else ():
            key, value = option.get("name"), option.get("value") or ""
            if value and (key == "ALG_DESC" or key in parameters):
                line = next((k + 1 for k in range(start, len(lines)) if 'name="{}"'.format(key) in lines[k]), 0)
                out.append((value, rel(path), line))
    return out


def extract() -> "OrderedDict[Tuple[str, str], List[str]]":
    """{(context, source): ["file:line", ...]}: what pylupdate5 finds, then context RoadSigns."""
    with tempfile.TemporaryDirectory() as tmp:
        pylupdate([os.path.join(tmp, "all.ts")])
        found = OrderedDict((key, ["{}:{}".format(rel(os.path.normpath(os.path.join(tmp, f))), line)
                                   for f, line in e.locations])
                            for key, e in read_ts(os.path.join(tmp, "all.ts")).items())
    for text, (_, places) in core_strings().items():
        found[(CORE_CONTEXT, text)] = ["{}:{}".format(*p) for p in places]
    return found


# --- placeholders, tags --------------------------------------------------------------------

def placeholders(text: str) -> List[str]:
    """The ``str.format`` fields as written (``{path}``, ``{}``, ``{value!r}``), sorted;
    ValueError for a malformed format string."""
    return sorted("{" + field + ("!" + conv if conv else "") + (":" + spec if spec else "") + "}"
                  for _, field, spec, conv in string.Formatter().parse(text) if field is not None)


TAG = re.compile(r"</?[a-zA-Z][a-zA-Z0-9]*\s*/?>")


def problems(source: str, translation: str) -> List[str]:
    """What is wrong with a translation: its placeholders or HTML tags differ from the source's."""
    out = []
    for what, find in (("placeholders", placeholders), ("HTML tags", lambda t: sorted(TAG.findall(t)))):
        try:
            want = find(source)
        except ValueError:
            continue  # the source is no format string
        try:
            got = find(translation)
        except ValueError as e:
            return ["not a valid format string ({})".format(e)]
        if got != want:
            out.append("{} {} instead of {}".format(what, " ".join(got) or "none", " ".join(want) or "none"))
    return out


# --- commands ------------------------------------------------------------------------------

def cmd_update(args) -> int:
    old = {language: read_ts(ts_path(language)) for language in args.languages}
    pylupdate([ts_path(language) for language in args.languages])
    core = core_strings()
    for language in args.languages:
        root, previous = ET.parse(ts_path(language)).getroot(), old[language]
        root.attrib.update(version="2.1", language=LANGUAGES[language], sourcelanguage="en")
        context = ET.Element("context")
        ET.SubElement(context, "name").text = CORE_CONTEXT
        for text, (kind, places) in core.items():
            message = ET.SubElement(context, "message")
            for path, line in places:
                ET.SubElement(message, "location", filename="../" + path, line=str(line))
            ET.SubElement(message, "source").text = text
            ET.SubElement(message, "extracomment").text = COMMENTS[kind]
            ET.SubElement(message, "translation", type="unfinished")
        contexts = [c for c in root.findall("context") if c.findtext("name") != CORE_CONTEXT] + [context]
        root[:] = sorted(contexts, key=lambda c: c.findtext("name") or "")
        # what pylupdate5 left unfinished: the same source's finished translation in any context,
        # else the entry's old (unfinished) one, else (RoadSigns) a reworded text's as a draft
        same_text: Dict[str, str] = {}
        for (_, source), e in previous.items():
            if e.finished:
                same_text.setdefault(source, e.translation)
        reworded = [s for (c, s), e in previous.items() if c == CORE_CONTEXT and s not in core and e.translation]
        todo = 0
        for name, message in messages(root):
            source, node = message.findtext("source") or "", message.find("translation")
            if node.get("type") != "unfinished":
                continue
            before = previous.get((name, source), Entry("", False, []))
            similar = difflib.get_close_matches(source, reworded, n=1, cutoff=0.8) if name == CORE_CONTEXT else []
            if source in same_text or before.translation or similar:
                set_translation(message, same_text.get(source) or before.translation or
                                previous[(CORE_CONTEXT, similar[0])].translation, source in same_text)
            todo += source not in same_text
        write_ts(ts_path(language), root)
        print("{}: {} strings, {} to translate or review".format(rel(ts_path(language)),
                                                              len(root.findall("context/message")), todo))
    return 0


def compile_ts(ts: str, qm: str):
    """lrelease ``ts`` into ``qm``: only finished translations ship."""
    lrelease = shutil.which("lrelease") or shutil.which("/usr/lib/qt5/bin/lrelease")
    if lrelease is None:
        raise SystemExit("lrelease not found: install the Debian package qttools5-dev-tools")
    p = subprocess.run([lrelease, "-silent", "-nounfinished", ts, "-qm", qm], capture_output=True, text=True)
    if p.returncode != 0 or not os.path.exists(qm):
        raise RuntimeError("lrelease failed on {}:\n{}{}".format(ts, p.stdout, p.stderr))


def qm_up_to_date(language: str) -> bool:
    """Whether the .qm is what lrelease makes of the .ts now (its output is deterministic)."""
    if not os.path.exists(qm_path(language)):
        return False
    with tempfile.TemporaryDirectory() as tmp:
        compile_ts(ts_path(language), os.path.join(tmp, "fresh.qm"))
        with open(os.path.join(tmp, "fresh.qm"), "rb") as a, open(qm_path(language), "rb") as b:
            return a.read() == b.read()


def cmd_compile(args) -> int:
    for language in args.languages:
        compile_ts(ts_path(language), qm_path(language))
        print("{} ({} bytes)".format(rel(qm_path(language)), os.path.getsize(qm_path(language))))
    return 0


def check(languages=tuple(LANGUAGES), found=None) -> Dict[str, List[Tuple[Tuple[str, str], str]]]:
    """Per language: [((context, source), what is wrong)], ``("", "")`` for a stale .qm."""
    found = extract() if found is None else found
    report = {}
    for language in languages:
        entries = read_ts(ts_path(language))
        report[language] = [(key, what) for key in found for what in (
            ["missing from the .ts"] if key not in entries else ["untranslated"] if not entries[key].translation
            else ["unfinished: a draft to review"] if not entries[key].finished
            else problems(key[1], entries[key].translation))]
        report[language] += [(key, "no longer used") for key in entries if key not in found]
        if not qm_up_to_date(language):
            report[language].append((("", ""), os.path.basename(qm_path(language)) + " not compiled from the .ts"))
    return report


def cmd_check(args) -> int:
    found = extract()
    report = check(args.languages, found)
    if args.json:  # to fill in and import: {language: {source: current translation}}
        entries = {language: read_ts(ts_path(language)) for language in report}
        print(json.dumps({language: OrderedDict((key[1], entries[language][key].translation
                                                 if key in entries[language] else "")
                                                for key, _ in issues if key in found)
                          for language, issues in report.items()}, ensure_ascii=False, indent=1))
    for language, issues in report.items() if not args.json else ():
        print("{}: {} of {} strings need work (run: make i18n)".format(
            language, len({key for key, _ in issues if key[1]}), len(found)))
        for (context, source), what in issues:
            print("  - {}{}".format(what, " [{}] {}".format(context, json.dumps(source, ensure_ascii=False))
                                    if source else ""))
    return 1 if any(report.values()) else 0


def cmd_import(path: str) -> int:
    """Set translations from {language: {source: translation}} (``check --json`` filled in) in
    every context the source is in. Empty values are left alone; translations with other
    placeholders or tags than the source are refused."""
    data = json.loads(Path(path).read_text(encoding="utf-8"))
    errors = ["{}: not a language of {}".format(k, " ".join(LANGUAGES)) for k in data if k not in LANGUAGES]
    for language, translations in ((k, v) for k, v in data.items() if k in LANGUAGES):
        root, done = ET.parse(ts_path(language)).getroot(), 0
        for source, translation in ((s, t) for s, t in translations.items() if t):
            found = [m for _, m in messages(root) if m.findtext("source") == source]
            bad = problems(source, translation) if found else ["not in the .ts"]
            errors += ["{}: {!r}: {}".format(language, source[:80], "; ".join(bad))] if bad else []
            for message in found if not bad else ():
                set_translation(message, translation, True)
            done += not bad
        write_ts(ts_path(language), root)
        print("{}: {} translations set".format(rel(ts_path(language)), done))
    print("".join("  skipped {}\n".format(e) for e in errors), end="", file=sys.stderr)
    return 1 if errors else 0


def cmd_extract(args) -> int:
    for (context, source), places in extract().items():
        print("{}: [{}] {}".format((places or ["?"])[0], context, source if len(source) < 100 else source[:97] + "..."))
    return 0


# --- audit ---------------------------------------------------------------------------------

TEXT = re.compile(r"[A-Za-z]{2,}[^A-Za-z_]*\s[^A-Za-z_]*[A-Za-z]{2,}|^[A-Z][a-z]+\b")


def _texts_outside_tr(node) -> List[ast.AST]:
    """Literals that read as English, and f-strings, in ``node`` but inside tr/tr_core calls."""
    if isinstance(node, ast.Call) and _name(node) in ("tr", "tr_core", "translate"):
        return []
    if isinstance(node, ast.JoinedStr) or isinstance(node, ast.Constant) and isinstance(node.value, str) \
            and TEXT.search(node.value):
        return [node]
    return [x for child in ast.iter_child_nodes(node) for x in _texts_outside_tr(child)]


def _built(node) -> bool:
    """An f-string, ``"...".format(...)`` or ``"..." + x``: finished English, no template."""
    return isinstance(node, ast.JoinedStr) or isinstance(node, ast.Call) and _name(node) == "format" or \
        isinstance(node, ast.BinOp) and any(isinstance(n, ast.JoinedStr) or isinstance(n, ast.Constant)
                                            and isinstance(n.value, str) for n in (node.left, node.right))


def audit(adapters: Optional[List[str]] = None, core: Optional[List[str]] = None) -> List[str]:
    """English text shown to users without tr. In the adapters: literals (and f-strings)
    outside tr/tr_core in messages, parameters and outputs; ``tr`` of anything but a literal
    (pylupdate5 cannot see it); ``tr_core`` of a literal (that is for tr). In core: messages
    built as finished text (f-string, format, +) instead of a template with fields, and text
    added as it is to the warnings/messages that the adapters show."""
    adapters = py_files(ADAPTERS) if adapters is None else adapters
    core_parsed = _parse(py_files(("core",)) if core is None else core)
    calls = signatures([t for _, t in core_parsed])
    out = []
    for path, tree in _parse(adapters) + core_parsed:
        for call in (n for n in ast.walk(tree) if isinstance(n, ast.Call)):
            name, where = _name(call), "{}:{}: ".format(rel(path), call.lineno)
            first = call.args[0] if call.args else None
            literal = isinstance(first, ast.Constant) and isinstance(first.value, str)
            if path not in adapters:
                out += [where + "built text, no template: " + ast.unparse(arg)[:100]
                        for param, arg in bound(call, calls.get(name, {})) if param == TEMPLATE and _built(arg)]
                target = call.func.value if name == "append" and isinstance(call.func, ast.Attribute) else None
                if (getattr(target, "id", None) or getattr(target, "attr", None)) in ("warnings", "messages") \
                        and first is not None and (literal or _built(first)):
                    out.append(where + "text added to the log as it is: " + ast.unparse(first)[:100])
            elif name == "tr" and not literal:
                out.append(where + "tr of no literal (pylupdate5 cannot see it): " + ast.unparse(call)[:100])
            elif name == "tr_core" and (literal or isinstance(first, ast.JoinedStr)):
                out.append(where + "tr_core of a literal (use tr): " + ast.unparse(call)[:100])
            elif name in USER_CALLS or (name or "").startswith(("QgsProcessingParameter", "QgsProcessingOutput",
                                                                "add_")):
                out += [where + "outside tr: " + ast.unparse(n)[:100]
                        for arg in call.args + [k.value for k in call.keywords] for n in _texts_outside_tr(arg)]
    return out


def cmd_audit(args) -> int:
    lines = audit()
    print("\n".join(lines + ["{} places show English text without tr".format(len(lines))]))
    return 1 if lines else 0


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter, epilog=__doc__)
    parser.add_argument("command", choices=("update", "compile", "check", "import", "extract", "audit"))
    parser.add_argument("args", nargs="*", help="languages (default: all), or import's JSON file")
    parser.add_argument("--json", action="store_true", help="check: as {language: {source: translation}}")
    args = parser.parse_args(argv)
    if args.command == "import":
        if len(args.args) != 1:
            parser.error("import takes one JSON file")
        return cmd_import(args.args[0])
    unknown = [x for x in args.args if x not in LANGUAGES]
    if unknown:
        parser.error("unknown language(s) {}: expected {}".format(" ".join(unknown), " ".join(LANGUAGES)))
    args.languages = args.args or list(LANGUAGES)
    return globals()["cmd_" + args.command](args)


if __name__ == "__main__":
    sys.exit(main())
