#!/usr/bin/python3
"""The codebase stays navigable: no source file over 600 lines and no function over 120
lines, tests excepted (lib/qa, lib/fuzz, python/rfseek/qa_*.py).

C++ functions are found by their braces (comments and string literals removed): a brace
opened outside any function, after a parameter list, starts one; it ends at its match.
Python functions come from the ast. Run from anywhere:
    scripts/check_layout.py [SOURCE_DIR]
"""
import ast
import os
import re
import sys

MAX_FILE_LINES = 600
MAX_FUNCTION_LINES = 120
CXX = (".cc", ".h")
SOURCE_DIRS = ("include", "lib", "apps", "python", "examples", "scripts")
PY_PROGRAMS = ("rfseek-sim", "rfseek-live", "rfseek-soak", "rfseek-plot-montecarlo")


def is_test(rel):
    parts = rel.split(os.sep)
    name = parts[-1]
    return ("qa" in parts or "fuzz" in parts or name.startswith("qa_")
            or name.startswith("fuzz_"))


def strip_cxx(text):
    """Comments and string/char literals blanked, newlines kept (line numbers hold)."""
    out, i, n = [], 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            i = n if j < 0 else j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append("\n" * text.count("\n", i, j))
            i = j
        elif text.startswith('R"', i) and (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == "_")):
            m = re.match(r'R"([^(\s]*)\(', text[i:])
            end = text.find(")" + (m.group(1) if m else "") + '"', i)
            end = n if end < 0 else end + len(m.group(1) if m else "") + 2
            out.append('""' + "\n" * text.count("\n", i, end))
            i = end
        elif c in "\"'":
            j = i + 1
            while j < n and text[j] != c and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            out.append(c + c)
            i = j + 1
        else:
            out.append(c)
            i += 1
    return "".join(out)


def cxx_functions(text):
    """(name, first line, last line) of each function body in C++ text."""
    code = strip_cxx(text)
    stack = []  # kinds of the open braces: ns, type, func, other
    head_start = 0  # where the text before the next brace begins
    line = 1
    head_line = 1
    found = []
    for i, c in enumerate(code):
        if c == "\n":
            line += 1
            continue
        if c in ";":
            if "func" not in [k for k, _, _ in stack]:
                head_start, head_line = i + 1, None
            continue
        if c == "{":
            head = code[head_start:i]
            in_func = any(k == "func" for k, _, _ in stack)
            if in_func:
                kind = "other"
            elif re.search(r"\bnamespace\b|\bextern\s*$", head):
                kind = "ns"
            elif re.search(r"\b(class|struct|union|enum)\b[^()]*$", head):
                kind = "type"
            elif ")" in head and not re.search(r"=\s*$", head.strip()):
                kind = "func"
            else:
                kind = "other"
            first = line - head.rstrip().count("\n") if head.strip() else line
            # the signature's first line: the first non-blank line of the head
            lines_before = head.split("\n")
            skip = 0
            for part in lines_before:
                if part.strip():
                    break
                skip += 1
            first = line - (len(lines_before) - 1) + skip
            name = re.findall(r"([~\w:]+)\s*\(", head)
            stack.append((kind, first, name[0] if name else "?"))
            head_start = i + 1
        elif c == "}":
            if stack:
                kind, first, name = stack.pop()
                if kind == "func":
                    found.append((name, first, line))
            if not any(k == "func" for k, _, _ in stack):
                head_start = i + 1
    return found


def py_functions(text, path):
    tree = ast.parse(text, path)
    for node in ast.walk(tree):
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
            yield node.name, node.lineno, node.end_lineno


def main(argv):
    root = argv[1] if len(argv) > 1 else os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    problems, files = [], 0
    for top in SOURCE_DIRS:
        for dirpath, dirnames, filenames in os.walk(os.path.join(root, top)):
            dirnames[:] = [d for d in dirnames if d not in ("__pycache__", "data")]
            for name in sorted(filenames):
                path = os.path.join(dirpath, name)
                rel = os.path.relpath(path, root)
                is_py = name.endswith(".py") or name in PY_PROGRAMS
                if not (name.endswith(CXX) or is_py) or is_test(rel):
                    continue
                files += 1
                text = open(path, encoding="utf-8").read()
                n = text.count("\n")
                if n > MAX_FILE_LINES:
                    problems.append(f"{rel}: {n} lines (at most {MAX_FILE_LINES})")
                funcs = py_functions(text, path) if is_py else cxx_functions(text)
                for fname, a, b in funcs:
                    if b - a + 1 > MAX_FUNCTION_LINES:
                        problems.append(f"{rel}:{a}: {fname} is {b - a + 1} lines "
                                        f"(at most {MAX_FUNCTION_LINES})")
    for p in problems:
        print("LAYOUT:", p)
    if problems:
        return 1
    print(f"layout: {files} source files, none over {MAX_FILE_LINES} lines, no function "
          f"over {MAX_FUNCTION_LINES} lines")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
