"""Validation of every file a user writes, with one schema library (jsonschema).

Each configuration kind (sensor, pipeline, detection thresholds, report, baseline) has a
JSON Schema, built next to the code that reads it. :func:`check` validates a parsed TOML
or JSON document against it and raises :class:`SchemaError` with ONE line naming the file,
the dotted field, the value and what is allowed; an unknown key or section is refused
with the nearest known name. Schemas may carry ``"x-unit"`` (shown in messages).
"""

from __future__ import annotations

import difflib
import math
import tomllib
from collections.abc import Mapping
from pathlib import Path
from typing import Any

from irnuc.common.errors import UserError


class SchemaError(UserError):
    """A configuration or input document does not match its schema."""


def _dotted(prefix: str, path: Any) -> str:
    parts = [prefix] if prefix else []
    for p in path:
        if isinstance(p, int):
            parts[-1:] = [f"{parts[-1]}[{p}]"] if parts else [f"[{p}]"]
        else:
            parts.append(str(p))
    return ".".join(parts) or "(top level)"


def _num(v: float) -> str:
    return f"{v:g}" if isinstance(v, float) else _show(v, str)


def _show(v: Any, fmt: Any = repr, width: int = 60) -> str:
    """A value as text for a one-line message, cut short (a thousand-digit number or a
    large table would swamp the line)."""
    if isinstance(v, int) and not isinstance(v, bool) and v.bit_length() > 200:
        return f"{'-' if v < 0 else ''}(an integer of {int(v.bit_length() * 0.30103) + 1} digits)"
    s = fmt(v)
    return s if len(s) <= width else s[: width - 4] + " ..."


def _range(schema: Mapping[str, Any]) -> str:
    lo = schema.get("minimum", schema.get("exclusiveMinimum"))
    hi = schema.get("maximum", schema.get("exclusiveMaximum"))
    left = "(" if "exclusiveMinimum" in schema else "["
    right = ")" if "exclusiveMaximum" in schema else "]"
    unit = f" {schema['x-unit']}" if schema.get("x-unit") else ""
    return (f"{left}{'-inf' if lo is None else _num(lo)}, "
            f"{'inf' if hi is None else _num(hi)}{right}{unit}")


_TYPE_WORDS = {"integer": "an integer", "number": "a number", "string": "a string",
               "boolean": "true or false", "object": "a table", "array": "a list",
               "null": "absent"}


def _type_text(t: Any) -> str:
    ts = t if isinstance(t, list) else [t]
    return " or ".join(_TYPE_WORDS.get(x, x) for x in ts)


def _message(err: Any, prefix: str) -> str:
    """One line for one jsonschema error."""
    where = _dotted(prefix, err.absolute_path)
    v = err.instance
    kind = err.validator
    sch = err.schema if isinstance(err.schema, Mapping) else {}
    if kind == "additionalProperties" and isinstance(v, Mapping):
        known = sorted((sch.get("properties") or {}).keys())
        unknown = sorted(k for k in v if k not in (sch.get("properties") or {}))
        key = unknown[0] if unknown else "?"
        field = _dotted(prefix, [*err.absolute_path, key])
        return f"{field} is not a known field{nearest(key, known)} (known here: {', '.join(known)})"
    if "propertyNames" in err.relative_schema_path and kind == "enum":
        known = sorted(map(str, err.validator_value))
        return (f"{where}.{v} is not a known field{nearest(str(v), known)} "
                f"(known here: {', '.join(known)})")
    if kind == "required":
        missing = [k for k in err.validator_value if not isinstance(v, Mapping) or k not in v]
        return f"{_dotted(prefix, [*err.absolute_path, missing[0]])} is required but missing"
    if kind == "type":
        return f"{where} = {_show(v)} must be {_type_text(err.validator_value)}"
    if kind in ("minimum", "maximum", "exclusiveMinimum", "exclusiveMaximum"):
        unit = f" {sch['x-unit']}" if sch.get("x-unit") else ""
        return f"{where} = {_num(v)}{unit} is outside the allowed range {_range(sch)}"
    if kind == "enum":
        return f"{where} = {_show(v)} is not one of {', '.join(map(repr, err.validator_value))}"
    if kind == "const":
        return f"{where} = {_show(v)} must be {err.validator_value!r}"
    if kind in ("minItems", "maxItems"):
        n = err.validator_value
        word = "at least" if kind == "minItems" else "at most"
        return f"{where} has {len(v)} item(s); {word} {n} allowed"
    if kind == "minLength":
        return f"{where} must not be empty"
    if kind == "minProperties":
        return f"{where} is empty; at least {err.validator_value} entry needed"
    if kind == "pattern" and sch.get("x-pattern-text"):
        return f"{where} = {_show(v)} must be {sch['x-pattern-text']}"
    if kind == "not" and isinstance(v, float) and not math.isfinite(v):
        return f"{where} = {_show(v)} must be a finite number"
    return f"{where}: {err.message}"


def _finite(instance: Any, prefix: str) -> str | None:
    """Path of the first NaN or infinity in a document (JSON allows them via Python);
    iterative, so a deeply nested document is no recursion error."""
    stack: list[tuple[tuple, Any]] = [((), instance)]
    while stack:
        path, v = stack.pop()
        if isinstance(v, float) and not math.isfinite(v):
            return f"{_dotted(prefix, path)} = {v!r} must be a finite number"
        if isinstance(v, Mapping):
            stack.extend(((*path, k), x) for k, x in reversed(list(v.items())))
        elif isinstance(v, list):
            stack.extend(((*path, i), x) for i, x in reversed(list(enumerate(v))))
    return None


_VALIDATORS: dict[int, tuple[Mapping[str, Any], Any]] = {}


def _validator(schema: Mapping[str, Any]) -> Any:
    """A compiled validator per schema object (schemas are module-level constants)."""
    hit = _VALIDATORS.get(id(schema))
    if hit is None or hit[0] is not schema:
        from jsonschema import Draft202012Validator

        hit = (schema, Draft202012Validator(schema))
        _VALIDATORS[id(schema)] = hit
    return hit[1]


def check(instance: Any, schema: Mapping[str, Any], *, source: str, prefix: str = "") -> None:
    """Validate ``instance`` against ``schema``; raise :class:`SchemaError` (one line).

    Parameters
    ----------
    instance : parsed document (dict from TOML or JSON)
    schema : JSON Schema (draft 2020-12)
    source : str
        What to name first in the message: the file, or the flag that gave it.
    prefix : str
        Dotted path of ``instance`` inside a larger document, if any.
    """
    bad = _finite(instance, prefix)
    if bad:
        raise SchemaError(f"{source}: {bad}")
    errors = list(_validator(schema).iter_errors(instance))
    if not errors:
        return
    # The deepest error first: it is the most specific (a bad value inside a table
    # rather than "the table is not valid"); at one depth an unknown key first, as it
    # is most often a misspelling that also explains a "missing" field.
    err = max(errors, key=lambda e: (len(e.absolute_path), e.validator == "additionalProperties"))
    raise SchemaError(f"{source}: {_message(err, prefix)}")


def nearest(word: str, known: list[str] | tuple[str, ...]) -> str:
    """``"; did you mean 'x'?"`` for the closest known name, or an empty string."""
    near = difflib.get_close_matches(word, list(known), n=1, cutoff=0.6)
    return f"; did you mean {near[0]!r}?" if near else ""


def read_toml(path: str | Path, flag: str = "") -> dict[str, Any]:
    """Parse a TOML file (at most :data:`irnuc.common.io.MAX_TEXT_BYTES`); one-line errors
    name the flag, the file and the problem."""
    from irnuc.common.io import read_bytes_capped

    p = Path(path)
    name = f"{flag} {p}" if flag else str(p)
    if not p.exists():
        raise UserError(f"{name}: no such file")
    if p.is_dir():
        raise UserError(f"{name}: is a folder, not a TOML file")
    data = read_bytes_capped(p, flag)
    try:
        return tomllib.loads(data.decode("utf-8"))
    except tomllib.TOMLDecodeError as exc:
        raise UserError(f"{name}: not valid TOML ({exc})") from None
    except RecursionError:
        raise UserError(f"{name}: not valid TOML (nested too deeply)") from None
    except (UnicodeDecodeError, ValueError) as exc:  # encoding; an integer too long
        raise UserError(f"{name}: cannot be read ({exc})") from None


def number(lo: float | None = None, hi: float | None = None, *, lo_open: bool = False,
           hi_open: bool = False, integer: bool = False, unit: str = "",
           nullable: bool = False) -> dict[str, Any]:
    """Schema of a number in an interval (``integer`` excludes floats; booleans never pass)."""
    s: dict[str, Any] = {"type": "integer" if integer else "number"}
    if lo is not None:
        s["exclusiveMinimum" if lo_open else "minimum"] = lo
    if hi is not None:
        s["exclusiveMaximum" if hi_open else "maximum"] = hi
    if unit:
        s["x-unit"] = unit
    if nullable:
        s["type"] = [s["type"], "null"]
    return s


def table(properties: Mapping[str, Any], required: list[str] | tuple[str, ...] = (),
          **extra: Any) -> dict[str, Any]:
    """Schema of a TOML table with known fields only."""
    return {"type": "object", "properties": dict(properties), "required": list(required),
            "additionalProperties": False, **extra}
