#!/usr/bin/python3
"""Prints a `[builds.NAME]` table of an experiment file for a driver build folder.

Usage: scripts/build_table.py NAME DIR [COMMENT]

The folder and the comment come from the user (a Mesa source path, a ref): the folder is written
as a TOML basic string (JSON's escapes are TOML's), the comment on lines of its own with every
line break made a space, so nothing in them can end the string or start a TOML line.
"""
import json
import sys

if len(sys.argv) not in (3, 4) or not sys.argv[1].replace("-", "").replace("_", "").isalnum():
    sys.exit("usage: scripts/build_table.py NAME DIR [COMMENT] (NAME: letters, digits, - and _)")
name, folder = sys.argv[1], sys.argv[2]
comment = " ".join(sys.argv[3].split()) if len(sys.argv) == 4 else ""
print()
if comment:
    print("# " + comment)
print(f"[builds.{name}]")
print("dir = " + json.dumps(folder, ensure_ascii=False))
