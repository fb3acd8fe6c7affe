#!/usr/bin/python3
"""Check that the pybind11 bindings follow the public headers.

Every header in include/gr-rfseek/ (but api.h) must have a binding file
python/rfseek/bindings/<name>_python.cc that records the md5 of the header it was
written against: /* BINDTOOL_HEADER_FILE_HASH(<md5>) */. After editing a header, update
its binding, then record the new hash with:  scripts/check_bindings.py --update
"""
import hashlib
import os
import re
import sys

HASH_RE = re.compile(r"BINDTOOL_HEADER_FILE_HASH\(([0-9a-f]+)\)")


def main(argv):
    update = "--update" in argv
    args = [a for a in argv[1:] if not a.startswith("--")]
    root = args[0] if args else os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    inc = os.path.join(root, "include", "gr-rfseek")
    bdir = os.path.join(root, "python", "rfseek", "bindings")
    problems = []
    for name in sorted(os.listdir(inc)):
        if not name.endswith(".h") or name == "api.h":
            continue
        digest = hashlib.md5(open(os.path.join(inc, name), "rb").read()).hexdigest()
        bfile = os.path.join(bdir, name[:-2] + "_python.cc")
        if not os.path.exists(bfile):
            problems.append(f"{name}: no binding file {os.path.relpath(bfile, root)}")
            continue
        text = open(bfile).read()
        m = HASH_RE.search(text)
        if not m:
            problems.append(f"{name}: {os.path.basename(bfile)} records no header hash")
            continue
        if m.group(1) != digest:
            if update:
                open(bfile, "w").write(HASH_RE.sub(f"BINDTOOL_HEADER_FILE_HASH({digest})", text, 1))
                print(f"updated {os.path.relpath(bfile, root)}")
            else:
                problems.append(f"{name} changed since {os.path.basename(bfile)} was written "
                                f"(recorded {m.group(1)}, now {digest}): update the binding, "
                                "then run scripts/check_bindings.py --update")
    for p in problems:
        print("STALE BINDING:", p)
    if problems:
        return 1
    print("bindings in sync with", len([n for n in os.listdir(inc) if n.endswith('.h')]) - 1, "headers")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
