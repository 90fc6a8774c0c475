"""Writes the type stubs of movseg: movseg/__init__.pyi.in with the attributes of Params and
Diagnostics generated from the field tables, which the built module lists.

Usage: PYTHONPATH=<build>/python python3 stubgen.py TEMPLATE OUTPUT
(It lives in tools/, not beside python/movseg/: a script's folder comes first in sys.path, and
the sources there are not the built package.)
"""
import sys

from movseg import _movseg

INDENT = "    "


def annotation(field):
    if field["choices"]:
        return "Literal[" + ", ".join(f'"{name}"' for name in field["choices"]) + "]"
    return "_Matrix" if field["type"] == "matrix" else field["type"]


def attributes(fields, read_only):
    lines = []
    for field in fields:
        lines.append(f'{INDENT}# {field["doc"]}')
        if read_only:
            lines += [f"{INDENT}@property", f'{INDENT}def {field["name"]}(self) -> {annotation(field)}: ...']
        else:
            lines.append(f'{INDENT}{field["name"]}: {annotation(field)}')
    return "\n".join(lines)


def keywords(fields):
    return "\n".join(f'{INDENT * 2}{field["name"]}: {annotation(field)} = ...,' for field in fields)


def main(template_path, output_path):
    params, diagnostics = _movseg._param_fields(), _movseg._diagnostic_fields()
    text = open(template_path, encoding="utf-8").read()
    for marker, lines in [("@PARAMS_KEYWORDS@", keywords(params)),
                          ("@PARAMS_ATTRIBUTES@", attributes(params, read_only=False)),
                          ("@DIAGNOSTICS_ATTRIBUTES@", attributes(diagnostics, read_only=True))]:
        text = text.replace(marker, lines)
    with open(output_path, "w", encoding="utf-8") as out:
        out.write(text)


if __name__ == "__main__":
    main(*sys.argv[1:])
