#!/usr/bin/env python3
"""No function in engine/, cli/ or python/src/ is longer than about 80 lines (docs/contributing.md, "Style").

Counts each function body by brace matching (comments and string literals blanked out) from the
line that opens it; lambdas count within their function. Prints the longest and fails on any
over the limit. Usage: tests/checks/function_length.py [LIMIT]
"""
import pathlib
import re
import sys

ROOT = pathlib.Path(__file__).resolve().parents[2]
LIMIT = int(sys.argv[1]) if len(sys.argv) > 1 else 80
OPENS_FUNCTION = re.compile(r"\)\s*(const\s*)?(noexcept\s*)?(->\s*[\w:<>,\s*&]+)?(override\s*)?\{\s*$")
NOT_A_FUNCTION = re.compile(r"^\s*(if|for|while|switch|else|do|catch)\b|\]\s*\(|=\s*\[")


def blank(line):
    line = re.sub(r"//.*", "", line)
    line = re.sub(r'"(\\.|[^"\\])*"', '""', line)
    return re.sub(r"'(\\.|[^'\\])*'", "''", line)


def lengths(path):
    stack = []  # (is_function, first line)
    for number, raw in enumerate(path.read_text(errors="replace").split("\n"), 1):
        code = blank(raw)
        for ch in code:
            if ch == "{":
                inside = any(f for f, _ in stack)
                stack.append((not inside and bool(OPENS_FUNCTION.search(code)) and not NOT_A_FUNCTION.search(code), number))
            elif ch == "}" and stack:
                is_function, first = stack.pop()
                if is_function:
                    yield number - first + 1, first


def main():
    found = []
    for path in sorted(list((ROOT / "engine").rglob("*.cpp")) + list((ROOT / "engine").rglob("*.h")) +
                       list((ROOT / "cli").glob("*.cpp")) +
                       list((ROOT / "python" / "src").glob("*.cpp"))):
        for n, first in lengths(path):
            found.append((n, f"{path.relative_to(ROOT)}:{first}"))
    found.sort(reverse=True)
    for n, where in found[:5]:
        print(f"{n:4d} lines  {where}")
    over = [f for f in found if f[0] > LIMIT]
    print(f"{len(found)} functions, {len(over)} over {LIMIT} lines")
    return 1 if over else 0


if __name__ == "__main__":
    sys.exit(main())
