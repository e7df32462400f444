"""The jinja2 environment shared by the template-based emitters (XML, Stage world)."""

from __future__ import annotations

from functools import cache

from jinja2 import Environment, PackageLoader, StrictUndefined, select_autoescape


def format_number(value: float, decimals: int = 3) -> str:
    """A number with at most `decimals` decimals, no trailing zeros and never `-0`."""
    text = f"{round(float(value), decimals):.{decimals}f}"
    if "." in text:
        text = text.rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


@cache
def environment() -> Environment:
    """The project's jinja2 environment (STYLE.md): strict, xml-escaped, whitespace-tidy."""
    env = Environment(
        loader=PackageLoader("layoutdsl.emit"),
        undefined=StrictUndefined,
        autoescape=select_autoescape(["xml", "xml.j2"]),
        trim_blocks=True,
        lstrip_blocks=True,
        keep_trailing_newline=True,
    )
    env.filters["m"] = format_number  # metres in world files
    env.filters["u"] = lambda value: format_number(value, 1)  # file units (cm) in XML
    return env
