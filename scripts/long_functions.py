#!/usr/bin/env python3
"""Lists the functions over a line limit or with too many parameters (issue 36's aim: no
function over 150 lines and none with more than 7 parameters in `src/physics`).

    python3 scripts/long_functions.py [DIR] [--lines 150] [--params 7]

A function's lines run from its `fn` line to its closing brace (tests included); its
parameters are the comma-separated items of its parameter list, `self` included (as clippy's
`too_many_arguments` counts them). Strings, chars and comments are skipped when matching
braces. Prints `lines params path:line name`, longest first; exit code 0.
"""

import os
import re
import sys

FN = re.compile(r"^\s*(?:pub(?:\([^)]*\))?\s+)?(?:const\s+)?(?:async\s+)?(?:unsafe\s+)?(?:extern\s+\"[^\"]*\"\s+)?fn\s+([A-Za-z_][A-Za-z0-9_]*)")


def strip(text):
    """The text with strings, chars and comments blanked (newlines kept)."""
    out, i, n = [], 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            out.append(" " * (j - i))
            i = j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append("".join(ch if ch == "\n" else " " for ch in text[i:j]))
            i = j
        elif c == "r" and re.match(r'r#*"', text[i:i + 10]) and (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == "_")):
            m = re.match(r'r(#*)"', text[i:])
            end = '"' + m.group(1)
            j = text.find(end, i + len(m.group(0)))
            j = n if j < 0 else j + len(end)
            out.append("".join(ch if ch == "\n" else " " for ch in text[i:j]))
            i = j
        elif c == '"':
            j = i + 1
            while j < n and text[j] != '"':
                j += 2 if text[j] == "\\" else 1
            j += 1
            out.append("".join(ch if ch == "\n" else " " for ch in text[i:j]))
            i = j
        elif c == "'":
            m = re.match(r"'(\\.|\\u\{[0-9a-fA-F]+\}|[^\\'])'", text[i:])
            if m:
                out.append(" " * len(m.group(0)))
                i += len(m.group(0))
            else:  # a lifetime
                out.append(c)
                i += 1
        else:
            out.append(c)
            i += 1
    return "".join(out)


def functions(path):
    text = strip(open(path, encoding="utf-8").read())
    lines = text.split("\n")
    offsets = [0]
    for line in lines:
        offsets.append(offsets[-1] + len(line) + 1)
    for number, line in enumerate(lines):
        m = FN.match(line)
        if not m:
            continue
        start = offsets[number] + m.end()
        # The parameter list: the first '(' after the name (past generics), to its match.
        depth, i = 0, start
        while i < len(text) and text[i] != "(":
            i += 1
        open_paren, depth = i, 0
        while i < len(text):
            if text[i] in "([{<" and text[i] != "<":
                depth += 1
            elif text[i] in ")]}":
                depth -= 1
                if depth == 0:
                    break
            i += 1
        params = text[open_paren + 1:i]
        count, d = 0, 0
        items = []
        current = ""
        for ch in params:
            if ch in "([{<":
                d += 1
            elif ch in ")]}>":
                d -= 1
            if ch == "," and d == 0:
                items.append(current)
                current = ""
            else:
                current += ch
        items.append(current)
        count = sum(1 for it in items if it.strip())
        # The body: the first '{' or ';' after the parameter list at depth 0.
        j = i + 1
        while j < len(text) and text[j] not in "{;":
            j += 1
        if j >= len(text) or text[j] == ";":
            continue
        depth = 0
        k = j
        while k < len(text):
            if text[k] == "{":
                depth += 1
            elif text[k] == "}":
                depth -= 1
                if depth == 0:
                    break
            k += 1
        end_line = text.count("\n", 0, k)
        yield m.group(1), number + 1, end_line - number + 1, count


def main():
    args = sys.argv[1:]
    root = "src/physics"
    limit_lines, limit_params = 150, 7
    i = 0
    while i < len(args):
        if args[i] == "--lines":
            limit_lines = int(args[i + 1]); i += 2
        elif args[i] == "--params":
            limit_params = int(args[i + 1]); i += 2
        else:
            root = args[i]; i += 1
    found = []
    for folder, _, files in os.walk(root):
        for f in files:
            if f.endswith(".rs"):
                path = os.path.join(folder, f)
                for name, line, length, params in functions(path):
                    if length > limit_lines or params > limit_params:
                        found.append((length, params, f"{path}:{line}", name))
    for length, params, where, name in sorted(found, key=lambda x: (-x[0], -x[1], x[2])):
        print(f"{length:5} {params:3} {where} {name}")


if __name__ == "__main__":
    main()
