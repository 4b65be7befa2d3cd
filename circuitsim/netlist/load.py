"""Load a YAML netlist into a typed, immutable ``Netlist``, with file:line on everything.

Pipeline stage 1. Values are parsed by the restricted expression parser (``expr``), never
evaluated as code. Units are checked against each parameter's declared unit. Includes are
merged before anything else; every element keeps the file and line it came from.
"""

from __future__ import annotations

import difflib
import hashlib
import json
import math
import re
import stat
from collections.abc import Mapping
from dataclasses import dataclass, field
from functools import lru_cache
from pathlib import Path
from typing import Any

from circuitsim.component import (
    COMPONENTS,
    DOMAINS,
    WAVEFORMS,
    Component,
    Expression,
    Option,
    Param,
    RecordList,
    Signal,
    TableData,
)
from circuitsim.errors import NetlistError, ParameterError, SourceLoc
from circuitsim.files import atomic_write
from circuitsim.netlist import expr as ex
from circuitsim.netlist.lines import copy_nodes
from circuitsim.netlist.lines import yaml_line as _loc
from circuitsim.netlist.pwlfile import pwl_points
from circuitsim.netlist.subckt import flatten, read_subckts
from circuitsim.units import (
    Dim,
    absolute_temperature,
    compatible,
    describe,
    explain_mismatch,
    spice_value,
    unit_info,
    unit_name,
)

SCHEMA_PATH = Path(__file__).with_name("schema.json")


@dataclass(frozen=True)
class Value:
    """One numeric value: its expression tree, where it was written, its unit rule."""

    node: ex.Node
    loc: SourceLoc
    param: Param
    unit: str
    explicit: bool = True  # written in the netlist (False: the parameter's default)

    def si(self, env: Mapping[str, float]) -> float:
        return ex.evaluate(self.node, env)


@dataclass(frozen=True)
class GlobalParam:
    name: str
    node: ex.Node
    loc: SourceLoc
    dim: Dim | None
    value: float


@dataclass(frozen=True)
class ComponentSpec:
    """A component as written: type, port bindings, values (by runtime symbol name)."""

    name: str
    type: str
    cls: type[Component]
    ports: tuple[tuple[str, str], ...]
    values: Mapping[str, Value]
    structure: Mapping[str, Any]
    loc: SourceLoc
    tables: tuple[TableData, ...] = ()


@dataclass(frozen=True)
class Probe:
    name: str
    node: ex.Node
    text: str
    loc: SourceLoc


@dataclass(frozen=True)
class Analysis:
    stop: float = 0.1
    step: float | None = None
    rtol: float = 1e-6
    atol: float = 1e-9
    max_step: float = 0.0
    init: str = "rest"
    window: float = 0.2


@dataclass(frozen=True)
class Netlist:
    """A parsed netlist: pure data."""

    path: str
    title: str
    parameters: Mapping[str, GlobalParam]
    components: tuple[ComponentSpec, ...]
    probes: Mapping[str, Probe]
    analysis: Analysis
    nodes: Mapping[str, tuple[str, SourceLoc]] = field(default_factory=dict)
    raw: Any = field(default=None, repr=False, compare=False)
    inputs: tuple[str, ...] = ()  # every file read: the netlist, its includes, its tables

    def component(self, name: str) -> ComponentSpec:
        for c in self.components:
            if c.name == name:
                return c
        raise KeyError(name)

    def global_values(self, overrides: Mapping[str, float] | None = None) -> dict[str, float]:
        """SI values of the named parameters, re-evaluated with ``overrides`` applied."""
        env: dict[str, float] = {}
        overrides = dict(overrides or {})
        for name, gp in self.parameters.items():  # insertion order is dependency order
            env[name] = float(overrides.pop(name)) if name in overrides else \
                ex.evaluate(gp.node, env)
        return env

    def topology_key(self) -> str:
        """Hash of everything that changes the equations (not the numbers)."""
        desc = [(c.name, c.type, c.ports, sorted(c.values), sorted(
            (k, repr(v)) for k, v in c.structure.items())) for c in self.components]
        desc.append(sorted((p.name, p.text) for p in self.probes.values()))
        return hashlib.sha256(json.dumps(desc, default=str).encode()).hexdigest()[:24]


def _near(name: str, options) -> str:
    close = difflib.get_close_matches(name, list(options), n=3, cutoff=0.6)
    return f" (did you mean {', '.join(repr(c) for c in close)}?)" if close else ""


@lru_cache(maxsize=1)
def _schema_validator():
    import jsonschema

    return jsonschema.Draft202012Validator(json.loads(SCHEMA_PATH.read_text()))


def _schema_key(plain: Any) -> str | None:
    """A digest naming a document exactly as the schema sees it (its JSON text), or None for
    one JSON cannot write (a YAML date): that one is validated every time."""
    try:
        text = json.dumps(plain, sort_keys=True, allow_nan=False)
    except (TypeError, ValueError):
        return None
    return hashlib.sha256(text.encode("utf-8")).hexdigest()


@lru_cache(maxsize=1)
def _schema_memo():
    """Documents that passed the schema in earlier runs, named by the schema and by the
    installed jsonschema (an edit or an upgrade starts a new table)."""
    import importlib.util
    import os

    from circuitsim.memo import Memo

    h = hashlib.sha256(SCHEMA_PATH.read_bytes())
    spec = importlib.util.find_spec("jsonschema")
    if spec is not None and spec.origin:
        st = os.stat(spec.origin)
        h.update(f"{spec.origin}|{st.st_size}|{st.st_mtime_ns}".encode())
    return Memo("schema", h.hexdigest()[:16])


def _plain(obj: Any) -> Any:
    if isinstance(obj, Mapping):
        return {str(k): _plain(v) for k, v in obj.items()}
    if isinstance(obj, list):
        return [_plain(v) for v in obj]
    if isinstance(obj, float) and not math.isfinite(obj):
        return str(obj)
    return obj


_MAX_VALUES = 1_000_000


def _expanded_size(obj: Any, memo: dict[int, int]) -> int:
    """Number of values ``obj`` holds once aliases are expanded (linear time, shared memo)."""
    if not isinstance(obj, (Mapping, list)):
        return 1
    key = id(obj)
    if key not in memo:
        memo[key] = 0  # a recursive alias (ruamel makes it None anyway) counts once
        items = [*obj.keys(), *obj.values()] if isinstance(obj, Mapping) else obj
        total = 1
        for v in items:
            total += _expanded_size(v, memo)
            if total > _MAX_VALUES:
                break
        memo[key] = total
    return memo[key]


_MAX_DEPTH = 100  # nesting of lists and mappings; a netlist needs a handful
_ALIAS = re.compile(r"(?:^|[\s\[{,:])\*[^\s,\]}]+", re.MULTILINE)
_LONG_INT = re.compile(r"\d{4000,}")


def _line_at(text: str, pos: int) -> int:
    return text.count("\n", 0, pos) + 1


def _read_text(path: Path) -> str:
    try:
        data = path.read_bytes()
    except OSError as exc:
        raise NetlistError(f"cannot read netlist: {exc.strerror}. Check the path.",
                           SourceLoc(str(path))) from None
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as exc:
        line = data.count(b"\n", 0, exc.start) + 1
        raise NetlistError("the file is not UTF-8 text (a byte here is not valid UTF-8); save "
                           "it as UTF-8", SourceLoc(str(path), line)) from None


def _too_deep(text: str) -> int:
    """Line where lists/mappings nest deeper than _MAX_DEPTH (0: nowhere). Checked before the
    parser, which would recurse (slowly) into a RecursionError."""
    import numpy as np

    codes = np.frombuffer(text.encode("utf-8"), np.uint8)
    step = np.isin(codes, (ord("["), ord("{"))).astype(np.int32) - \
        np.isin(codes, (ord("]"), ord("}"))).astype(np.int32)
    depth = np.cumsum(step)
    if depth.size and depth.max() > _MAX_DEPTH:
        pos = int(np.argmax(depth > _MAX_DEPTH))
        return text.encode("utf-8")[:pos].count(b"\n") + 1
    deep = re.search(rf"^ {{{2 * _MAX_DEPTH},}}\S", text, re.MULTILINE)
    return _line_at(text, deep.start()) if deep else 0


def _read_yaml(path: Path) -> Any:
    text = _read_text(path)
    deep = _too_deep(text)
    if deep:
        raise NetlistError(f"lists or mappings are nested too deeply (more than {_MAX_DEPTH} "
                           f"levels; a netlist needs a few)", SourceLoc(str(path), deep))
    doc = _parse_yaml(path, text)
    if _expanded_size(doc, {}) > _MAX_VALUES:
        alias = _ALIAS.search(text)
        raise NetlistError(f"the YAML expands to more than {_MAX_VALUES} values (anchors and "
                           f"aliases repeat their content); write the netlist out plainly",
                           SourceLoc(str(path), _line_at(text, alias.start()) if alias else 1))
    if not isinstance(doc, Mapping):
        raise NetlistError("a netlist is a YAML mapping with 'components:' (and optionally "
                           "'parameters:', 'probes:', 'analysis:', 'include:')",
                           SourceLoc(str(path), 1))
    _check_schema(path, doc)
    return doc


def _parse_yaml(path: Path, text: str) -> Any:
    from ruamel.yaml import YAML
    from ruamel.yaml.error import MarkedYAMLError, YAMLError

    # ruamel's round-trip parser builds only mappings, sequences and scalars (no Python
    # objects from tags), and keeps the line of every node for the error messages
    parser = YAML(typ="rt")
    try:
        return parser.load(text)
    except MarkedYAMLError as exc:
        mark = exc.problem_mark or exc.context_mark
        what = (exc.problem or exc.context or "syntax error").strip()
        ctx = exc.context_mark
        if exc.problem and exc.context and ctx is not None and ctx is not mark:
            if "end of stream" in exc.problem:  # e.g. an unclosed quote: where it started
                mark = ctx
            what = f"{what} ({exc.context.strip()} from line {ctx.line + 1})"
        line = mark.line + 1 if mark is not None else 0
        raise NetlistError(f"YAML syntax error: {what}. Check indentation, colons and quotes.",
                           SourceLoc(str(path), line)) from None
    except RecursionError:
        raise NetlistError("YAML error: lists or mappings are nested too deeply",
                           SourceLoc(str(path))) from None
    except ValueError as exc:
        if "digits" in str(exc):  # Python's guard against huge integer strings
            long = _LONG_INT.search(text)
            raise NetlistError("a number has thousands of digits; write it with an exponent "
                               "(1e400) or as a plain size", SourceLoc(
                                   str(path), _line_at(text, long.start()) if long else 0)) \
                from None
        raise NetlistError(f"YAML error: {type(exc).__name__}: {exc}. Check the values and "
                           f"'!!' tags", SourceLoc(str(path))) from None
    except (YAMLError, LookupError, TypeError) as exc:
        # ruamel's scalar constructors fail with bare IndexError/KeyError on e.g. '!!float'
        # with no value or '!!bool x'
        raise NetlistError(f"YAML error: {type(exc).__name__}: {exc}. Check the values and "
                           f"'!!' tags", SourceLoc(str(path))) from None


def _check_schema(path: Path, doc: Any) -> None:
    plain = _plain(doc)
    key = _schema_key(plain)
    if key is not None and _schema_memo().get(key):
        return  # this very document passed before: no jsonschema import (0.1 s)
    errors = sorted(_schema_validator().iter_errors(plain), key=lambda e: list(e.path))
    if not errors:
        if key is not None:
            _schema_memo().put(key, True)
        return
    err = errors[0]
    node, loc = doc, _loc(str(path), doc)
    for part in err.path:
        try:
            loc = _loc(str(path), node, key=part) if isinstance(node, Mapping) else \
                _loc(str(path), node, index=part)
            node = node[part]
        except (KeyError, IndexError, TypeError):
            break
    where = "/".join(str(p) for p in err.path) or "top level"
    raise NetlistError(f"does not match the netlist schema at {where}: {_schema_message(err)}. "
                       f"See circuitsim/netlist/schema.json.", loc)


def _schema_message(err) -> str:
    """The schema's complaint without the offending value: the file may not be a netlist at
    all (an include of a private file), and its content must not be echoed."""
    kind = err.validator
    if kind == "type":
        want = err.validator_value
        want = " or ".join(want) if isinstance(want, list) else want
        return f"expected {want}, got {type(err.instance).__name__}"
    if kind == "additionalProperties":
        return err.message  # names the unexpected key, which the user needs to see
    if kind == "required":
        return err.message
    if kind == "pattern":
        return f"does not match the pattern {err.validator_value}"
    if kind == "enum":
        return f"must be one of {err.validator_value}"
    return f"fails the '{kind}' rule"


@dataclass
class RawNetlist:
    """Merged raw sections of a file and its includes, with locations: what the YAML said,
    before typing. Patches (the diagnosis's effects) edit a copy and build it again; ``dump``
    writes it back as one self-contained netlist."""

    params: dict[str, tuple[Any, SourceLoc]] = field(default_factory=dict)
    comps: list[tuple[Mapping, SourceLoc, str]] = field(default_factory=list)
    probes: dict[str, tuple[Any, SourceLoc]] = field(default_factory=dict)
    analysis: dict[str, tuple[Any, SourceLoc]] = field(default_factory=dict)
    title: str = ""
    path: str = ""
    files: list[str] = field(default_factory=list)  # the netlist and its includes
    root: str | None = None  # the folder tree includes and tables must lie in (None: any)
    subckts: dict[str, Any] = field(default_factory=dict)  # subckt.Subckt by name
    # components a diagnosis patch added (a friction, a sensor's filter): the catalog does
    # not propose effects on them
    patch_parts: set[str] = field(default_factory=set)

    def copy(self) -> RawNetlist:
        """A deep copy that keeps the lines of every entry (``lines.copy_nodes``)."""
        return copy_nodes(self)

    def component_entry(self, name: str) -> dict:
        for entry, _, _ in self.comps:
            if str(entry["name"]) == name:
                return entry  # type: ignore[return-value]
        raise KeyError(name)

    def dump(self, path: str | Path, header: str = "") -> None:
        """Write a self-contained netlist (includes merged; table files re-pointed), atomically."""
        import io
        import os

        from ruamel.yaml import YAML

        out_dir = Path(path).resolve().parent

        def plain(v: Any) -> Any:
            if isinstance(v, Mapping):
                return {str(k): plain(x) for k, x in v.items()}
            if isinstance(v, list):
                return [plain(x) for x in v]
            return v

        comps = []
        for entry, _, file in self.comps:
            e = plain(entry)
            for v in e.values():
                if isinstance(v, dict) and isinstance(v.get("table"), dict) and \
                        "file" in v["table"]:
                    src = (Path(file).parent / v["table"]["file"]).resolve()
                    v["table"]["file"] = os.path.relpath(src, out_dir)
            comps.append(e)
        doc: dict[str, Any] = {"title": self.title}
        if self.params:
            doc["parameters"] = {k: plain(v) for k, (v, _) in self.params.items()}
        doc["components"] = comps
        if self.probes:
            doc["probes"] = {k: plain(v) for k, (v, _) in self.probes.items()}
        if self.analysis:
            doc["analysis"] = {k: plain(v) for k, (v, _) in self.analysis.items()}
        yaml = YAML(typ="rt")
        yaml.default_flow_style = False
        yaml.width = 100
        buf = io.StringIO()
        yaml.dump(doc, buf)
        text = "".join(f"# {ln}\n" if ln else "#\n" for ln in header.splitlines()) + \
            buf.getvalue()
        atomic_write(path, text)


_Raw = RawNetlist


# Limits on what a netlist makes circuitsim read: a netlist received from someone else must not
# exhaust memory (an include of /dev/zero, a fan-out of includes) or read files elsewhere.
MAX_NETLIST_BYTES = 10 * 2**20
MAX_TABLE_BYTES = 256 * 2**20
MAX_INCLUDES = 200
OUTSIDE_HINT = ("a netlist may read only files in its own folder tree (or in the repository "
                "holding it); if you trust it, pass --allow-outside (CLI) or "
                "allow_outside=True (load)")


def trust_root(folder: Path) -> Path:
    """The folder tree a netlist in ``folder`` may read: the repository (a folder with ``.git``
    or ``pyproject.toml``) holding it, else its own folder. A netlist received by mail sits in
    no repository and may read only beside and below itself; the examples of a project may read
    the project's data."""
    for d in (folder, *folder.parents):
        if (d / ".git").exists() or (d / "pyproject.toml").exists():
            return d
    return folder


def check_input_file(target: Path, root: str | None, what: str, loc: SourceLoc,
                     limit: int, comp: str | None = None) -> Path:
    """The resolved path of a file a netlist reads, after checking that it lies in ``root``
    (None: anywhere), exists, is a regular file (not a folder, device or pipe) and is at
    most ``limit`` bytes. Raises NetlistError at ``loc``; never reads the file."""
    real = target.resolve()
    if root is not None and not real.is_relative_to(root):
        raise NetlistError(f"{what} '{target}' is outside {root}: "
                           f"{OUTSIDE_HINT}", loc, comp)
    try:
        st = real.stat()
    except OSError:
        raise NetlistError(f"{what} '{target}' not found (looked in {target.parent})", loc,
                           comp) from None
    if stat.S_ISDIR(st.st_mode):
        raise NetlistError(f"{what} '{target}' is a folder; name a file", loc, comp)
    if not stat.S_ISREG(st.st_mode):
        raise NetlistError(f"{what} '{target}' is not a regular file (a device or a pipe); "
                           f"name a file", loc, comp)
    if st.st_size > limit:
        raise NetlistError(f"{what} '{target}' is {st.st_size / 2**20:.0f} MB, more than the "
                           f"{limit / 2**20:.0f} MB a netlist may read", loc, comp)
    return real


def _gather(path: Path, raw: _Raw, stack: tuple[Path, ...], loc: SourceLoc | None = None
            ) -> None:
    path = check_input_file(path, None if not stack else raw.root, "included file" if stack
                            else "netlist", loc or SourceLoc(str(path)), MAX_NETLIST_BYTES)
    if path in stack:
        chain = " -> ".join(p.name for p in (*stack, path))
        raise NetlistError(f"include cycle: {chain}; remove one of the includes", loc)
    if len(raw.files) >= MAX_INCLUDES:
        raise NetlistError(f"more than {MAX_INCLUDES} files are included (an include fans "
                           f"out or repeats); include each file once", loc)
    doc = _read_yaml(path)
    sp = str(path)
    raw.files.append(sp)
    includes = doc.get("include", []) or []
    for i, inc in enumerate(includes):
        _gather(path.parent / inc, raw, (*stack, path), _loc(sp, includes, index=i))
    raw.title = str(doc.get("title", raw.title or path.stem))
    raw.subckts.update(read_subckts(doc, sp))
    params = doc.get("parameters") or {}
    for k in params:
        raw.params[str(k)] = (params[k], _loc(sp, params, key=k))  # later files override
    comps = doc.get("components") or []
    for i, c in enumerate(comps):
        raw.comps.append((c, _loc(sp, comps, index=i), sp))
    probes = doc.get("probes") or {}
    for k in probes:
        raw.probes[str(k)] = (probes[k], _loc(sp, probes, key=k))
    analysis = doc.get("analysis") or {}
    for k in analysis:
        raw.analysis[str(k)] = (analysis[k], _loc(sp, analysis, key=k))


def _parse_value(text: Any, loc: SourceLoc, what: str, comp: str | None = None,
                 unit: str | None = None) -> ex.Node:
    """Parse a value; ``unit`` (the expected one, if known) decides a SPICE suffix that is also
    a unit (``1F`` on a capacitor is a farad; see ``units.spice_value``)."""
    if isinstance(text, str):
        text = absolute_temperature(text) or text  # '20 degC' is 293.15 K, not 20 x 274.15
        try:
            target = unit_info(unit)[1] if unit is not None else None
            plain = spice_value(text, target)
        except ValueError as exc:
            raise ParameterError(f"{what}: {exc}", loc, comp) from None
        if plain is not None:
            return ex.Node("num", float(plain))
    if isinstance(text, bool):
        raise ParameterError(f"{what} must be a number or expression, not {text}", loc, comp)
    if isinstance(text, (int, float)):
        try:
            return ex.Node("num", float(text))
        except OverflowError:  # an int beyond float range: infinite, refused as such later
            return ex.Node("num", math.inf if text > 0 else -math.inf)
    try:
        return ex.parse(str(text))
    except ex.ExprError as exc:
        raise NetlistError(f"{what}: {exc}. Values are numbers with optional units "
                           f"('0.87 mH'), parameter names, or arithmetic of those.",
                           loc, comp) from None


def typed_value(text: str, target: Dim | None = None, unit: str | None = None) -> float:
    """A value typed outside a netlist (``--set``, ``--stop``, a sweep axis) in SI: a number,
    a number with a unit (``10 ms``), with a SPICE multiplier (``2k``) or a temperature alone
    in Celsius or Fahrenheit (``20 degC``); a unit is checked against ``target`` (named
    ``unit`` in the message). ValueError saying what is wrong; names are refused."""
    read = absolute_temperature(text) or text  # '20 degC' is 293.15 K
    try:
        plain = spice_value(read, target)
        if plain is not None:
            return float(plain)
        node = ex.parse(read.strip())
        if ex.names(node):
            raise ValueError(f"'{text.strip()}' is not a number (names such as "
                             f"{min(ex.names(node))!r} are not allowed here)")
        value = ex.evaluate(node, {})
        dim = ex.dimension(node, {})
    except (ZeroDivisionError, OverflowError, KeyError) as exc:
        raise ValueError(_why(exc)) from None
    if node.kind == "unit" and target is not None and dim is not None and \
            not compatible(dim, target):
        raise ValueError(explain_mismatch(dim, target, unit or unit_name(target)))
    return value


def _carries_units(node: ex.Node, dims: Mapping[str, Dim | None]) -> bool:
    """True when a unit is written in the expression or comes with a named parameter; pure
    number arithmetic (``2*5``, ``1/1000``) is a bare number, taken in the expected unit."""
    if node.kind == "unit":
        return True
    if node.kind == "name":
        return dims.get(str(node.value)) is not None
    return any(_carries_units(a, dims) for a in node.args)


# Names a netlist may not give a parameter: each already means something in an expression, and
# letting the user's value win in one place and the built-in meaning in another would give a
# silent wrong answer.
RESERVED_PARAMS = {"pi": "the constant 3.14159... in every expression",
                   "t": "the simulated time in behavioural expressions",
                   "time": "the time column of every output table"}
_IDENT = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")
# characters a node name may not hold: they would split or shift a CSV header, or make the
# name impossible to write in a probe
_BAD_NODE_CHARS = re.compile(r"[,\"'\s;=]")


def _check_param_name(name: str, loc: SourceLoc) -> None:
    if name in RESERVED_PARAMS:
        raise ParameterError(f"parameter name '{name}' is reserved: it is "
                             f"{RESERVED_PARAMS[name]}; rename the parameter (e.g. "
                             f"'{name}_')", loc)
    if not _IDENT.fullmatch(name):
        raise ParameterError(f"parameter name '{name}' is not a plain name (letters, digits, "
                             f"'_'; no dots): a dotted name reads as a circuit quantity such as "
                             f"'R1.v'; rename it", loc)


def _order_params(raw: _Raw, scoped: set[str] = frozenset()) -> dict[str, GlobalParam]:
    # a dotted name (a subcircuit instance's parameter, X1.R, as flattened or written back)
    # is safe while its prefix names no component or node: it can then mean nothing else
    taken = {str(e.get("name")) for e, _, _ in raw.comps} | {
        v for e, _, _ in raw.comps for v in e.values() if isinstance(v, str)}
    for k, (_, loc) in raw.params.items():
        prefix, _, leaf = k.rpartition(".")
        plain = k in scoped or (prefix and prefix not in taken and
                                all(_IDENT.fullmatch(part) for part in prefix.split(".")))
        _check_param_name(leaf if plain else k, loc)
    nodes = {k: _parse_value(v, loc, f"parameter '{k}'") for k, (v, loc) in raw.params.items()}
    order: list[str] = []
    state: dict[str, int] = {}

    def visit(name: str, chain: tuple[str, ...]) -> None:
        if state.get(name) == 2:
            return
        if state.get(name) == 1:
            cyc = " -> ".join((*chain[chain.index(name):], name))
            raise ParameterError(f"parameters depend on each other in a cycle: {cyc}",
                                 raw.params[name][1])
        state[name] = 1
        for dep in sorted(ex.names(nodes[name])):
            if dep not in nodes:
                raise ParameterError(f"parameter '{name}' refers to unknown parameter "
                                     f"'{dep}'{_near(dep, nodes)}", raw.params[name][1])
            visit(dep, (*chain, name))
        state[name] = 2
        order.append(name)

    for name in nodes:
        visit(name, ())
    out: dict[str, GlobalParam] = {}
    env: dict[str, float] = {}
    dims: dict[str, Dim | None] = {}
    for name in order:
        loc = raw.params[name][1]
        try:
            val = ex.evaluate(nodes[name], env)
            dim = ex.dimension(nodes[name], dims)
        except (ValueError, ZeroDivisionError, OverflowError) as exc:
            raise ParameterError(f"parameter '{name}': {_why(exc)}", loc) from None
        if not math.isfinite(val):
            raise ParameterError(f"parameter '{name}' evaluates to {val}", loc)
        # An expression over unit-less names stays unknowable; a bare number (also a signed
        # one, or number arithmetic: '-0.91', '1/1000') is a wildcard, and so is a parameter
        # computed from wildcards only ('b: a' with 'a: -0.91')
        if not _carries_units(nodes[name], dims):
            dim = None
        env[name], dims[name] = val, dim
        out[name] = GlobalParam(name, nodes[name], loc, dim, val)
    return out


class _Builder:
    """Turns raw component entries into ComponentSpecs, checking names, units, validity."""

    def __init__(self, params: Mapping[str, GlobalParam], nodes: dict[str, tuple[str,
                 SourceLoc]], root: str | None = None):
        self.params = params
        self.root = root
        self.env = {k: p.value for k, p in params.items()}
        self.dims = {k: p.dim for k, p in params.items()}
        self.nodes = nodes
        self.n_tables = 0
        self.table_files: list[str] = []

    def value(self, raw: Any, loc: SourceLoc, comp: str, key: str, param: Param,
              unit: str, local: Mapping[str, Value] | None = None) -> Value:
        node = _parse_value(raw, loc, f"parameter '{key}'", comp, unit)
        for dep in ex.names(node):
            if dep not in self.params:
                raise ParameterError(f"parameter '{key}' refers to unknown parameter '{dep}'"
                                     f"{_near(dep, self.params)}; {_unknown_fix(dep)}", loc,
                                     comp)
        try:
            val = ex.evaluate(node, self.env)
            dim = ex.dimension(node, self.dims)
        except (ValueError, ZeroDivisionError, OverflowError) as exc:
            raise ParameterError(f"parameter '{key}': {_why(exc)}", loc, comp) from None
        if dim is not None and unit not in ("1",) and _carries_units(node, self.dims):
            _, target = unit_info(unit)
            if not compatible(dim, target):
                raise ParameterError(f"parameter '{key}': {explain_mismatch(dim, target, unit)}",
                                     loc, comp)
        elif dim is not None and unit == "1" and dim.dims and _carries_units(node, self.dims):
            raise ParameterError(f"parameter '{key}' must be dimensionless, got "
                                 f"{describe(dim)}", loc, comp)
        why = param.violation(val)
        if why:
            raise ParameterError(f"{key} = {val:g} [{unit}]: {why} ({param.doc})", loc, comp)
        return Value(node, loc, param, unit)

    def params_of(self, entry: Mapping, decl: Mapping[str, Param], loc_of, comp: str,
                  prefix: str, unit_at: str, out: dict[str, Value], what: str) -> None:
        """Fill ``out`` with the values of the declared scalar parameters in ``entry``."""
        for key in entry:
            if key not in decl:
                raise NetlistError(f"unknown {what} '{key}'{_near(str(key), decl)}; "
                                   f"known: {', '.join(decl) or 'none'}", loc_of(key), comp)
        local: dict[str, float] = {}
        # parameters defaulting to another parameter go last, whatever the declaration order
        for key, p in sorted(decl.items(), key=lambda kv: isinstance(kv[1].default, str)):
            unit = unit_at if p.unit == "@" else p.unit
            name = f"{prefix}{key}"
            if key in entry:
                out[name] = self.value(entry[key], loc_of(key), comp, key, p, unit)
            elif isinstance(p.default, str):
                src = out[f"{prefix}{p.default}"]
                out[name] = Value(src.node, src.loc, p, unit, src.explicit)
            elif p.default is not None:
                out[name] = Value(ex.Node("num", float(p.default)), loc_of(None), p, unit,
                                  explicit=False)
            else:
                raise ParameterError(f"missing parameter '{key}' [{unit}] ({p.doc}); add "
                                     f"'{key}: <value>'", loc_of(None), comp)
            local[key] = out[name].si(self.env)

    def component(self, entry: Mapping, loc: SourceLoc, path: str) -> ComponentSpec:
        name = str(entry["name"])
        typ = str(entry["type"])
        cls = COMPONENTS.get(typ)
        if cls is None:
            raise NetlistError(f"unknown component type '{typ}'{_near(typ, COMPONENTS)}; "
                               f"`circuitsim components` lists them", loc, name)

        def loc_of(key: Any) -> SourceLoc:
            return _loc(path, entry, key=key) if key is not None and key in entry else loc

        ports: list[tuple[str, str]] = []
        for port in cls.ports:
            if port.name not in entry:
                raise NetlistError(f"port '{port.name}' ({port.domain.name}) is not connected; "
                                   f"add '{port.name}: <node>'", loc, name)
            node = str(entry[port.name])
            ports.append((port.name, node))
            self.bind_node(node, port.domain.name, loc_of(port.name), name, port.name)
        decl = cls.declared()
        values: dict[str, Value] = {}
        structure: dict[str, Any] = {}
        tables: list[TableData] = []
        known = {"name", "type", *(p.name for p in cls.ports), *decl}
        for key in entry:
            if key not in known:
                raise NetlistError(f"unknown parameter '{key}' for type '{typ}'"
                                   f"{_near(str(key), known)}; known: "
                                   f"{', '.join(sorted(known - {'name', 'type'}))}",
                                   loc_of(key), name)
        scalars = {k: d for k, d in decl.items() if isinstance(d, Param)}
        self.params_of({k: entry[k] for k in scalars if k in entry}, scalars, loc_of, name,
                       f"{name}.", "1", values, "parameter")
        self.declared_values(entry, decl, loc_of, name, path, values, structure, tables)
        return ComponentSpec(name, typ, cls, tuple(ports), values, structure, loc,
                             tuple(tables))

    def declared_values(self, entry: Mapping, decl: Mapping[str, Any], loc_of, name: str,
                        path: str, values: dict[str, Value], structure: dict[str, Any],
                        tables: list[TableData]) -> None:
        """Options, record lists, signals and expressions of one component entry."""
        for key, d in decl.items():
            if isinstance(d, Option):
                val = entry.get(key, d.default)
                if val not in d.choices:
                    raise ParameterError(f"option '{key}' must be one of {list(d.choices)}, "
                                         f"got {val!r}", loc_of(key), name)
                structure[key] = val
            elif isinstance(d, RecordList):
                items = entry.get(key, []) or []
                if not isinstance(items, list):
                    raise NetlistError(f"'{key}' must be a list of mappings with fields "
                                       f"{', '.join(d.fields)}", loc_of(key), name)
                if len(items) < d.min_rows:
                    raise NetlistError(f"'{key}' needs at least {d.min_rows} row(s) with "
                                       f"fields {', '.join(d.fields)}", loc_of(key), name)
                for i, item in enumerate(items):
                    iloc = _loc(path, items, index=i)
                    if not isinstance(item, Mapping):
                        raise NetlistError(f"{key}[{i}] must be a mapping with fields "
                                           f"{', '.join(d.fields)}", iloc, name)
                    self.params_of(item, d.fields, lambda k, it=item, il=iloc:
                                   _loc(path, it, key=k) if k is not None else il, name,
                                   f"{name}.{key}[{i}].", "1", values, f"field of {key}")
                structure[key] = len(items)
            elif isinstance(d, Signal):
                kind, n = self.signal(entry.get(key, d.default), loc_of(key), name, key, d,
                                      values, tables, path)
                structure[key] = (kind, n)
            elif isinstance(d, Expression):
                structure[key] = self.expression(entry.get(key), loc_of(key), name, key, d,
                                                 values)

    def expression(self, raw: Any, loc: SourceLoc, comp: str, key: str, d: Expression,
                   values: dict[str, Value]) -> str:
        """A behavioural expression: its netlist parameters become run-time values of the
        component; the other names are circuit quantities, resolved when the DAE is built."""
        if raw is None or isinstance(raw, bool):
            raise ParameterError(f"missing expression '{key}' [{d.unit}] ({d.doc}), e.g. "
                                 f"'{key}: Kp*(ref.v - x.x)'", loc, comp)
        text = str(raw)
        try:
            node = ex.parse(text, allow_unit=False)
        except ex.ExprError as exc:
            raise NetlistError(f"expression '{key}': {exc}. Behavioural expressions use "
                               f"numbers in SI, netlist parameters, t and circuit quantities "
                               f"named as in probes", loc, comp) from None
        for pname in sorted(ex.names(node) & set(self.params)):
            values[f"{comp}.{key}.{pname}"] = Value(ex.Node("name", pname), loc,
                                                   Param("1", f"parameter {pname}"), "1")
        return text

    def signal(self, raw: Any, loc: SourceLoc, comp: str, key: str, d: Signal,
               values: dict[str, Value], tables: list[TableData], path: str) -> tuple[str, int]:
        if raw is None:
            raise ParameterError(f"missing parameter '{key}' [{d.unit}] ({d.doc}): a value or a "
                                 f"waveform ({', '.join(sorted(WAVEFORMS))})", loc, comp)
        if not isinstance(raw, Mapping):
            raw = {"dc": {"value": raw}}
        if len(raw) != 1:
            raise NetlistError(f"'{key}' takes one waveform, e.g. {{sine: {{amplitude: 1, "
                               f"freq: 50 Hz}}}}; got {list(raw)}", loc, comp)
        kind = str(next(iter(raw)))
        wcls = WAVEFORMS.get(kind)
        if wcls is None:
            raise NetlistError(f"unknown waveform '{kind}'{_near(kind, WAVEFORMS)}; known: "
                               f"{', '.join(sorted(WAVEFORMS))}", loc, comp)
        body = raw[kind]
        prefix = f"{comp}.{key}."
        if kind == "pwl":
            # from a CSV file: the inline form; the file under the same rule as a table's
            body = pwl_points(body, path, loc, comp, check=lambda f: self._input_file(
                f, "pwl file", loc, comp), unit=d.unit)
            return kind, self.pwl(body, loc, comp, key, d, values, prefix)
        if kind == "table":
            if not isinstance(body, Mapping) or "file" not in body or "column" not in body:
                raise NetlistError("a table waveform needs {file: data.csv, column: NAME} "
                                   "(and optionally time: NAME, scale: NUMBER)", loc, comp)
            tables.append(self.table(body, loc, comp, path, d.unit))
            body = {k: v for k, v in body.items() if k not in ("file", "column", "time")}
        elif not isinstance(body, Mapping):
            if wcls.scalar_key is None:
                raise NetlistError(f"waveform '{kind}' needs a mapping of "
                                   f"{', '.join(wcls.params)}", loc, comp)
            body = {wcls.scalar_key: body}
        self.params_of(body, wcls.params, lambda k: loc, comp, prefix, d.unit, values,
                       f"field of waveform '{kind}'")
        return kind, 0

    def pwl(self, body: Any, loc: SourceLoc, comp: str, key: str, d: Signal,
            values: dict[str, Value], prefix: str) -> int:
        if not isinstance(body, list) or len(body) < 2 or not all(
                isinstance(p, list) and len(p) == 2 for p in body):
            raise NetlistError("pwl takes a list of [time, value] pairs, at least two, e.g. "
                               "[[0, 0], [1 ms, 12 V]]", loc, comp)
        last = -math.inf
        for i, (tv, vv) in enumerate(body):
            tval = self.value(tv, loc, comp, f"pwl time {i}", Param("s", "time",
                              nonnegative=True), "s")
            ts = tval.si(self.env)
            if ts <= last:
                raise ParameterError(f"pwl times must increase (point {i}: {ts:g} s)", loc, comp)
            last = ts
            values[f"{prefix}t{i}"] = tval
            values[f"{prefix}v{i}"] = self.value(vv, loc, comp, f"pwl value {i}",
                                                 Param(d.unit, "value"), d.unit)
        return len(body)

    def table(self, body: Mapping, loc: SourceLoc, comp: str, path: str,
              unit: str | None = None) -> TableData:
        from circuitsim.netlist.tables import read_column

        file = Path(path).parent / str(body["file"])
        self._input_file(file, "table file", loc, comp)
        x, y = read_column(file, str(body["column"]), str(body.get("time", "time")), loc, comp,
                           unit)
        self.n_tables += 1
        return TableData(x, y, f"{file.name}:{body['column']}")

    def _input_file(self, file: Path, what: str, loc: SourceLoc, comp: str) -> None:
        """A data file the netlist reads: inside its tree (unless allowed), a regular file of
        bounded size; remembered as an input (no output may overwrite it)."""
        check_input_file(file, self.root, what, loc, MAX_TABLE_BYTES, comp)
        self.table_files.append(str(file))

    def bind_node(self, node: str, domain: str, loc: SourceLoc, comp: str, port: str) -> None:
        if node in DOMAINS[domain].references:
            # a reference is per domain ('fixed' serves shafts and sliders alike)
            self.nodes.setdefault(node, (domain, loc))
            return
        for d in DOMAINS.values():
            if node in d.references:
                raise NetlistError(f"port '{port}' is {domain} but '{node}' is the {d.name} "
                                   f"reference; use "
                                   f"{' or '.join(DOMAINS[domain].references)}", loc, comp)
        if node in self.nodes and self.nodes[node][0] != domain:
            other, oloc = self.nodes[node]
            raise NetlistError(f"port '{port}' is {domain}, but node '{node}' is {other} "
                               f"(first used at {oloc}): an electrical pin cannot connect to a "
                               f"shaft; use a coupling component such as 'emf'", loc, comp)
        self.nodes.setdefault(node, (domain, loc))


def load(path: str | Path, *, allow_outside: bool = False) -> Netlist:
    """Read, validate and type a netlist file (with its includes).

    Includes and table files must lie in the netlist's folder tree unless ``allow_outside``
    (a netlist from someone else must not read your files). Raises NetlistError /
    ParameterError naming file, line and component.
    """
    import circuitsim_components  # noqa: F401 - fills the registries

    path = Path(path)
    raw = _Raw(path=str(path))
    raw.root = None if allow_outside else str(trust_root(path.resolve().parent))
    _gather(path, raw, ())
    return build(raw)


def build(raw: RawNetlist) -> Netlist:
    """Type a raw netlist (as read, or as patched): the second half of ``load``."""
    import circuitsim_components  # noqa: F401 - fills the registries

    written = set(raw.params)
    raw = flatten(raw)  # subcircuit instances become scoped components
    path = Path(raw.path)
    # an instance's parameters are scoped by the flattening (X1.R): the user wrote the plain
    # name after the dot, and that is what is checked
    params = _order_params(raw, set(raw.params) - written)
    nodes: dict[str, tuple[str, SourceLoc]] = {}
    b = _Builder(params, nodes, raw.root)
    comps: list[ComponentSpec] = []
    seen: dict[str, SourceLoc] = {}
    for entry, loc, file in raw.comps:
        name = str(entry["name"])
        if name in seen:
            raise NetlistError(f"component name '{name}' is used twice (also at {seen[name]})",
                               loc, name)
        seen[name] = loc
        comps.append(b.component(entry, loc, file))
    if not comps:
        raise NetlistError("the netlist has no components", SourceLoc(str(path), 1))
    _check_node_names(nodes, seen)
    probes = _probes(raw)
    analysis = _analysis(raw, b)
    tables = [t for c in comps for t in c.tables]
    if tables:
        comps = _index_tables(comps)
    return Netlist(str(path), raw.title, params, tuple(comps), probes, analysis, nodes, raw,
                   (*dict.fromkeys(raw.files), *dict.fromkeys(b.table_files)))


def _check_node_names(nodes: Mapping[str, tuple[str, SourceLoc]],
                      comps: Mapping[str, SourceLoc]) -> None:
    """Refuse node names that would read as something else in a probe or a CSV header."""
    for n, (_, loc) in nodes.items():
        if n in comps:
            raise NetlistError(f"'{n}' names both a node and a component; rename one",
                               loc, n)
        head = n.split(".", 1)[0]
        if "." in n and head in comps:
            # 'R1.n.v' would mean both this node's voltage and the voltage at R1's port n
            raise NetlistError(f"node name '{n}' reads as a port of component '{head}' "
                               f"(probes write ports as COMPONENT.PORT); rename the node, e.g. "
                               f"'{n.replace('.', '_')}'", loc)
        if _BAD_NODE_CHARS.search(n) or not n:
            raise NetlistError(f"node name {n!r} holds a space, comma, quote, ';' or '=': it "
                               f"could not be named in a probe or a CSV header; use letters, "
                               f"digits and '_'", loc)


def _probes(raw: _Raw) -> dict[str, Probe]:
    probes = {}
    for name, (text, loc) in raw.probes.items():
        if name == "time":
            raise NetlistError("probe name 'time' is reserved for the time column of the "
                               "output; rename the probe (e.g. 't_probe')", loc)
        try:
            node = ex.parse(str(text), allow_unit=False)
        except ex.ExprError as exc:
            raise NetlistError(f"probe '{name}': {exc}", loc) from None
        try:  # with every name a free symbol: catches 'x/0', 'sqrt(-1)' before codegen
            if not ex.is_polynomial(node):  # a sum of products cannot fail: no sympy
                ex.to_sympy(node, {n: _free_symbol(n) for n in ex.names(node)})
        except NetlistError as exc:
            raise NetlistError(f"probe '{name}': {exc.bare}", loc) from None
        probes[name] = Probe(name, node, str(text), loc)
    return probes


def _free_symbol(name: str):
    import sympy as sp

    return sp.Symbol(name, real=True)


def _index_tables(comps: list[ComponentSpec]) -> list[ComponentSpec]:
    out, k = [], 0
    for c in comps:
        new = []
        for t in c.tables:
            new.append(TableData(t.x, t.y, t.label, k))
            k += 1
        out.append(ComponentSpec(c.name, c.type, c.cls, c.ports, c.values, {
            **c.structure, "_tables": tuple(t.label for t in new)}, c.loc, tuple(new)))
    return out


def _unknown_fix(name: str) -> str:
    """What fixes a value naming ``name``, which is no parameter [text]: the time and circuit
    quantities belong in behavioural expressions, anything else under 'parameters:'."""
    behavioural = "a behavioural part's expr (BV, BI, btorque, bforce)"
    if name == "t":
        return (f"a component's value is a constant: the time t may appear only in "
                f"{behavioural}; a source follows time through a waveform (step, sine, pwl, ...)")
    if "." in name:
        return (f"a component's value is a constant: a circuit quantity ('{name}') may appear "
                f"only in {behavioural}")
    return "define it under 'parameters:'"


def _analysis(raw: _Raw, b: _Builder) -> Analysis:
    kw: dict[str, Any] = {}
    for key, (val, loc) in raw.analysis.items():
        if key in ("stop", "step", "max_step"):
            v = b.value(val, loc, "analysis", key, Param("s", key, nonnegative=True), "s")
            kw[key] = v.si(b.env)
        else:
            kw[key] = val
    if kw.get("stop", 1.0) <= 0:
        raise ParameterError("analysis stop time must be positive", raw.analysis["stop"][1])
    for key in ("step", "rtol"):
        problem = analysis_problem(key, kw.get(key))
        if problem:
            raise ParameterError(f"analysis: {problem}", raw.analysis[key][1])
    points = output_points(kw.get("stop", Analysis.stop), kw.get("step"))
    if points > MAX_OUTPUT_POINTS:
        raise ParameterError(too_many_points(points), raw.analysis.get(
            "step", raw.analysis.get("stop", (None, SourceLoc(raw.path))))[1])
    return Analysis(**kw)


# Output points a run may ask for: 2e7 points hold 160 MB per series; a 1 fs step over a
# second would ask for 1e15 (petabytes) and must be refused before anything is allocated.
MAX_OUTPUT_POINTS = 20_000_000


#: IDA's relative error per step: above this the answer is off by percents (the series RLC
#: example's capacitor at 1 ms: 0.1 % off at 0.01, 1.3 % at 0.03, 17 % at 0.1); SPICE's
#: RELTOL default is 1e-3.
MAX_RTOL = 0.01


def analysis_problem(key: str, value: float | None) -> str:
    """What is wrong with an analysis setting ``step`` [s] or ``rtol``, or '' (None: unset)."""
    if value is None:
        return ""
    if key == "step" and not value > 0:
        return (f"step = {value:g} [s]: the output step must be positive (leave 'step' out "
                f"for stop / 20000)")
    if key == "rtol" and not 0 < value <= MAX_RTOL:
        return (f"rtol = {value:g}: the relative tolerance must lie in (0, {MAX_RTOL:g}]; "
                f"above it the answer is off by percents (SPICE uses 1e-3, "
                f"circuitsim 1e-6 by default)")
    return ""


def output_points(stop: float, step: float | None) -> float:
    """Output points of a run of ``stop`` [s] at ``step`` [s] (default: stop / 20000)."""
    return stop / step if step else 20_000.0


def too_many_points(points: float) -> str:
    return (f"stop / step asks for {points:.3g} output points, more than "
            f"{MAX_OUTPUT_POINTS:.0e}; raise the output step (analysis: step) or shorten "
            f"the run (a waveform's rise time needs no output step of its own: the integrator "
            f"steps through it)")


def _why(exc: Exception) -> str:
    """An evaluation error in words: Python's OverflowError reads '(34, 'Numerical result
    out of range')'."""
    if isinstance(exc, OverflowError):
        return ("its value overflows a float (beyond 1.8e308: a power tower or too large an "
                "exponent); rewrite the expression")
    return str(exc)
