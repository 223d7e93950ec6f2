"""Small type checks for hand-validated JSON documents, with messages that name the JSON path.

A path is written the way a user would point at the element: ``frames[3].targets.head`` or
``handles["left foot"][2]``. Every check raises SchemaViolation(path, problem); the caller adds the
file name.
"""
import math
import re
from typing import Any, Dict, Iterable, List, Tuple

_IDENTIFIER = re.compile(r"^[A-Za-z_][A-Za-z0-9_\-]*$")


class SchemaViolation(Exception):
    """One violation: `path` is the JSON path of the element, `problem` says what is wrong."""

    def __init__(self, path: str, problem: str):
        super().__init__(f"{path}: {problem}" if path else problem)
        self.path = path
        self.problem = problem


def child(path: str, key) -> str:
    """The JSON path of member `key` (a str: object member, an int: list element) under `path`."""
    if isinstance(key, int):
        return f"{path}[{key}]"
    if _IDENTIFIER.match(key):
        return f"{path}.{key}" if path else key
    quoted = '"' + key.replace("\\", "\\\\").replace('"', '\\"') + '"'
    return f"{path}[{quoted}]"


def describe(value: Any) -> str:
    """A short description of a JSON value for messages: 'a string', 'a list of 2', 'null', ..."""
    if value is None:
        return "null"
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (int, float)):
        return f"the number {value!r}" if math.isfinite(value) else repr(value).replace("inf", "Infinity").replace("nan", "NaN")
    if isinstance(value, str):
        return f'"{value}"' if len(value) <= 40 else "a long string"
    if isinstance(value, list):
        return f"a list of {len(value)}"
    if isinstance(value, dict):
        return "an object"
    return type(value).__name__


def expect_object(value: Any, path: str) -> Dict[str, Any]:
    """`value` if it is a JSON object (dict), else SchemaViolation."""
    if not isinstance(value, dict):
        raise SchemaViolation(path, f"expected an object, got {describe(value)}")
    return value


def expect_list(value: Any, path: str, non_empty: bool = False) -> List[Any]:
    """`value` if it is a JSON array (list), optionally non-empty, else SchemaViolation."""
    if not isinstance(value, list):
        raise SchemaViolation(path, f"expected a list, got {describe(value)}")
    if non_empty and not value:
        raise SchemaViolation(path, "expected a non-empty list")
    return value


def expect_string(value: Any, path: str, non_empty: bool = True) -> str:
    """`value` if it is a (non-empty) string, else SchemaViolation."""
    if not isinstance(value, str):
        raise SchemaViolation(path, f"expected a string, got {describe(value)}")
    if non_empty and not value.strip():
        raise SchemaViolation(path, "expected a non-empty string")
    return value


def expect_number(value: Any, path: str, minimum: float = -math.inf, exclusive_minimum: bool = False) -> float:
    """`value` as a float if it is a finite JSON number >= (or >) `minimum`, else SchemaViolation."""
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise SchemaViolation(path, f"expected a number, got {describe(value)}")
    try:
        number = float(value)
    except OverflowError:
        raise SchemaViolation(path, "number is too large") from None
    if not math.isfinite(number):
        raise SchemaViolation(path, f"expected a finite number, got {describe(number)}")
    if number < minimum or (exclusive_minimum and number == minimum):
        relation = ">" if exclusive_minimum else ">="
        raise SchemaViolation(path, f"expected a number {relation} {minimum:g}, got {number:g}")
    return number


def expect_int(value: Any, path: str, minimum: int, what: str = "an integer") -> int:
    """`value` if it is a JSON integer >= `minimum` (no fraction, no bool), else SchemaViolation."""
    if isinstance(value, bool) or not isinstance(value, int):
        raise SchemaViolation(path, f"expected {what}, got {describe(value)}")
    if value < minimum:
        raise SchemaViolation(path, f"expected {what} >= {minimum}, got {value}")
    return value


def expect_numbers(value: Any, path: str, count: int) -> Tuple[float, ...]:
    """`value` as a tuple of floats if it is a list of exactly `count` finite numbers."""
    if not isinstance(value, list) or len(value) != count:
        raise SchemaViolation(path, f"expected {count} numbers, got {describe(value)}")
    return tuple(expect_number(item, child(path, i)) for i, item in enumerate(value))


def check_members(obj: Dict[str, Any], path: str, required: Iterable[str], optional: Iterable[str]) -> None:
    """SchemaViolation when a required member is missing or an unknown one is present.

    Members whose name starts with '_' are the user's own annotations and are always allowed.
    """
    required = list(required)
    allowed = set(required) | set(optional)
    for name in required:
        if name not in obj:
            raise SchemaViolation(path, f'missing member "{name}"')
    for name in obj:
        if name not in allowed and not name.startswith("_"):
            listed = ", ".join(sorted(allowed))
            raise SchemaViolation(child(path, name), f"unknown member (expected one of: {listed})")
