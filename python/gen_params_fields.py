"""Writes the X-macro list of movseg::Params fields, with their header comments as docstrings.

Usage: gen_params_fields.py include/movseg/params.h OUTPUT.h

The bindings expand MOVSEG_PARAM(cpp_name, python_name, doc) once per field, so a field added to
params.h becomes a Python attribute with its comment as docstring without touching the bindings.
A comment documents the fields that follow it up to the next blank line (e.g. lk_window and
lk_levels share one); "// ----" lines are section titles, not documentation.
"""
import keyword
import re
import sys

FIELD = re.compile(r"^\s*[\w:]+\s+(\w+)\s*(=[^;]*)?;")


def fields(header_text):
    body = header_text.split("struct Params {", 1)[1].split("\n};", 1)[0]
    comment, group_doc = [], ""
    for line in body.splitlines():
        stripped = line.strip()
        if not stripped:
            comment, group_doc = [], ""
        elif stripped.startswith("// ----"):
            comment = []
        elif stripped.startswith("//"):
            text = stripped[2:]
            comment.append((text[1:] if text.startswith(" ") else text).rstrip())
        elif FIELD.match(line):
            if comment:
                group_doc, comment = "\n".join(comment), []
            yield FIELD.match(line).group(1), group_doc


def python_name(name):
    return name + "_" if keyword.iskeyword(name) else name


def main(header, output):
    with open(header, encoding="utf-8") as f:
        found = list(fields(f.read()))
    if not found:
        sys.exit(f"gen_params_fields: no Params fields found in {header}")
    lines = ["// Generated from include/movseg/params.h by python/gen_params_fields.py.\n"]
    for name, doc in found:
        lines.append(f'MOVSEG_PARAM({name}, "{python_name(name)}", R"doc({doc})doc")\n')
    with open(output, "w", encoding="utf-8") as f:
        f.writelines(lines)


if __name__ == "__main__":
    main(*sys.argv[1:])
