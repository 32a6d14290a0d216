"""Translations of Road Sign Inventory: extract the user-visible strings, keep the Qt TS
sources in ``i18n/`` up to date, compile them to ``.qm`` and list what is left to translate.

    python scripts/i18n.py extract [--json]      every user-visible string, with its places
    python scripts/i18n.py update                merge them into i18n/roadsigns_<lang>.ts
    python scripts/i18n.py compile               lrelease: i18n/roadsigns_<lang>.qm
    python scripts/i18n.py check [--json]        untranslated / unfinished / broken entries
    python scripts/i18n.py import FILE.json      set translations from {"lang": {"source": "translation"}}
    python scripts/i18n.py audit                 English strings shown to users without tr()

``make i18n`` runs update, compile and check. Workflow for new strings: ``make i18n`` (it
fails listing what is untranslated), then ``python scripts/i18n.py check --json > todo.json``,
fill in the empty values (and review the drafts) of ``todo.json``, ``python scripts/i18n.py
import todo.json``, then ``make i18n`` again. Qt Linguist (``linguist i18n/roadsigns_es.ts``)
works on the same files.

Extraction reads the sources with :mod:`ast` (implicit concatenation is already joined by
the parser). A string is user-visible when it reaches ``QCoreApplication.translate``: the
script follows function parameters through calls (``tr(text)`` -> ``translate``;
``self.add(parameter, help_text)`` -> ``self.tr(help_text)``; ``add_number(.., label, ..,
help_text)``...), local variables, comprehension and loop variables (``[self.tr(m) for m in
self.METHODS]``), subscripts (``OUTPUT_LABELS[name]``), class attributes read as
``self.X`` (``DISPLAY_NAME``, ``HELP`` ... of every algorithm subclass), module constants,
and return values of the functions whose result is translated (``dependencies.py``).
``self.tr(error.template)`` on an ``InputError`` takes every ``InputError(template, ...)``
template of the sources; the values of the fields named in :data:`TRANSLATED_FIELDS`
(``what="Trajectory"``) are extracted too.
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
import xml.etree.ElementTree as ET
from collections import OrderedDict
from typing import Dict, List, Optional, Set, Tuple

REPO_ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
I18N_DIR = os.path.join(REPO_ROOT, "i18n")
CONTEXT = "RoadSigns"
#: TS language code -> file suffix (roadsigns_<suffix>.ts/.qm)
LANGUAGES = OrderedDict([("zh_Hans", "zh_CN"), ("es", "es")])
#: the plugin's Python sources (what ships: see scripts/package.py)
SOURCES = ("__init__.py", "plugin.py", "dependencies.py", "provider", "algorithms", "core")
#: InputError fields whose (English) values are extracted too: they name a kind of file or
#: CRS inside a template ("{what} file {path}: ..."); translated when the adapters pass
#: them through tr (see algorithms/base.py core_errors)
TRANSLATED_FIELDS = ("what", "role", "kind")
#: Processing models shipped with the plugin: ``helpContent()`` in the sources reads their help
#: (the description, ALG_DESC, and each parameter's help)
MODELS = "models"
#: calls whose first argument is an English template the adapters translate (core/errors.py)
TEMPLATE_CALLS = {"InputError", "Message"}
#: adapter calls whose text reaches users: their literals must go through tr
USER_CALLS = {"QgsProcessingException", "pushInfo", "pushWarning", "reportError", "pushFormattedMessage",
              "logMessage", "pushMessage", "pushCommandInfo"}
#: core log calls whose first argument is such a template (``Progress.info/warning``)
CORE_CALLS = {"info", "warning"}
#: lrelease candidates (Debian: qttools5-dev-tools)
LRELEASE = ("lrelease", "/usr/lib/qt5/bin/lrelease", "lrelease-qt5", "lrelease6")


# =====================================================================================
# Extraction
# =====================================================================================

class Found:
    """One extracted string and where it is defined."""

    def __init__(self, text: str, kind: str):
        self.text = text
        self.kind = kind
        self.places: List[Tuple[str, int]] = []

    def __repr__(self):
        return "Found({!r})".format(self.text)


class Module:
    def __init__(self, path: str):
        self.path = path
        self.rel = os.path.relpath(path, REPO_ROOT).replace(os.sep, "/")
        with open(path, encoding="utf-8") as f:
            self.tree = ast.parse(f.read(), filename=path)
        self.assigns: Dict[str, List[ast.AST]] = {}     # module-level NAME = value
        self.imports: Dict[str, Tuple[str, str]] = {}   # local name -> (module rel, name)
        for node in self.tree.body:
            for target, value in _assignments(node):
                self.assigns.setdefault(target, []).append(value)
            if isinstance(node, ast.ImportFrom) and node.level:
                base = os.path.dirname(self.rel)
                for _ in range(node.level - 1):
                    base = os.path.dirname(base)
                mod = (base + "/" if base else "") + (node.module or "").replace(".", "/")
                for alias in node.names:
                    self.imports[alias.asname or alias.name] = (mod.strip("/"), alias.name)


class Function:
    def __init__(self, module: Module, node, cls: Optional[ast.ClassDef]):
        self.module = module
        self.node = node
        self.cls = cls
        self.name = node.name
        args = node.args
        self.params = [a.arg for a in args.posonlyargs + args.args]
        self.kwonly = [a.arg for a in args.kwonlyargs]
        self.is_method = cls is not None and not any(
            isinstance(d, ast.Name) and d.id == "staticmethod" for d in node.decorator_list)


def _assignments(node):
    """(name, value) of ``name = value`` / ``name: T = value`` statements."""
    if isinstance(node, ast.Assign):
        for target in node.targets:
            if isinstance(target, ast.Name):
                yield target.id, node.value
    elif isinstance(node, ast.AnnAssign) and isinstance(node.target, ast.Name) and node.value:
        yield node.target.id, node.value


def _call_name(call: ast.Call) -> Tuple[Optional[str], bool]:
    """(function name, called as attribute ``x.name(...)``)."""
    if isinstance(call.func, ast.Name):
        return call.func.id, False
    if isinstance(call.func, ast.Attribute):
        return call.func.attr, True
    return None, False


def source_files() -> List[str]:
    out = []
    for entry in SOURCES:
        path = os.path.join(REPO_ROOT, entry)
        if os.path.isfile(path):
            out.append(path)
        elif os.path.isdir(path):
            for root, dirs, files in os.walk(path):
                dirs[:] = sorted(d for d in dirs if d != "__pycache__")
                out += [os.path.join(root, f) for f in sorted(files) if f.endswith(".py")]
    return out


class Extractor:
    """Finds every string that reaches ``QCoreApplication.translate``."""

    def __init__(self, files: Optional[List[str]] = None):
        self.modules = [Module(p) for p in (files or source_files())]
        self.by_rel = {m.rel[:-3]: m for m in self.modules}
        self.functions: List[Function] = []
        self.classes: Dict[str, List[Tuple[Module, ast.ClassDef]]] = {}
        self.parents: Dict[ast.AST, ast.AST] = {}
        for m in self.modules:
            for node in ast.walk(m.tree):
                for child in ast.iter_child_nodes(node):
                    self.parents[child] = node
            self._collect(m, m.tree.body, None)
        self.found: "OrderedDict[str, Found]" = OrderedDict()
        self.warnings: List[str] = []
        #: function name -> translated parameter names
        self.translated_params: Dict[str, Set[str]] = {}
        #: parameters whose values are InputError fields to extract (TRANSLATED_FIELDS)
        self.field_params: Dict[str, Set[str]] = {}
        self.templates_translated = False

    def _collect(self, module, body, cls):
        for node in body:
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
                self.functions.append(Function(module, node, cls))
                self._collect(module, node.body, None)  # nested functions
            elif isinstance(node, ast.ClassDef):
                self.classes.setdefault(node.name, []).append((module, node))
                self._collect(module, node.body, node)

    # --- scopes --------------------------------------------------------------------

    def _function_of(self, node) -> Optional[Function]:
        while node is not None:
            node = self.parents.get(node)
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
                for f in self.functions:
                    if f.node is node:
                        return f
        return None

    def _module_of(self, node) -> Module:
        while node in self.parents:
            node = self.parents[node]
        for m in self.modules:
            if m.tree is node:
                return m
        raise KeyError(node)

    def _class_family(self, cls: ast.ClassDef) -> List[ast.ClassDef]:
        """The class, its (scanned) bases and every (scanned) subclass, transitively."""
        family = {cls.name}
        changed = True
        while changed:
            changed = False
            for name, defs in self.classes.items():
                for _, c in defs:
                    bases = {b.id if isinstance(b, ast.Name) else getattr(b, "attr", None) for b in c.bases}
                    if name not in family and bases & family:
                        family.add(name)
                        changed = True
        pending = [cls]
        while pending:  # bases of the class itself
            c = pending.pop()
            for b in c.bases:
                bname = b.id if isinstance(b, ast.Name) else getattr(b, "attr", None)
                if bname in self.classes and bname not in family:
                    family.add(bname)
                    pending += [d for _, d in self.classes[bname]]
        return [c for name in family for _, c in self.classes.get(name, [])]

    # --- resolution ------------------------------------------------------------------

    def resolve(self, expr, scope: Optional[Function], module: Module, kind: str, on_param,
                seen=None) -> List[Tuple[str, ast.AST]]:
        """Strings ``expr`` can take: [(text, node)]. Parameters of ``scope`` it comes from
        are passed to ``on_param(function, name)``."""
        seen = set() if seen is None else seen
        key = (id(expr), id(scope))
        if key in seen:
            return []
        seen.add(key)
        r = lambda e, s=scope, m=module: self.resolve(e, s, m, kind, on_param, seen)  # noqa: E731
        where = "{}:{}".format(module.rel, getattr(expr, "lineno", "?"))
        if isinstance(expr, ast.Constant):
            return [(expr.value, expr)] if isinstance(expr.value, str) else []
        if isinstance(expr, ast.JoinedStr):
            self.warnings.append("{}: f-string given to tr(): translate a template and .format() "
                                 "it after tr".format(where))
            return []
        if isinstance(expr, ast.BinOp) and isinstance(expr.op, ast.Add):
            left, right = r(expr.left), r(expr.right)
            return [(a + b, na) for a, na in left for b, _ in right]
        if isinstance(expr, (ast.List, ast.Tuple, ast.Set)):
            return [x for e in expr.elts for x in r(e)]
        if isinstance(expr, ast.Dict):
            return [x for e in expr.values for x in r(e)]
        if isinstance(expr, ast.IfExp):
            return r(expr.body) + r(expr.orelse)
        if isinstance(expr, ast.BoolOp):
            return [x for e in expr.values for x in r(e)]
        if isinstance(expr, ast.Subscript):
            return r(expr.value)
        if isinstance(expr, ast.Starred):
            return r(expr.value)
        if isinstance(expr, ast.Attribute):
            if expr.attr == "template":
                self.templates_translated = True
                return []
            if expr.attr == "fields":  # InputError fields: see TRANSLATED_FIELDS
                return []
            if isinstance(expr.value, ast.Name) and expr.value.id in ("self", "cls") and scope and scope.cls:
                out = []
                for c in self._class_family(scope.cls):
                    cmod = self._module_of(c)
                    for node in c.body:
                        for target, value in _assignments(node):
                            if target == expr.attr:
                                out += r(value, None, cmod)
                return out
            if isinstance(expr.value, ast.Name) and expr.value.id in module.imports:
                return self._resolve_global(expr.attr, self.by_rel.get(module.imports[expr.value.id][0]),
                                            kind, on_param, seen)
            self.warnings.append("{}: cannot follow {} given to tr()".format(where, ast.unparse(expr)))
            return []
        if isinstance(expr, ast.Call):
            name, _ = _call_name(expr)
            if name == "format" and isinstance(expr.func, ast.Attribute):
                texts = r(expr.func.value)
                if texts:
                    self.warnings.append("{}: a string is formatted before tr() ({}...): the "
                                         "formatted text is never found in the translations; "
                                         "translate the template, then format".format(where, texts[0][0][:40]))
                return texts
            if name in ("strip", "rstrip", "lstrip"):
                return r(expr.func.value)
            if name == "str" and expr.args:
                return r(expr.args[0])
            if name == "get" and isinstance(expr.func, ast.Attribute):  # d.get(key, default)
                default = expr.args[1:2]
                return r(expr.func.value) + (r(default[0]) if default and isinstance(default[0], ast.Constant) else [])
            if name == "helpContent":
                return self._model_help()
            targets = [f for f in self.functions if f.name == name and f.cls is None]
            out = []
            for f in targets:  # the function's return values
                for node in ast.walk(f.node):
                    if isinstance(node, ast.Return) and node.value is not None and \
                            self._function_of(node) is f:
                        out += self.resolve(node.value, f, f.module, kind, on_param, seen)
            if not targets:
                self.warnings.append("{}: cannot follow {} given to tr()".format(where, ast.unparse(expr)))
            return out
        if isinstance(expr, ast.Name):
            return self._resolve_name(expr, scope, module, kind, on_param, seen)
        self.warnings.append("{}: cannot follow {} given to tr()".format(where, ast.unparse(expr)))
        return []

    def _resolve_name(self, expr, scope, module, kind, on_param, seen):
        name = expr.id
        r = lambda e, s=scope, m=module: self.resolve(e, s, m, kind, on_param, seen)  # noqa: E731
        # comprehension variables around expr
        node = expr
        while node in self.parents:
            node = self.parents[node]
            if isinstance(node, (ast.ListComp, ast.SetComp, ast.GeneratorExp, ast.DictComp)):
                for gen in node.generators:
                    position = _target_position(gen.target, name)
                    if position is not False:
                        return self._resolve_iter(gen.iter, position, r, scope, module)
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
                break
        if scope is not None:
            out, bound = [], False
            for node in ast.walk(scope.node):
                if self._function_of(node) is not scope and node is not scope.node:
                    continue
                for target, value in _assignments(node):
                    if target == name:
                        out += r(value)
                        bound = True
                if isinstance(node, (ast.For, ast.AsyncFor)):
                    position = _target_position(node.target, name)
                    if position is not False:
                        out += self._resolve_iter(node.iter, position, r, scope, module)
                        bound = True
            if name in scope.params or name in scope.kwonly:
                on_param(scope, name)
                bound = True
            if bound:
                return out
        return self._resolve_global(name, module, kind, on_param, seen)

    def _resolve_iter(self, iterable, position, r, scope, module):
        """Strings a loop variable takes: ``position`` is its index in a tuple target
        (None for a plain name); ``d.items()``, ``d.keys()``, ``d.values()``, ``zip``,
        ``enumerate`` and iterating a dict (its keys) are understood."""
        if isinstance(iterable, ast.Call):
            name, attr = _call_name(iterable)
            if attr and name in ("items", "keys", "values"):
                if name == "values" or (name == "items" and position == 1):
                    return r(iterable.func.value)
                if name == "keys" or (name == "items" and position == 0):
                    return [x for k in self._dict_keys(iterable.func.value, scope, module) for x in r(k)]
                return []
            if name == "zip" and not attr and position is not None:
                return r(iterable.args[position]) if position < len(iterable.args) else []
            if name == "enumerate" and not attr and iterable.args:
                return r(iterable.args[0]) if position == 1 else []
            if name == "sorted" and not attr and iterable.args:
                return self._resolve_iter(iterable.args[0], position, r, scope, module)
        keys = self._dict_keys(iterable, scope, module)
        if keys:
            return [x for k in keys for x in r(k)]
        return r(iterable)

    def _dict_keys(self, expr, scope, module, depth=0):
        """Key nodes of the dict literal(s) ``expr`` names ([] when it is not a dict)."""
        if depth > 5:
            return []
        if isinstance(expr, ast.Dict):
            return [k for k in expr.keys if k is not None]
        values = []
        if isinstance(expr, ast.Name):
            if scope is not None:
                values = [v for node in ast.walk(scope.node) for t, v in _assignments(node) if t == expr.id]
            if not values:
                m = module
                while m is not None and expr.id not in m.assigns and expr.id in m.imports:
                    m = self.by_rel.get(m.imports[expr.id][0])
                values = m.assigns.get(expr.id, []) if m is not None else []
        return [k for v in values for k in self._dict_keys(v, scope, module, depth + 1)]

    def _model_help(self) -> List[Tuple[str, "ModelString"]]:
        """The description (ALG_DESC) and parameter help of every shipped model."""
        out = []
        for path in sorted(glob.glob(os.path.join(REPO_ROOT, MODELS, "*.model3"))):
            rel = os.path.relpath(path, REPO_ROOT).replace(os.sep, "/")
            with open(path, encoding="utf-8") as f:
                text = f.read()
            root = ET.fromstring(re.sub(r"<!DOCTYPE[^>]*>", "", text))
            maps = {o.get("name"): o for o in root.findall("Option")}
            help_map = maps.get("help")
            parameters = {o.get("name") for o in maps["parameterDefinitions"].findall("Option")} \
                if "parameterDefinitions" in maps else set()
            if help_map is None:
                continue
            lines = text.splitlines()
            start = next((i for i, line in enumerate(lines) if 'name="help"' in line and 'type="Map"' in line), 0)
            for option in help_map.findall("Option"):
                key, value = option.get("name"), option.get("value") or ""
                if key == "ALG_DESC" or key in parameters:
                    line = next((i + 1 for i in range(start, len(lines)) if 'name="{}"'.format(key) in lines[i]), 0)
                    out.append((value, ModelString(rel, line)))
        return out

    def _resolve_global(self, name, module, kind, on_param, seen):
        if module is None:
            return []
        if name in module.assigns:
            return [x for v in module.assigns[name]
                    for x in self.resolve(v, None, module, kind, on_param, seen)]
        if name in module.imports:
            rel, original = module.imports[name]
            return self._resolve_global(original, self.by_rel.get(rel), kind, on_param, seen)
        return []

    # --- the analysis ----------------------------------------------------------------

    def _add(self, text, node, module, kind):
        if not text.strip():
            return
        item = self.found.get(text)
        if item is None:
            item = self.found[text] = Found(text, kind)
        place = (module.rel, getattr(node, "lineno", 0))
        if place not in item.places:
            item.places.append(place)

    def _sink(self, expr, call_node, kind, param_map):
        scope = self._function_of(call_node)
        module = self._module_of(call_node)

        def on_param(function, name):
            param_map.setdefault(function.name, set())
            if name not in param_map[function.name]:
                param_map[function.name].add(name)
                self._changed = True

        for text, node in self.resolve(expr, scope, module, kind, on_param):
            if isinstance(node, ModelString):
                self._add(text, node, node, kind)
            else:
                self._add(text, node, self._module_of(node) if node in self.parents else module, kind)

    def _argument(self, call: ast.Call, function: Function, param: str):
        """The argument ``call`` passes for ``param`` of ``function`` (None if not given)."""
        for kw in call.keywords:
            if kw.arg == param:
                return kw.value
        if param in function.params:
            index = function.params.index(param)
            if function.is_method and isinstance(call.func, ast.Attribute):
                index -= 1  # self
            if 0 <= index < len(call.args) and not any(isinstance(a, ast.Starred) for a in call.args[:index + 1]):
                return call.args[index]
        return None

    def run(self) -> "OrderedDict[str, Found]":
        calls = [n for m in self.modules for n in ast.walk(m.tree) if isinstance(n, ast.Call)]
        # seeds: QCoreApplication.translate(context, text), and translate(text) where a
        # translating function is passed in as ``translate`` (dependencies.py)
        for call in calls:
            name, _ = _call_name(call)
            if name == "translate" and len(call.args) >= 2:
                self._sink(call.args[1], call, "tr", self.translated_params)
            elif name == "translate" and len(call.args) == 1:
                self._sink(call.args[0], call, "tr", self.translated_params)
            if name in TEMPLATE_CALLS:
                for kw in call.keywords:
                    if kw.arg in TRANSLATED_FIELDS:
                        self._sink(kw.value, call, "field", self.field_params)
        # follow parameters through calls until nothing changes
        self._changed = True
        done: Set[Tuple[int, str, str]] = set()
        while self._changed:
            self._changed = False
            for param_map, kind in ((self.translated_params, "tr"), (self.field_params, "field")):
                for fname, params in list(param_map.items()):
                    functions = [f for f in self.functions if f.name == fname]
                    for call in calls:
                        name, _ = _call_name(call)
                        if name != fname:
                            continue
                        for param in list(params):
                            for f in functions:
                                arg = self._argument(call, f, param)
                                if arg is not None and (id(call), param, kind) not in done:
                                    done.add((id(call), param, kind))
                                    self._sink(arg, call, kind, param_map)
        if self.templates_translated:
            for module in self.modules:
                in_core = module.rel.startswith("core/")
                for call in (n for n in ast.walk(module.tree) if isinstance(n, ast.Call)):
                    name, attr = _call_name(call)
                    template = call.args[0] if call.args else next(
                        (k.value for k in call.keywords if k.arg == "template"), None)
                    if template is None:
                        continue
                    if name in TEMPLATE_CALLS:
                        self._sink(template, call, "template", {})
                    elif in_core and ((attr and name in CORE_CALLS) or (not attr and name == "warn")) \
                            and isinstance(template, ast.Constant) and isinstance(template.value, str):
                        self._sink(template, call, "template", {})  # Progress.info/warning(template)
        # order: by file, then line of the first place
        items = sorted(self.found.values(), key=lambda f: ((SOURCES + (MODELS,)).index(_top(f.places[0][0])),
                                                            f.places[0][0], f.places[0][1]))
        self.warnings = sorted(set(self.warnings))
        return OrderedDict((f.text, f) for f in items)


class ModelString:
    """Where a string of a shipped model is (stands in for an ast node)."""

    def __init__(self, rel: str, line: int):
        self.rel = rel
        self.lineno = line


def _target_position(target, name):
    """None if the loop target is ``name`` itself, its index in a tuple target, or False."""
    if isinstance(target, ast.Name):
        return None if target.id == name else False
    if isinstance(target, (ast.Tuple, ast.List)):
        for i, element in enumerate(target.elts):
            if isinstance(element, ast.Name) and element.id == name:
                return i
            if _target_position(element, name) is not False:
                return i
    return False


def _top(rel):
    top = rel.split("/")[0]
    return top if top in SOURCES else MODELS if top == MODELS else SOURCES[0]


def extract(files: Optional[List[str]] = None) -> "OrderedDict[str, Found]":
    return Extractor(files).run()


# =====================================================================================
# Placeholders, tags
# =====================================================================================

def placeholders(text: str) -> List[str]:
    """The ``str.format`` fields of ``text`` as written (``{path}``, ``{}``, ``{value!r}``),
    sorted; raises ValueError for a malformed format string."""
    out = []
    for _, field, spec, conversion in string.Formatter().parse(text):
        if field is not None:
            out.append("{" + field + ("!" + conversion if conversion else "") +
                       (":" + spec if spec else "") + "}")
    return sorted(out)


TAG = re.compile(r"</?[a-zA-Z][a-zA-Z0-9]*\s*/?>")


def tags(text: str) -> List[str]:
    return sorted(TAG.findall(text))


def problems(source: str, translation: str) -> List[str]:
    """What is wrong with a (non-empty) translation: placeholders or HTML tags differ."""
    out = []
    try:
        want = placeholders(source)
    except ValueError:
        want = None  # not a format string (never .format()ed)
    if want is not None:
        try:
            got = placeholders(translation)
        except ValueError as e:
            return ["not a valid format string ({})".format(e)]
        if got != want:
            out.append("placeholders {} instead of {}".format(" ".join(got) or "none", " ".join(want) or "none"))
    if tags(source) != tags(translation):
        out.append("HTML tags {} instead of {}".format(" ".join(tags(translation)) or "none",
                                                     " ".join(tags(source)) or "none"))
    return out


# =====================================================================================
# TS files
# =====================================================================================

class Entry:
    def __init__(self, source, translation="", state="unfinished", places=(), comment=""):
        self.source = source
        self.translation = translation
        self.state = state            # "finished", "unfinished" or "vanished"
        self.places = list(places)
        self.comment = comment        # <extracomment> for the translator (never a disambiguation)


def ts_path(language: str) -> str:
    return os.path.join(I18N_DIR, "roadsigns_{}.ts".format(language))


def qm_path(language: str) -> str:
    return os.path.join(I18N_DIR, "roadsigns_{}.qm".format(language))


def read_ts(path: str) -> "OrderedDict[str, Entry]":
    entries: "OrderedDict[str, Entry]" = OrderedDict()
    if not os.path.exists(path):
        return entries
    root = ET.parse(path).getroot()
    for context in root.iter("context"):
        if (context.findtext("name") or "") != CONTEXT:
            continue
        for message in context.iter("message"):
            source = message.findtext("source") or ""
            node = message.find("translation")
            text = (node.text or "") if node is not None else ""
            kind = node.get("type") if node is not None else None
            state = "vanished" if kind in ("vanished", "obsolete") else \
                "unfinished" if kind == "unfinished" or not text else "finished"
            places = [(loc.get("filename", ""), int(loc.get("line", "0") or 0))
                      for loc in message.findall("location")]
            entries[source] = Entry(source, text, state, places, message.findtext("extracomment") or "")
    return entries


def _x(text: str) -> str:
    return (text.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")
            .replace('"', "&quot;").replace("'", "&apos;"))


def write_ts(path: str, language: str, entries: List[Entry]):
    lines = ['<?xml version="1.0" encoding="utf-8"?>', "<!DOCTYPE TS>",
             '<TS version="2.1" language="{}" sourcelanguage="en">'.format(LANGUAGES.get(language, language)),
             "<context>", "    <name>{}</name>".format(CONTEXT)]
    for e in entries:
        lines.append("    <message>")
        if e.state != "vanished":
            for filename, line in e.places:
                lines.append('        <location filename="{}" line="{}"/>'.format(_x(filename), line))
        lines.append("        <source>{}</source>".format(_x(e.source)))
        if e.comment:
            lines.append("        <extracomment>{}</extracomment>".format(_x(e.comment)))
        kind = {"finished": "", "unfinished": ' type="unfinished"', "vanished": ' type="vanished"'}[e.state]
        lines.append("        <translation{}>{}</translation>".format(kind, _x(e.translation)))
        lines.append("    </message>")
    lines += ["</context>", "</TS>", ""]
    tmp = path + ".part"
    with open(tmp, "w", encoding="utf-8", newline="\n") as f:
        f.write("\n".join(lines))
    os.replace(tmp, path)


COMMENTS = {
    "template": "Error message. Keep every {field} exactly as written; they are filled in afterwards.",
    "field": "A fragment filled into {what}, {role} or {kind} of error messages (a kind of file or CRS, "
             "or 'is duplicated'): write it to fit those messages' translations, lowercase.",
}


def merge(found: "OrderedDict[str, Found]", old: "OrderedDict[str, Entry]") -> Tuple[List[Entry], Dict[str, int]]:
    """Entries for ``found`` keeping ``old`` translations; vanished ones at the end. New
    strings close to a vanished one (a reworded source) get its translation as a draft."""
    out, stats = [], {"kept": 0, "new": 0, "draft": 0, "vanished": 0}
    from_i18n = lambda p: ("../" + p[0], p[1])  # noqa: E731  (paths relative to i18n/)
    vanished = [e for s, e in old.items() if s not in found and e.translation]
    for text, item in found.items():
        comment = COMMENTS.get(item.kind, "")
        previous = old.get(text)
        if previous is not None and previous.translation:
            state = "finished" if previous.state == "vanished" else previous.state
            out.append(Entry(text, previous.translation, state, map(from_i18n, item.places), comment))
            stats["kept"] += 1
            continue
        similar = difflib.get_close_matches(text, [e.source for e in vanished], n=1, cutoff=0.8)
        if similar:
            draft = next(e for e in vanished if e.source == similar[0])
            out.append(Entry(text, draft.translation, "unfinished", map(from_i18n, item.places), comment))
            stats["draft"] += 1
        else:
            out.append(Entry(text, "", "unfinished", map(from_i18n, item.places), comment))
            stats["new"] += 1
    for e in vanished:
        out.append(Entry(e.source, e.translation, "vanished", (), e.comment))
        stats["vanished"] += 1
    return out, stats


# =====================================================================================
# Commands
# =====================================================================================

def cmd_extract(args) -> int:
    extractor = Extractor()
    found = extractor.run()
    if args.json:
        json.dump([{"source": f.text, "kind": f.kind, "places": ["{}:{}".format(*p) for p in f.places]}
                   for f in found.values()], sys.stdout, ensure_ascii=False, indent=1)
        print()
    else:
        for f in found.values():
            print("{}:{}: [{}] {}".format(f.places[0][0], f.places[0][1], f.kind,
                                          f.text if len(f.text) < 100 else f.text[:97] + "..."))
        print("{} strings".format(len(found)), file=sys.stderr)
    for w in extractor.warnings:
        print("warning: " + w, file=sys.stderr)
    return 0


def cmd_update(args) -> int:
    found = extract()
    os.makedirs(I18N_DIR, exist_ok=True)
    for language in args.languages or LANGUAGES:
        entries, stats = merge(found, read_ts(ts_path(language)))
        write_ts(ts_path(language), language, entries)
        print("{}: {} strings ({kept} kept, {new} new, {draft} drafts from similar strings, "
              "{vanished} vanished)".format(os.path.relpath(ts_path(language), REPO_ROOT), len(found), **stats))
    return 0


def find_lrelease() -> Optional[str]:
    for name in LRELEASE:
        path = shutil.which(name) or (name if os.path.isabs(name) and os.access(name, os.X_OK) else None)
        if path:
            return path
    return None


def compile_ts(ts: str, qm: str, lrelease: Optional[str] = None) -> None:
    lrelease = lrelease or find_lrelease()
    if lrelease is None:
        raise FileNotFoundError("lrelease not found: install the Debian package qttools5-dev-tools "
                                "(sudo apt-get install qttools5-dev-tools)")
    # only finished translations ship: drafts (unfinished) stay English until reviewed
    p = subprocess.run([lrelease, "-silent", "-nounfinished", ts, "-qm", qm],
                       capture_output=True, text=True)
    if p.returncode != 0 or not os.path.exists(qm):
        raise RuntimeError("lrelease failed on {}:\n{}{}".format(ts, p.stdout, p.stderr))


def qm_up_to_date(ts: str, qm: str) -> bool:
    """Whether ``qm`` is what lrelease makes of ``ts`` now (lrelease's output is
    deterministic); without lrelease, whether it is newer than ``ts``."""
    lrelease = find_lrelease()
    if lrelease is None:
        return os.path.getmtime(qm) >= os.path.getmtime(ts)
    import tempfile
    with tempfile.TemporaryDirectory() as tmp:
        fresh = os.path.join(tmp, "fresh.qm")
        compile_ts(ts, fresh, lrelease)
        with open(fresh, "rb") as a, open(qm, "rb") as b:
            return a.read() == b.read()


def cmd_compile(args) -> int:
    lrelease = find_lrelease()
    if lrelease is None:
        print("lrelease not found: install the Debian package qttools5-dev-tools "
              "(sudo apt-get install qttools5-dev-tools); the .qm files were not rebuilt",
              file=sys.stderr)
        return 2
    for language in args.languages or LANGUAGES:
        compile_ts(ts_path(language), qm_path(language), lrelease)
        print("{} ({} bytes)".format(os.path.relpath(qm_path(language), REPO_ROOT),
                                    os.path.getsize(qm_path(language))))
    return 0


def check(found=None, languages=None) -> Dict[str, List[Tuple[str, str]]]:
    """Per language: [(source, what is wrong)] for every extracted string without a
    finished, well-formed translation, plus stale .qm files."""
    found = extract() if found is None else found
    report = {}
    for language in languages or LANGUAGES:
        entries = read_ts(ts_path(language))
        issues = []
        for text in found:
            e = entries.get(text)
            if e is None:
                issues.append((text, "missing from the .ts (run: python scripts/i18n.py update)"))
            elif not e.translation:
                issues.append((text, "untranslated"))
            elif e.state != "finished":
                issues.append((text, "draft to review (copied from a similar, reworded string)"))
            else:
                issues += [(text, p) for p in problems(text, e.translation)]
        ts, qm = ts_path(language), qm_path(language)
        if not os.path.exists(qm):
            issues.append(("", "{} missing (run: python scripts/i18n.py compile)".format(os.path.basename(qm))))
        elif os.path.exists(ts) and not qm_up_to_date(ts, qm):
            issues.append(("", "{} not compiled from the current .ts (run: python scripts/i18n.py compile)"
                           .format(os.path.basename(qm))))
        report[language] = issues
    return report


def cmd_check(args) -> int:
    found = extract()
    report = check(found, args.languages)
    if args.json:  # ready to fill in and import: {language: {source: current translation}}
        out = {}
        for language, issues in report.items():
            entries = read_ts(ts_path(language))
            out[language] = OrderedDict(
                (s, entries[s].translation if s in entries else "") for s, _ in issues if s)
        json.dump(out, sys.stdout, ensure_ascii=False, indent=1)
        print()
    else:
        for language, issues in report.items():
            print("{}: {} of {} strings need work".format(language, len([s for s, _ in issues if s]), len(found)))
            for source, what in issues:
                print("  - {}{}".format(what, ": " + json.dumps(source, ensure_ascii=False) if source else ""))
    return 1 if any(report.values()) else 0


def cmd_import(args) -> int:
    """Set translations from JSON: {language: {source: translation}} (what ``check --json``
    writes) or, with --language, {source: translation}. Empty values are left alone."""
    with open(args.file, encoding="utf-8") as f:
        data = json.load(f)
    if data and all(k in LANGUAGES and isinstance(v, dict) for k, v in data.items()):
        jobs = [(k, v) for k, v in data.items() if not args.language or k == args.language]
    elif args.language:
        jobs = [(args.language, data)]
    else:
        print("{}: expected {{language: {{source: translation}}}}, or give --language".format(args.file),
              file=sys.stderr)
        return 2
    status = 0
    for language, translations in jobs:
        status = max(status, _import(language, translations))
    return status


def _import(language, data) -> int:
    path = ts_path(language)
    entries = read_ts(path)
    if not entries:
        entries = OrderedDict((e.source, e) for e in merge(extract(), entries)[0])
    done, errors = 0, []
    for source, translation in data.items():
        if not translation:
            continue
        if source not in entries:
            errors.append("not in {}: {!r}".format(os.path.basename(path), source[:80]))
            continue
        bad = problems(source, translation)
        if bad:
            errors.append("{!r}: {}".format(source[:80], "; ".join(bad)))
            continue
        e = entries[source]
        e.translation = translation
        if e.state != "vanished":
            e.state = "finished"
        done += 1
    write_ts(path, language, list(entries.values()))
    print("{}: {} translations set".format(os.path.relpath(path, REPO_ROOT), done))
    for e in errors:
        print("  skipped " + e, file=sys.stderr)
    return 1 if errors else 0




def audit() -> List[str]:
    """English text shown to users without tr(): literals in messages of the adapters
    (exceptions, feedback, message log), and log messages of core built as finished text
    (f-strings, ``.format``, ``+``) instead of a template with fields (``Message``,
    ``progress.info/warning(template, **fields)``), which the adapters cannot translate."""
    out = []
    for m in Extractor().modules:
        in_core = m.rel.startswith("core/")
        parents = {}
        for node in ast.walk(m.tree):
            for child in ast.iter_child_nodes(node):
                parents[child] = node
        for call in (n for n in ast.walk(m.tree) if isinstance(n, ast.Call)):
            name, attr = _call_name(call)
            target = None
            if in_core and ((attr and name in CORE_CALLS) or (not attr and name == "warn") or
                            name in TEMPLATE_CALLS or (
                                attr and name == "append" and isinstance(call.func.value, ast.Name)
                                and call.func.value.id in ("warnings", "messages"))):
                first = call.args[:1]
                if first and _built_text(first[0]):
                    out.append("{}:{}: {}".format(m.rel, call.lineno, ast.unparse(first[0])[:110]))
                continue
            elif not in_core and name in USER_CALLS:
                target = call.args
            if not target:
                continue
            for arg in target:
                for node in ast.walk(arg):
                    if isinstance(node, (ast.Constant, ast.JoinedStr)) and \
                            (isinstance(node, ast.JoinedStr) or isinstance(node.value, str)) and \
                            re.search(r"[A-Za-z]{2,}[^A-Za-z_]*\s[^A-Za-z_]*[A-Za-z]{2,}", _text(node)) and \
                            not _inside_tr(node, parents):
                        out.append("{}:{}: {}".format(m.rel, call.lineno, ast.unparse(arg)[:110]))
                        break
    return out


def _built_text(node) -> bool:
    """An f-string, ``"...".format(...)`` or a ``+`` of strings: finished English text."""
    if isinstance(node, ast.JoinedStr):
        return True
    if isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) and node.func.attr == "format":
        return True
    return isinstance(node, ast.BinOp) and any(
        isinstance(n, (ast.Constant, ast.JoinedStr)) and isinstance(getattr(n, "value", ""), str)
        for n in (node.left, node.right))


def _text(node) -> str:
    """A literal's text; an f-string's literal parts with {} for the values."""
    if isinstance(node, ast.JoinedStr):
        return "".join(v.value if isinstance(v, ast.Constant) else " {} " for v in node.values)
    return node.value


def _inside_tr(node, parents) -> bool:
    while node in parents:
        node = parents[node]
        if isinstance(node, ast.Call) and _call_name(node)[0] in ("tr", "translate"):
            return True
    return False


def cmd_audit(args) -> int:
    lines = audit()
    for line in lines:
        print(line)
    print("{} places show English text without tr()".format(len(lines)), file=sys.stderr)
    return 0


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter, epilog=__doc__)
    sub = parser.add_subparsers(dest="command", required=True)
    p = sub.add_parser("extract", help="list the user-visible strings")
    p.add_argument("--json", action="store_true")
    p.set_defaults(run=cmd_extract)
    for name, run, what in (("update", cmd_update, "merge the strings into the .ts files"),
                            ("compile", cmd_compile, "build the .qm files with lrelease")):
        p = sub.add_parser(name, help=what)
        p.add_argument("languages", nargs="*", help="default: " + " ".join(LANGUAGES))
        p.set_defaults(run=run)
    p = sub.add_parser("check", help="list untranslated, unfinished or broken translations")
    p.add_argument("languages", nargs="*", help="default: " + " ".join(LANGUAGES))
    p.add_argument("--json", action="store_true", help="as {language: {source: translation}} to fill in")
    p.set_defaults(run=cmd_check)
    p = sub.add_parser("import", help="set translations from JSON (as check --json writes it)")
    p.add_argument("file")
    p.add_argument("--language", choices=list(LANGUAGES), help="only this language / the file is "
                   "{source: translation} for it")
    p.set_defaults(run=cmd_import)
    p = sub.add_parser("audit", help="English strings shown to users without tr()")
    p.set_defaults(run=cmd_audit)
    args = parser.parse_args(argv)
    unknown = [x for x in getattr(args, "languages", None) or [] if x not in LANGUAGES]
    if unknown:
        parser.error("unknown language(s) {}: expected {}".format(" ".join(unknown), " ".join(LANGUAGES)))
    return args.run(args)


if __name__ == "__main__":
    sys.exit(main())
