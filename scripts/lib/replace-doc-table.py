#!/usr/bin/env python3
"""Replaces the text between "<!-- tables: NAME -->" and "<!-- end of tables: NAME -->" in DOC by the
table read from standard input, leaving the rest of DOC as it is: how the measuring scripts write
their tables into docs/ (a table in the docs always comes from the script that measured it).

    scripts/lib/replace-doc-table.py DOC NAME < table.md
"""
import os
import sys


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__.strip().splitlines()[-1].strip())
    path, name = sys.argv[1], sys.argv[2]
    table = sys.stdin.read().rstrip("\n")
    begin, end = f"<!-- tables: {name} -->", f"<!-- end of tables: {name} -->"
    text = open(path, encoding="utf-8").read()
    if text.count(begin) != 1 or text.count(end) != 1:
        sys.exit(f"replace-doc-table: {path} must hold {begin} and {end} once each")
    head, rest = text.split(begin)
    _, tail = rest.split(end)
    with open(path + ".tmp", "w", encoding="utf-8") as out:
        out.write(f"{head}{begin}\n{table}\n{end}{tail}")
    os.replace(path + ".tmp", path)


if __name__ == "__main__":
    main()
