"""The documentation's generated pages, drawn from the code at every build.

Sphinx extension (``docs/conf.py``), run when the builder starts. It writes Markdown into
``docs/_generated/`` (included by the reference pages) and ``docs/results/generated/``
(the results, one page per report), each from one source:

- the scene keys: ``contract.scene.KEYS`` (the parser's own table: keys, what each accepts,
  unit, default) and ``reference_fem.settings`` (the ``[fem]`` keys and the values the
  parser resolves), with the meanings of ``docs/reference/scene-keys.toml``;
- the record keys: ``contract.record`` (the keys of every record) and the keys the
  committed records in ``reports/data`` hold, with the meanings of
  ``docs/reference/record-keys.toml``;
- the make targets: the Makefile, each target's comment;
- the registered elements, laws, formulations and integrators: their registries;
- the API: one ``automodule`` per module of ``contract``, ``mechanics`` and ``ancf``;
- the results: ``reports/*.md`` and ``reports/cards/*.md``, each figure made a captioned
  figure (its caption the report's own paragraph under the image, or the one of
  ``docs/results/figures.toml``) with the legend of ``docs/results/figures.toml``.

A key, target, figure or table that misses its text is a warning, and ``make docs`` turns
warnings into errors: a new scene key, record key or figure cannot go undocumented.
:func:`generate` runs without Sphinx too (``tests/test_docs_reference.py``).
"""
from __future__ import annotations

import fnmatch
import importlib
import json
import math
import os
import pkgutil
import re
import tomllib
from pathlib import Path
from collections.abc import Mapping
from typing import Callable

DOCS = Path(__file__).resolve().parents[1]
ROOT = DOCS.parent
GENERATED = DOCS / "_generated"
RESULTS = DOCS / "results" / "generated"
REPORTS = ROOT / "reports"
API_PACKAGES = ("contract", "mechanics", "ancf")


# -- small helpers ----------------------------------------------------------------------

def _cell(text) -> str:
    """Text fit for one cell of a Markdown table."""
    return str(text).replace("|", "\\|").replace("\n", " ").strip()


def _table(header: list[str], rows: list[list]) -> str:
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(_cell(c) for c in row) + " |" for row in rows]
    return "\n".join(lines) + "\n"


def _code(v) -> str:
    return f"`{v}`"


def _value(v) -> str:
    """A default as a reader types it in TOML."""
    if isinstance(v, bool):
        return _code(str(v).lower())
    if isinstance(v, float):
        return _code(f"{v:g}")
    if isinstance(v, str):
        return _code(f'"{v}"')
    if isinstance(v, (list, tuple)):
        return _code("[" + ", ".join(f"{x:g}" if isinstance(x, float) else str(x) for x in v) + "]")
    return _code(v)


def _write(path: Path, text: str) -> None:
    """Write only when the text changed (Sphinx rereads what changed)."""
    path.parent.mkdir(parents=True, exist_ok=True)
    if not path.is_file() or path.read_text(encoding="utf-8") != text:
        path.write_text(text, encoding="utf-8")


def _toml(path: Path) -> dict:
    return tomllib.loads(path.read_text(encoding="utf-8"))


# -- the scene keys ----------------------------------------------------------------------

def _registered(what: str) -> list[str]:
    if what == "law":
        from mechanics.laws import LAWS
        return list(LAWS)
    if what == "formulation":
        from contract.scene import FORMULATIONS
        return list(FORMULATIONS)
    if what == "element":
        from ancf.elements import ELEMENTS
        return list(ELEMENTS)
    if what == "integrator":
        from ancf.solvers.integrators import INTEGRATORS
        return list(INTEGRATORS)
    raise KeyError(what)


def accepts_text(accepts: tuple) -> str:
    """What a key accepts (``contract.scene.Key.accepts``), in words."""
    from contract.scene import MAX_GAUSS

    kind, *args = accepts
    if kind == "name" and args:
        names = ", ".join(_code(n) for n in _registered(args[0]))
        return f"a registered {args[0]} name: {names}" + (" or a user's" if args[0] in ("law", "element") else "")
    return {
        "name": lambda: "non-empty string",
        "text": lambda: "string",
        "table": lambda: "table",
        "number": lambda: "finite number",
        "positive": lambda: "number > 0",
        "positive int": lambda: "integer > 0",
        "range": lambda: f"number in [{args[0]:g}, {args[1]:g}]",
        "int range": lambda: f"integer in [{args[0]:g}, {args[1]:g}]",
        "choice": lambda: ", ".join(_code(a) for a in args[0]),
        "vector": lambda: "[x, y], two numbers",
        "rule": lambda: f"[points along x, points across the thickness], integers in [1, {MAX_GAUSS}]",
        "times": lambda: "rising list of times within [0, t_end]",
        "limit": lambda: 'number > 0, or `"inf"` (no check)',
    }[kind]()


TABLE_TITLES = {
    "": "The top level",
    "beam": "`[beam]`: the geometry",
    "material": "`[material]`: the law and its constants",
    "ancf": "`[ancf]`: the ANCF discretisation (read by `ancf` only)",
    "supports": "`[supports]`: the support at x = 0 (the right end is free)",
    "loads": "`[loads]`",
    "analysis": "`[analysis]`",
    "fem": "`[fem]`: the continuum discretisation (read by `python -m reference_fem` only)",
}


def _fem_defaults() -> dict[str, object]:
    """The values ``reference_fem.settings`` resolves for an empty [fem] table (2D) and
    for ``model = "3d"`` (its 3D keys): the parser's defaults, asked of the parser."""
    from contract import paper
    from contract.scene import scene_from_dict
    from reference_fem import settings

    scene = paper.cantilever_scene("yeoh", "plane-strain", "HB2n-12", 16)
    out = {}
    for table, keys in (({}, settings.KEYS), ({"model": "3d"}, settings.KEYS_3D)):
        s = settings.fem_settings(scene_from_dict({**scene, "fem": table}))
        out.update({k: getattr(s, k) for k in keys if hasattr(s, k)})
    return out


def _filler(module, warn: Callable[[str], None]) -> Callable[[str], str]:
    """Fill {NAME} in a text with the value of the module's constant NAME."""
    def value(m: re.Match) -> str:
        v = getattr(module, m.group(1), None)
        if v is None:
            warn(f"scene-keys.toml names {{{m.group(1)}}}, which {module.__name__} does not define")
            return m.group(0)
        if isinstance(v, Mapping):          # a registry: its names
            v = tuple(v)
        if isinstance(v, tuple):
            return ", ".join(_code(x) for x in v)
        if isinstance(v, (int, float)) and not isinstance(v, bool):
            return f"{v:g}"
        return _value(v)
    return lambda text: re.sub(r"\{([A-Z][A-Z_0-9]*)\}", value, text)


def scene_keys(warn: Callable[[str], None]) -> str:
    import contract.scene as scene_module
    from contract.scene import KEYS, REQUIRED
    from mechanics.laws import LAWS
    from reference_fem import settings

    doc = _toml(DOCS / "reference" / "scene-keys.toml")
    code_keys = {f"{k.table}.{k.name}" if k.table else k.name: k for k in KEYS}
    fem_keys = {f"fem.{k}" for k in settings.KEYS}
    documented = set(doc) - {"material.constants", "tables"}
    for missing in sorted((set(code_keys) | fem_keys) - documented):
        warn(f"scene key {missing!r} has no meaning in docs/reference/scene-keys.toml")
    for extra in sorted(documented - set(code_keys) - fem_keys):
        warn(f"docs/reference/scene-keys.toml documents {extra!r}, which no parser reads")

    out = ["<!-- generated from contract.scene.KEYS, reference_fem.settings and "
           "docs/reference/scene-keys.toml; do not edit -->\n"]
    for table in TABLE_TITLES:
        rows = []
        fill = _filler(settings if table == "fem" else scene_module, warn)
        if table == "fem":
            defaults = _fem_defaults()
            for name in settings.KEYS:
                d = doc.get(f"fem.{name}", {})
                default = fill(d["default"]) if "default" in d else (
                    _value(defaults[name]) if name in defaults else "unset")
                rows.append([_code(name), fill(d.get("accepts", "")), d.get("unit", ""), default,
                             fill(d.get("meaning", ""))])
        else:
            for k in KEYS:
                if k.table != table:
                    continue
                full = f"{table}.{k.name}" if table else k.name
                d = doc.get(full, {})
                if k.default is REQUIRED:
                    default = "required" + (f" ({k.analysis})" if k.analysis else "")
                elif k.default is None:
                    default = fill(d.get("default", "unset"))
                else:
                    default = _value(k.default)
                if "default" in d and k.default is not None:
                    warn(f"scene-keys.toml gives {full!r} a default, which contract.scene.KEYS holds")
                when = f" ({k.analysis} only)" if k.analysis and k.default is not REQUIRED else ""
                meaning = fill(d.get("meaning", ""))
                if full == "supports.left":   # what each support is, stated once (contract.loads)
                    from contract.loads import SUPPORTS
                    meaning += " " + "; ".join(f"{_code(n)}: {m}" for n, m in SUPPORTS.items())
                rows.append([_code(k.name), accepts_text(k.accepts), k.unit, default + when, meaning])
            if table == "material":
                laws = "; ".join(f"{_code(n)}: {', '.join(_code(c) for c in law.constants)}"
                                 for n, law in LAWS.items())
                d = doc.get("material.constants", {})
                rows.append(["the law's constants", "finite number", "Pa (as the law says)",
                             "required by the law", f"{d.get('meaning', '')} {laws}"])
        out.append(f"## {TABLE_TITLES[table]}\n")
        if table in doc.get("tables", {}):
            out.append(doc["tables"][table] + "\n")
        out.append(_table(["key", "accepts", "unit", "default", "meaning"], rows))
    return "\n".join(out)


# -- the record keys ---------------------------------------------------------------------

RECORD_GROUPS = {
    "every": "Every record, both solvers",
    "both": "Added by either solver when there is something to say",
    "ancf": "Added by `ancf`",
    "continuum": "Added by `python -m reference_fem`",
    "dynamic": "Added by a dynamic run, both solvers",
    "study": "Added by the study runner (`python -m studies`) to the records in `reports/data`",
}
def record_solvers() -> dict[str, str]:
    """{a record's solver label: the solver}: ``ancf``, and every continuum backend's name
    (its records are labelled with the backend that ran, :data:`reference_fem.backends.BACKENDS`)."""
    from reference_fem.backends import BACKENDS

    return {"ancf": "ancf", **{name: "continuum" for name in BACKENDS}}


def observed_record_keys() -> dict[str, set[str]]:
    """{solver: top-level keys} of the committed records of the two solvers."""
    seen: dict[str, set[str]] = {}
    solvers = record_solvers()
    for f in sorted((REPORTS / "data").glob("*.jsonl")):
        for line in f.read_text(encoding="utf-8").splitlines():
            try:
                rec = json.loads(line)
            except ValueError:
                continue
            if isinstance(rec, dict) and rec.get("solver") in solvers:
                seen.setdefault(rec["solver"], set()).update(rec)
    return seen


def record_keys(warn: Callable[[str], None]) -> str:
    from contract import record

    doc = _toml(DOCS / "reference" / "record-keys.toml")
    every = set(record.new_record("ancf", {}))
    for k in sorted(every - set(doc)):
        warn(f"record key {k!r} (contract.record) has no meaning in docs/reference/record-keys.toml")
    for k, d in doc.items():
        if d.get("by") not in RECORD_GROUPS:
            warn(f"record-keys.toml: {k!r} has by = {d.get('by')!r}; one of {', '.join(RECORD_GROUPS)}")
        if (k in every) != (d.get("by") == "every"):
            warn(f"record-keys.toml: {k!r} is {'' if k in every else 'not '}a key of every record "
                 f"(contract.record.new_record), but by = {d.get('by')!r}")
    seen = observed_record_keys()
    for solver, keys in sorted(seen.items()):
        for k in sorted(keys - set(doc)):
            warn(f"record key {k!r} (in committed {solver} records) has no meaning in "
                 "docs/reference/record-keys.toml")
    out = ["<!-- generated from contract.record, the records in reports/data and "
           "docs/reference/record-keys.toml; do not edit -->\n",
           f"Schema `{record.SCHEMA}`. Every key below is documented; the build checks that "
           "every key of `contract.record` and every key the committed records of "
           + " and ".join(f"`{s}`" for s in sorted(seen)) + " in `reports/data` hold is here.\n"]
    for group, title in RECORD_GROUPS.items():
        rows = [[_code(k), d.get("meaning", "")] for k, d in doc.items() if d.get("by") == group]
        out.append(f"## {title}\n")
        out.append(_table(["key", "meaning"], rows))
    return "\n".join(out)


# -- the make targets --------------------------------------------------------------------

ASSIGNMENT = re.compile(r"^[A-Za-z_][A-Za-z_0-9]*\s*(\?|:|\+)?=")
TARGET = re.compile(r"^([a-z][a-z0-9-]*):(?!=)\s*(.*)$")


def make_targets(warn: Callable[[str], None]) -> str:
    """Every .PHONY target with the comment block above it (variable lines between the
    comment and the target are skipped)."""
    lines = (ROOT / "Makefile").read_text(encoding="utf-8").splitlines()
    phony = next(l.split(":", 1)[1].split() for l in lines if l.startswith(".PHONY:"))
    rows = []
    for i, line in enumerate(lines):
        m = TARGET.match(line)
        if not m or m.group(1) not in phony:
            continue
        comment, j = [], i - 1
        while j >= 0 and (ASSIGNMENT.match(lines[j]) or lines[j].startswith("#")):
            if lines[j].startswith("#"):
                comment.insert(0, lines[j].lstrip("#").strip())
            j -= 1
        if not comment:
            warn(f"Makefile: target {m.group(1)!r} has no comment above it")
        needs = " ".join(_code(n) for n in m.group(2).split())
        rows.append([_code(f"make {m.group(1)}"), " ".join(comment), needs or "-"])
    missing = sorted(set(phony) - {r[0].strip("`")[5:] for r in rows})
    for t in missing:
        warn(f"Makefile: .PHONY names {t!r}, which has no rule")
    return ("<!-- generated from the Makefile's comments; do not edit -->\n\n"
            + _table(["target", "what it does", "runs first"], rows))


# -- the registries ----------------------------------------------------------------------

def _rules(spec) -> str:
    if not spec.quadrature:
        return "the rule exact for its basis"
    parts = []
    for penalised in (False, True):
        entries = [(lo, rule) for p, lo, rule in spec.quadrature if p == penalised]
        text = ", ".join(f"[{r[0]}, {r[1]}]" + (f" for l_e/h ≥ {lo:g}" if lo > 0 else
                                                 " below" if len(entries) > 1 else " at every l_e/h")
                         for lo, rule in entries for r in [rule])
        parts.append(("penalised: " if penalised else "plane stress: ") + text)
    return "; ".join(parts)


def _refuses(e, refused: dict) -> str:
    """What a scene may not ask of the element: its refused integrators and, for a
    kinematics that runs only some, the formulations it takes."""
    parts = [f"{_code(i)}: {why}" for i, why in sorted(refused.items())]
    if e.family.formulations is not None:
        parts.append(f"formulations other than {', '.join(_code(f) for f in e.family.formulations)}")
    return "; ".join(parts) or "-"


def registries(warn: Callable[[str], None]) -> str:
    from ancf.admission import refused_integrators
    from ancf.elements import ELEMENTS
    from ancf.core.formulations import FORMULATIONS
    from ancf.solvers.integrators import INTEGRATORS
    from contract.scene import FORMULATIONS as PENALISED
    from mechanics.laws import LAWS

    out = ["<!-- generated from ancf.elements.ELEMENTS, mechanics.laws.LAWS, ancf.core.formulations"
           ".FORMULATIONS and ancf.solvers.integrators.INTEGRATORS; do not edit -->\n", "## Elements\n"]
    rows = []
    for name, e in ELEMENTS.items():
        dof = 2 * len(e.nodes) * len(e.kinds)
        rows.append([_code(name), ", ".join(f"{x:g}" for x in e.nodes), ", ".join(e.kinds), dof,
                     ", ".join(e.pressure) or "-", ", ".join(f"C_{c}" for c in e.assumed) or "-",
                     _rules(e), _refuses(e, refused_integrators(e)), e.reference])
    out.append(_table(["element", "nodes (x / l_e)", "nodal coordinates per node", "dof",
                       "pressure basis", "assumed strain", "default elastic rule",
                       "refuses (ancf.admission)", "reference"], rows))
    out.append("\n## Laws\n")
    rows = []
    for name, law in LAWS.items():
        example = ", ".join(f"{k} = {v:g}" for k, v in law.example.items()) or "-"
        mu = f"{law.shear_modulus(law.example):.6g}" if law.example else "-"
        rows.append([_code(name), ", ".join(_code(c) for c in law.constants), law.doc, example, mu])
    out.append(_table(["law", "constants", "energy psi(I1, I2)", "example constants (Pa)",
                       "mu of the example (Pa)"], rows))
    out.append("\n## Formulations\n")
    rows = [[_code(n), f.doc, "yes" if PENALISED.get(n) else "no", "yes" if f.stress_free else "no"]
            for n, f in FORMULATIONS.items()]
    out.append(_table(["formulation", "what it is", "carries `material.penalty`", "stress-free at rest"],
                      rows))
    out.append("\n## Integrators\n")
    rows = [[_code(n), " ".join((cls.__doc__ or "").split("\n\n")[0].split())]
            for n, cls in INTEGRATORS.items()]
    out.append(_table(["integrator", "what it is"], rows))
    return "\n".join(out)


# -- the API pages -----------------------------------------------------------------------

def api(package: str) -> str:
    mod = importlib.import_module(package)
    names = [package] + sorted(i.name for i in pkgutil.walk_packages(mod.__path__, package + ".")
                               if not i.name.endswith("__main__"))
    out = [f"<!-- generated: one automodule per module of {package}; do not edit -->\n"]
    for name in names:
        out.append(f"## `{name}`\n\n```{{eval-rst}}\n.. automodule:: {name}\n```\n")
    return "\n".join(out)


# -- the results -------------------------------------------------------------------------

IMAGE = re.compile(r"^!\[([^\]]*)\]\(([^)\s]+\.png)\)\s*$")
LINK = re.compile(r"(?<!!)\[([^\]]*)\]\(([^)\s]+)\)")
TABLE_CAPTION = re.compile(r"\(\[([A-Za-z0-9_.-]+\.md)\]\(\1\)")


def _relpath(target: Path, page: Path) -> str:
    return os.path.relpath(target, page.parent).replace(os.sep, "/")


def _figure_text(figures: dict, rel: str) -> dict:
    for pattern, text in figures.items():
        if fnmatch.fnmatch(rel, pattern):
            return text
    return {}


def _paragraphs(lines: list[str], start: int) -> tuple[str | None, int]:
    """The plain paragraph starting at ``start`` (after blank lines), and the index
    after it; None when the next block is a heading, table, list, image or code."""
    i = start
    while i < len(lines) and not lines[i].strip():
        i += 1
    if i >= len(lines) or re.match(r"\s*(#|\||- |\* |!\[|```|<)", lines[i]):
        return None, start
    j = i
    while j < len(lines) and lines[j].strip():
        j += 1
    return " ".join(l.strip() for l in lines[i:j]), j


def render_report(src: Path, page: Path, figures: dict, captions: dict[str, str],
                  warn: Callable[[str], None]) -> str:
    """One report as a page: figures captioned, links to CSV files and figures pointing
    into reports/, a title for a file that has none."""
    rel = src.relative_to(REPORTS).as_posix()
    lines = _headings(src.read_text(encoding="utf-8").splitlines())
    out = []
    if not any(l.startswith("# ") for l in lines):
        out += [f"# `{src.stem}`", ""]
        if rel in captions:
            out += [captions[rel], ""]
    i = 0
    while i < len(lines):
        line = lines[i]
        m = IMAGE.match(line)
        if m:
            image = (src.parent / m.group(2)).resolve()
            key = image.relative_to(REPORTS).as_posix()
            if not image.is_file():
                warn(f"{rel}: figure {m.group(2)} not found")
            text = _figure_text(figures, key)
            caption, after = _paragraphs(lines, i + 1)
            if caption is None:
                caption = text.get("caption", "").format(stem=image.stem, element=image.stem.rsplit("-", 1)[0])
                after = i + 1
            if not caption:      # warned, and a figure with a body (docutils fails on an empty one)
                warn(f"{rel}: figure {key} has neither a caption paragraph under it nor one in "
                     "docs/results/figures.toml")
                caption = f"(no caption: {key})"
            legend = text.get("legend", "")
            if not legend:
                warn(f"{rel}: figure {key} has no legend in docs/results/figures.toml")
            legend = legend.format(stem=image.stem, element=image.stem.rsplit("-", 1)[0])
            out += [f"```{{figure}} {_relpath(image, page)}", f":alt: {m.group(1) or image.stem}", "",
                    _links(caption, src, page, warn), "", legend, "```"]
            i = after
            continue
        out.append(_links(line, src, page, warn))
        i += 1
    text = "\n".join(out) + "\n"
    if rel == "README.md":
        text = text.replace("# Results\n", "# The studies, one by one\n", 1)
    return text


ISSUES = ((re.compile(r"\s*\([Ii]ssues? \d+(, \d+)*\)"), ""), (re.compile(r"\(([Ii]ssues? \d+(, \d+)*); "), "("),
          (re.compile(r"\b[Ii]ssue \d+'s\s+"), "the "))


def no_issue_numbers(text: str) -> str:
    """The text without references to the project's issue tracker ("(issue 20)",
    "(issue 20; ...", "issue 20's"): a report's or a docstring's history, not the reader's."""
    for pattern, by in ISSUES:
        text = pattern.sub(by, text)
    return text


def _headings(lines: list[str]) -> list[str]:
    """Heading levels that rise one at a time (a report may jump from # to ###), and no
    issue numbers of the project's tracker in the text (a report's history is not the
    reader's)."""
    out, level, fence = [], 0, False
    for line in lines:
        if line.startswith("```"):
            fence = not fence
        m = re.match(r"(#+) ", line)
        if m and not fence:
            want = min(len(m.group(1)), level + 1)
            line, level = "#" * want + line[len(m.group(1)):], want
        out.append(no_issue_numbers(line) if not fence else line)
    return out


def _links(line: str, src: Path, page: Path, warn: Callable[[str], None]) -> str:
    def fix(m: re.Match) -> str:
        label, target = m.group(1), m.group(2)
        if re.match(r"[a-z]+://", target) or target.startswith("#"):
            return m.group(0)
        path = (src.parent / target).resolve()
        if target.endswith(".md"):          # another report: its page, mirrored beside this one
            if not path.is_file():
                warn(f"{src.relative_to(REPORTS)}: link to {target}, which does not exist")
            return m.group(0)
        if not path.is_file():
            warn(f"{src.relative_to(REPORTS)}: link to {target}, which does not exist")
            return m.group(0)
        return f"[{label}]({_relpath(path, page)})"   # a file: MyST makes it a download link
    return LINK.sub(fix, line)


def table_captions() -> dict[str, str]:
    """{report file: the sentence of reports/README.md that describes it}."""
    captions = {}
    for para in (REPORTS / "README.md").read_text(encoding="utf-8").split("\n\n"):
        m = TABLE_CAPTION.search(para)
        if m and not para.startswith("|"):
            captions[m.group(1)] = para[:m.start()].strip()
    return captions


def results(warn: Callable[[str], None], out: Path = RESULTS) -> dict[str, list[str]]:
    """Every report rendered into ``out`` (docs/results/generated/); returns the pages by
    kind."""
    figures = _toml(DOCS / "results" / "figures.toml")
    captions = table_captions()
    kinds: dict[str, list[str]] = {"summary": [], "peers": [], "reports": [], "tables": [], "cards": []}
    written = set()
    for src in (sorted(REPORTS.glob("*.md")) + sorted((REPORTS / "cards").glob("*.md"))
                + sorted((REPORTS / "external").glob("*.md")) + sorted((REPORTS / "external" / "cards").glob("*.md"))):
        rel = src.relative_to(REPORTS)
        page = out / rel
        _write(page, render_report(src, page, figures, captions, warn))
        written.add(page)
        stem = rel.with_suffix("").as_posix()
        text = src.read_text(encoding="utf-8")
        kind = ("summary" if stem == "README" else "cards" if stem.startswith("cards/")
                else "peers" if stem.startswith(("peers", "external/")) else
                "reports" if any(l.startswith("# ") for l in text.splitlines()) else "tables")
        first = next((l for l in text.splitlines() if l.strip()), "")
        if kind == "tables" and rel.as_posix() not in captions and first.startswith("|"):
            warn(f"reports/{rel}: no sentence of reports/README.md describes it (its page has no caption)")
        kinds[kind].append(stem)
    for kind, title, intro in (
            ("cards", "Element report cards",
             "Every check the harness knows, run on one element (`python -m studies card NAME`)."),
            ("reports", "Further reports",
             "Reports with a page of their own: the continuum reference's refinement, the penalty "
             "range, the kernels' times, the hard cases as one page each, the loops a user waits on."),
            ("tables", "Every table",
             "Each table of the results page as a page of its own, with its CSV file.")):
        pages = [p.split("/", 1)[1] if kind == "cards" else p for p in kinds[kind]]
        index = out / f"{kind}.md"
        body = [f"# {title}", "", intro, "", "```{toctree}", ":maxdepth: 1", ""]
        body += [f"cards/{p}" if kind == "cards" else p for p in pages] + ["```", ""]
        _write(index, "\n".join(body))
        written.add(index)
    for stale in out.rglob("*.md"):
        if stale not in written:
            stale.unlink()
    return kinds


# -- entry points ------------------------------------------------------------------------

def generate(warn: Callable[[str], None], generated: Path = GENERATED, results_out: Path = RESULTS) -> None:
    """Every generated page: the reference's into ``generated``, the results into
    ``results_out``; each missing text is one call of ``warn``."""
    _write(generated / "scene-keys.md", scene_keys(warn))
    _write(generated / "record-keys.md", record_keys(warn))
    _write(generated / "make-targets.md", make_targets(warn))
    _write(generated / "registries.md", registries(warn))
    for package in API_PACKAGES:
        _write(generated / f"api-{package}.md", api(package))
    results(warn, results_out)


def _builder_inited(app) -> None:
    from sphinx.util import logging

    log = logging.getLogger("harness_docs")
    generate(lambda message: log.warning(message, type="harness_docs"))


LITERAL = re.compile(r"(``.+?``|:[a-z:]+:`[^`]+`|`[^`]+`)")


def plain_docstring(app, what, name, obj, options, lines: list[str]) -> None:
    """The code's docstrings are plain text with reST's literals and roles: their math
    (|u|, a * b) is not markup, so | and * outside literals and roles are escaped; and no
    issue numbers (:func:`no_issue_numbers`)."""
    for i, line in enumerate(lines):
        parts = LITERAL.split(no_issue_numbers(line))
        lines[i] = "".join(p if k % 2 else p.replace("\\", "\\\\").replace("|", "\\|").replace("*", "\\*")
                           for k, p in enumerate(parts))


def setup(app):
    app.connect("builder-inited", _builder_inited)
    app.connect("autodoc-process-docstring", plain_docstring)
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}
